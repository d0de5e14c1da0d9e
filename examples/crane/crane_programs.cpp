// The crane program's other runs (crane_run.hpp): a batch of operators, each driving their own
// version of the work cycle in parallel, and the cycle in a fixed-step game loop with
// interpolated display states, the boom's deformed shape at render vertices and a live damage
// read-out.
#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <thread>
#include <vector>

#include <flexstress/core/batch.hpp>
#include <flexstress/stress/deformed_shape.hpp>

#include "crane_operators.hpp"
#include "crane_run.hpp"

namespace crane {

namespace {

/// What one operator's cycle gives.
struct OperatorOutcome {
  double lift = 0, duration = 0, hot_max = -1e300, hot_min = 1e300, damage = 0;
  long steps = 0;
  BudgetCount budget;  // steps kept at --newton-budget
  StepStatus status = StepStatus::ok;
  std::string error;
};

}  // namespace

int run_operators(const RunOptions& o, int first, int count, unsigned threads) {
  using Clock = std::chrono::steady_clock;
  auto made = build_crane(o);
  if (!made) return 1;
  const Crane& crane = *made;  // its model is shared by every job, read only
  const Index hot_row = crane.detail.hot_spot;
  std::vector<OperatorOutcome> out(static_cast<std::size_t>(count));
  auto job = [&](std::size_t j) {
    const int k = first + static_cast<int>(j);
    OperatorOutcome& r = out[j];
    std::vector<double> tk, dk;
    operator_cycle(k, o.spec, o.t, o.ds, tk, dk);
    r.lift = *std::max_element(dk.begin(), dk.end());
    r.duration = tk.back() - tk.front();
    std::vector<double> stroke(dk);
    for (double& v : stroke) v += crane.initial_length;
    auto law = TableLaw<double>::create(tk, stroke);
    Data<double> d = start_data(crane, o);
    if (!law) {
      r.status = StepStatus::invalid_input;
      r.error = law.error().what();
      return;
    }
    (void)set_law(crane.model, d, crane.stroke_driver,
                  MotionLaw<double>::from_table(std::move(*law)));
    // The shared start is in equilibrium for the base cycle's first stroke; another start
    // needs its own.
    if (dk.front() != o.ds.front())
      if (Status st = solve_static_equilibrium(crane.model, d); !st) {
        r.status = StepStatus::non_finite_state;
        r.error = st.error().what();
        return;
      }
    if (Status st = initialize(crane.model, d); !st) {
      r.status = StepStatus::non_finite_state;
      r.error = st.error().what();
      return;
    }
    const auto steps = static_cast<long>(std::ceil(r.duration / o.step));
    for (long i = 0; i < steps; ++i) {
      if (const StepStatus st = step(crane.model, d); !r.budget.keep(st, d.statistics)) {
        r.status = st;
        return;
      }
      (void)evaluate_outputs(crane.model, d);
      const double hot = output_value(d, crane.output(hot_row)) / 1e6;
      r.hot_max = std::max(r.hot_max, hot);
      r.hot_min = std::min(r.hot_min, hot);
      ++r.steps;
    }
    r.damage = meter_damage(d, crane.hot_spot_meter);
  };
  const bool progress = !o.quiet && ::isatty(STDERR_FILENO);
  const unsigned used = batch_threads(threads, out.size());
  const auto start = Clock::now();
  run_batch(out.size(), used, job, [&](std::size_t done, std::size_t total) {
    if (progress) std::fprintf(stderr, "\r  operators done: %zu of %zu", done, total);
  });
  const double wall = std::chrono::duration<double>(Clock::now() - start).count();
  if (progress) std::fprintf(stderr, "\r%40s\r", "");

  std::ofstream csv(o.output + "/operators.csv");
  csv << "operator,lift_m,cycle_s,hot_spot_max_MPa,hot_spot_min_MPa,damage_per_cycle,steps\n";
  csv.precision(9);
  std::printf("crane: %d operators (from operator %d) on %u threads, FFRF boom with %d modes\n",
              count, first, used, o.crane.modes);
  long steps = 0, failed = 0;
  double total = 0;
  BudgetCount budget;
  for (std::size_t j = 0; j < out.size(); ++j) {
    const OperatorOutcome& r = out[j];
    const int k = first + static_cast<int>(j);
    if (r.status != StepStatus::ok) {
      ++failed;
      std::fprintf(stderr, "error: operator %d: %s%s%s\n", k, to_string(r.status),
                   r.error.empty() ? "" : ": ", r.error.c_str());
      continue;
    }
    steps += r.steps;
    total += r.damage;
    budget.add(r.budget);
    std::printf(
        "  operator %d: lift %.4f m in %.3f s, hot spot %.3f to %.3f MPa, damage per cycle "
        "%.6g\n",
        k, r.lift, r.duration, r.hot_min, r.hot_max, r.damage);
    csv << k << ',' << r.lift << ',' << r.duration << ',' << r.hot_max << ',' << r.hot_min << ','
        << r.damage << ',' << r.steps << '\n';
  }
  if (failed > 0) {
    std::fprintf(stderr, "error: %ld of %d operators failed; no totals are reported\n", failed,
                 count);
    return 1;
  }
  print_budget(o, budget, steps);
  std::printf("operators: %d\n", count);
  std::printf("threads: %u\n", used);
  std::printf("batch_wall_s: %.3f\n", wall);
  std::printf("batch_steps_per_s: %.0f\n", static_cast<double>(steps) / wall);
  std::printf("damage_per_round: %.6g\n", total);
  return 0;
}

int run_game_loop(const RunOptions& o, double render_hz, bool realtime) {
  using Clock = std::chrono::steady_clock;
  auto made = build_crane(o);
  if (!made) return 1;
  const Crane& cr = *made;
  const Model<double>& model = cr.model;
  Data<double> d = start_data(cr, o);
  if (Status st = initialize(model, d); !st) {
    std::fprintf(stderr, "error: %s\n", st.error().what().c_str());
    return 1;
  }
  // Render vertices: 91 along the top flange (y = +75 mm), 5 cm apart, carried by the boom's
  // beam line with Hermite interpolation between its nodes.
  std::vector<Vector3d> vertices;
  for (int i = 0; i <= 90; ++i) vertices.emplace_back(0.05 * i, 0.075, 0.0);
  auto shape =
      stress::DeformedShape<Eigen::Dynamic>::along_beam(cr.boom.data, cr.boom.line.nodes, vertices);
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
  // The boom's last two states, for the display between them.
  Vector3d r_prev = body_position(model, d, cr.boom_body), r_shown;
  Eigen::Vector4d theta_prev = body_orientation(model, d, cr.boom_body), theta_shown;
  VectorXd p_prev = modal_coordinates(model, d, cr.boom_body), p_shown = p_prev;
  const VectorXd p_zero = VectorXd::Zero(p_prev.size());
  double accumulator = 0.0, hot = 0.0, largest_deflection = 0.0;
  long frames = 0, steps = 0, most_steps = 0;
  BudgetCount budget;  // steps kept at --newton-budget
  bool failed = false;
  const bool hud = !o.quiet && ::isatty(STDERR_FILENO);
  auto next_frame = Clock::now();
  auto last = Clock::now();
  while (d.t < t_end - 0.5 * h && !failed) {
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
    while (accumulator >= h && d.t < t_end - 0.5 * h) {
      r_prev = body_position(model, d, cr.boom_body);
      theta_prev = body_orientation(model, d, cr.boom_body);
      p_prev = modal_coordinates(model, d, cr.boom_body);
      if (const StepStatus st = step(model, d); !budget.keep(st, d.statistics)) {
        std::fprintf(stderr, "error: step at t = %g s: %s\n", d.t, to_string(st));
        failed = true;
        break;
      }
      (void)evaluate_outputs(model, d);
      hot = output_value(d, cr.output(cr.detail.hot_spot)) / 1e6;
      accumulator -= h;
      ++taken;
    }
    if (failed) break;
    steps += taken;
    most_steps = std::max(most_steps, taken);
    // Render: the boom between its last two states (normalized linear interpolation of the
    // Euler parameters on one hemisphere), its vertices from the mode shapes.
    const double alpha = std::clamp(accumulator / h, 0.0, 1.0);
    const Eigen::Vector4d theta_now = body_orientation(model, d, cr.boom_body);
    const double sign = theta_prev.dot(theta_now) < 0 ? -1.0 : 1.0;
    r_shown = r_prev + alpha * (body_position(model, d, cr.boom_body) - r_prev);
    theta_shown = (theta_prev + alpha * (sign * theta_now - theta_prev)).normalized();
    p_shown = p_prev + alpha * (modal_coordinates(model, d, cr.boom_body) - p_prev);
    shape->evaluate(r_shown, theta_shown, p_shown, drawn);
    shape->evaluate(r_shown, theta_shown, p_zero, rigid);
    const Index tip = shape->size() - 1;
    const double deflection = (drawn.col(tip) - rigid.col(tip)).norm() * 1e3;
    largest_deflection = std::max(largest_deflection, deflection);
    const double damage = d.meters[std::size_t(cr.hot_spot_meter.index)].closed_damage();
    csv << frames << ',' << dt << ',' << d.t << ',' << taken << ',' << alpha << ',' << drawn(0, tip)
        << ',' << drawn(1, tip) << ',' << deflection << ',' << hot << ',' << damage << '\n';
    if (hud && frames % 10 == 0)
      std::fprintf(stderr, "\r  t %5.2f s | hot spot %6.2f MPa | damage so far %.3e | tip %.2f mm",
                   d.t, hot, damage, deflection);
    ++frames;
  }
  if (hud) std::fprintf(stderr, "\r%80s\r", "");
  if (failed) return 1;
  const double damage = meter_damage(d, cr.hot_spot_meter);
  std::printf(
      "crane: game loop, %ld frames at %.0f Hz (%s), %ld fixed steps of %g s, %ld render "
      "vertices on the boom\n",
      frames, render_hz, realtime ? "wall clock" : "simulated clock with jitter", steps, h,
      static_cast<long>(shape->size()));
  std::printf("  largest tip deflection on screen %.3f mm; damage per work cycle %.6g\n",
              largest_deflection, damage);
  print_budget(o, budget, steps);
  std::printf("frames: %ld\n", frames);
  std::printf("steps: %ld\n", steps);
  std::printf("max_steps_per_frame: %ld\n", most_steps);
  std::printf("tip_deflection_max_mm: %.4f\n", largest_deflection);
  std::printf("damage_per_cycle: %.6g\n", damage);
  return 0;
}

}  // namespace crane
