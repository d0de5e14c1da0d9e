// The crane in a plain fixed-step game loop (--game-loop): what an engine does with flexstress.
//
// The renderer runs at its own rate with uneven frame times; the simulation steps at its own
// fixed h. A time accumulator collects each frame's time and takes as many fixed steps as fit
// (Fiedler, "Fix your timestep!", 2004); the remainder alpha = accumulator / h places the frame
// between the last two states, which are interpolated for display (positions and modal
// coordinates linearly, Euler parameters normalized-linearly), so motion is smooth at any frame
// rate and the physics never depends on it. Every frame shows the boom's deformed shape at render
// vertices along its top flange (stress/deformed_shape.hpp, from the mode shapes) and a live
// read-out: the hot spot at detail D and the damage accumulated so far.
//
// The frame clock is simulated by default (60 Hz with jitter, deterministic) so the run is
// reproducible; --realtime paces the frames by the wall clock like a real engine would.
#pragma once

#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <thread>
#include <vector>

#include <flexstress/fatigue/damage.hpp>
#include <flexstress/fatigue/sn_curve.hpp>
#include <flexstress/fatigue/streaming_damage.hpp>
#include <flexstress/stress/deformed_shape.hpp>

#include "crane_run.hpp"

namespace crane {

/// The state shown on screen: a fraction alpha in [0, 1] of the way from `a` to `b`.
template <int N>
BodyCoordinates<double, N> interpolate(const BodyCoordinates<double, N>& a,
                                       const BodyCoordinates<double, N>& b, double alpha) {
  BodyCoordinates<double, N> c;
  c.position = a.position + alpha * (b.position - a.position);
  c.p = a.p + alpha * (b.p - a.p);
  // Normalized linear interpolation of Euler parameters on the same hemisphere.
  const double sign = a.theta.dot(b.theta) < 0 ? -1.0 : 1.0;
  c.theta = (a.theta + alpha * (sign * b.theta - a.theta)).normalized();
  return c;
}

template <int N, int StorageLimit>
int run_game_loop(const RunOptions& o, double render_hz, bool realtime) {
  using Scene = CraneScene<N, StorageLimit, double, CraneEffects>;
  using Clock = std::chrono::steady_clock;
  auto made = build_crane<N, StorageLimit>(o);
  if (!made) return 1;
  auto& cr = *made;
  typename Scene::State s = cr.initial;
  typename ImplicitIntegrator<Scene>::Settings settings;
  settings.step = o.step;
  settings.acceleration_tolerance = o.tolerance;
  settings.refresh_workspace = false;  // nothing here reads the workspace after a step
  ImplicitIntegrator<Scene> integ(cr.scene, settings);
  if (Status st = integ.initialize(s); !st) {
    std::fprintf(stderr, "error: %s\n", st.error().what().c_str());
    return 1;
  }
  auto meter = make_damage_meter();
  if (!meter) return 1;

  // Render vertices: 91 along the top flange (y = +75 mm), 5 cm apart, carried by the boom's
  // beam line with Hermite interpolation between its nodes.
  std::vector<Vector3d> vertices;
  for (int i = 0; i <= 90; ++i) vertices.emplace_back(0.05 * i, 0.075, 0.0);
  auto shape = stress::DeformedShape<N>::along_beam(cr.boom.data, cr.boom.line.nodes, vertices);
  if (!shape) {
    std::fprintf(stderr, "error: %s\n", shape.error().what().c_str());
    return 1;
  }
  Eigen::Matrix3Xd drawn(3, shape->size()), rigid(3, shape->size());

  std::ofstream csv(o.output + "/game_loop.csv");
  csv << "frame,frame_dt_s,sim_time_s,steps_this_frame,alpha,tip_x_m,tip_y_m,tip_deflection_mm,"
         "hot_spot_MPa,damage_so_far\n";
  csv.precision(9);
  const double h = o.step, t_end = o.t.back();
  const double frame_dt = 1.0 / render_hz, max_frame_dt = 0.25;  // no spiral of death
  VectorXd y(cr.fused->num_outputs());
  auto previous = s.template coordinates<0>();
  double accumulator = 0.0, hot = 0.0, largest_deflection = 0.0;
  long frames = 0, steps = 0, most_steps = 0;
  bool failed = false;
  const bool hud = !o.quiet && ::isatty(STDERR_FILENO);
  auto next_frame = Clock::now();
  auto last = Clock::now();
  while (s.t < t_end - 0.5 * h && !failed) {
    // The frame's time: measured (--realtime) or 60 Hz with a deterministic jitter of +-30 %.
    double dt = frame_dt * (1.0 + 0.3 * std::sin(1.7 * static_cast<double>(frames)));
    if (realtime) {
      next_frame +=
          std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(frame_dt));
      std::this_thread::sleep_until(next_frame);
      const auto now = Clock::now();
      dt = std::chrono::duration<double>(now - last).count();
      last = now;
    }
    accumulator += std::min(dt, max_frame_dt);
    // Simulate: as many fixed steps as the accumulated time holds.
    long taken = 0;
    while (accumulator >= h && s.t < t_end - 0.5 * h) {
      previous = s.template coordinates<0>();
      if (const StepStatus st = integ.step(s); st != StepStatus::ok) {
        std::fprintf(stderr, "error: step at t = %g s: %s\n", s.t, to_string(st));
        failed = true;
        break;
      }
      cr.fused->evaluate(s.template coordinates<0>().p, y);
      hot = y(cr.hot_spot_row) / 1e6;
      (void)meter->push(hot);
      accumulator -= h;
      ++taken;
    }
    steps += taken;
    most_steps = std::max(most_steps, taken);
    // Render: the boom between its last two states, its vertices from the mode shapes.
    const double alpha = std::clamp(accumulator / h, 0.0, 1.0);
    const auto shown = interpolate<N>(previous, s.template coordinates<0>(), alpha);
    shape->evaluate(shown.position, shown.theta, shown.p, drawn);
    shape->evaluate(shown.position, shown.theta, Vec<double, N>::Zero(), rigid);
    const Index tip = shape->size() - 1;
    const double deflection = (drawn.col(tip) - rigid.col(tip)).norm() * 1e3;
    largest_deflection = std::max(largest_deflection, deflection);
    const double damage = meter->closed_damage();
    csv << frames << ',' << dt << ',' << s.t << ',' << taken << ',' << alpha << ',' << drawn(0, tip)
        << ',' << drawn(1, tip) << ',' << deflection << ',' << hot << ',' << damage << '\n';
    if (hud && frames % 10 == 0)
      std::fprintf(stderr, "\r  t %5.2f s | hot spot %6.2f MPa | damage so far %.3e | tip %.2f mm",
                   s.t, hot, damage, deflection);
    ++frames;
  }
  if (hud) std::fprintf(stderr, "\r%80s\r", "");
  const double damage = meter->damage(fatigue::CycleClosure::repeating);
  std::printf(
      "crane: game loop, %ld frames at %.0f Hz (%s), %ld fixed steps of %g s, %ld render "
      "vertices on the boom\n",
      frames, render_hz, realtime ? "wall clock" : "simulated clock with jitter", steps, h,
      static_cast<long>(shape->size()));
  std::printf("  largest tip deflection on screen %.3f mm; damage per work cycle %.6g\n",
              largest_deflection, damage);
  std::printf("frames: %ld\n", frames);
  std::printf("steps: %ld\n", steps);
  std::printf("max_steps_per_frame: %ld\n", most_steps);
  std::printf("tip_deflection_max_mm: %.4f\n", largest_deflection);
  std::printf("damage_per_cycle: %.6g\n", damage);
  return failed ? 1 : 0;
}

extern template int run_game_loop<10, fixed_storage_limit>(const RunOptions&, double, bool);

}  // namespace crane
