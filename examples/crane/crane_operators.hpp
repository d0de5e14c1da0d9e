// The crane's batch mode (--operators): many operators drive the same crane through their own
// versions of the work cycle, in parallel threads (core/batch.hpp), each with its own damage
// meter. What is precomputed (boom reduction, sub-model, fused stress rows, the equilibrium at
// the start) is built once and shared read-only; each job copies the scene description (a few
// kilobytes: the driver's stroke table is part of it) and has its own state, integrator and
// meter. Operator k's cycle depends on k only, so the results do not depend on the thread count
// or on how a campaign is split into ranges of operators (--first-operator): a job array on a
// cluster runs ranges and concatenates their operators.csv files (docs/scaling.md).
#pragma once

#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <vector>

#include <flexstress/core/batch.hpp>
#include <flexstress/fatigue/damage.hpp>
#include <flexstress/fatigue/sn_curve.hpp>
#include <flexstress/fatigue/streaming_damage.hpp>

#include "crane_run.hpp"

namespace crane {

/// Operator k's version of the base cycle (t, ds): operator 0 drives it as it is; the others
/// lift to 60-100 % of its height at 80-125 % of its pace, with their own small corrections
/// (up to 4 mm) while the boom is up. Deterministic in k (golden-ratio sequences, no random
/// generator), and kept within the cylinder's travel.
inline void operator_cycle(int k, const CraneSpec& spec, const std::vector<double>& t,
                           const std::vector<double>& ds, std::vector<double>& tk,
                           std::vector<double>& dk) {
  tk = t;
  dk = ds;
  if (k == 0) return;
  auto frac = [](double x) { return x - std::floor(x); };
  const double height = 0.6 + 0.4 * frac(0.5 + 0.6180339887 * k);
  const double pace = 0.8 + 0.45 * frac(0.5 + 0.4142135624 * k);
  const double lo = -spec.hydraulics.initial_position,
               hi = spec.hydraulics.stroke - spec.hydraulics.initial_position;
  for (std::size_t i = 0; i < t.size(); ++i) {
    tk[i] = t[0] + (t[i] - t[0]) / pace;
    const double correction = ds[i] != 0.0 ? 0.004 * std::sin(1.3 * k + double(i)) : 0.0;
    dk[i] = std::clamp(ds[i] * height + correction, lo, hi);
  }
}

/// What one operator's cycle gives.
struct OperatorOutcome {
  double lift = 0, duration = 0, hot_max = -1e300, hot_min = 1e300, damage = 0;
  long steps = 0;
  StepStatus status = StepStatus::ok;
};

/// Runs operators first .. first + count - 1 on `threads` threads (0: all hardware threads);
/// writes <output>/operators.csv and prints a line per operator and "key: value" lines.
template <int N, int StorageLimit>
int run_operators(const RunOptions& o, int first, int count, unsigned threads) {
  using Scene = CraneScene<N, StorageLimit, double, CraneEffects>;
  using Clock = std::chrono::steady_clock;
  auto made = build_crane<N, StorageLimit>(o);
  if (!made) return 1;
  const auto& crane = *made;  // shared by every job, read only
  const auto meter = make_damage_meter();
  if (!meter) return 1;
  typename ImplicitIntegrator<Scene>::Settings settings;
  settings.step = o.step;
  settings.acceleration_tolerance = o.tolerance;
  settings.refresh_workspace = false;  // nothing here reads the workspace after a step
  const double l0 = (o.spec.b - o.spec.c).norm();

  std::vector<OperatorOutcome> out(static_cast<std::size_t>(count));
  auto job = [&](std::size_t j) {
    const int k = first + static_cast<int>(j);
    OperatorOutcome& r = out[j];
    std::vector<double> tk, dk;
    operator_cycle(k, o.spec, o.t, o.ds, tk, dk);
    r.lift = *std::max_element(dk.begin(), dk.end());
    r.duration = tk.back() - tk.front();
    std::vector<double> stroke(dk);
    for (double& v : stroke) v += l0;
    auto law = TableLaw<double>::create(tk, stroke);
    if (!law) {
      r.status = StepStatus::invalid_input;
      return;
    }
    Scene scene = crane.scene;
    scene.template joint<4>().params.law = *law;
    typename Scene::State s = crane.initial;
    // The shared start is in equilibrium for the base cycle's first stroke; another start
    // needs its own.
    if (dk.front() != o.ds.front() && !solve_static_equilibrium(scene, s).ok()) {
      r.status = StepStatus::non_finite_state;
      return;
    }
    ImplicitIntegrator<Scene> integ(scene, settings);
    if (!integ.initialize(s).ok()) {
      r.status = StepStatus::non_finite_state;
      return;
    }
    auto damage = *meter;
    VectorXd y(crane.fused->num_outputs());
    const auto steps = static_cast<long>(std::ceil(r.duration / o.step));
    for (long i = 0; i < steps; ++i) {
      r.status = integ.step(s);
      if (r.status != StepStatus::ok) return;
      crane.fused->evaluate(s.template coordinates<0>().p, y);
      const double hot = y(crane.hot_spot_row) / 1e6;
      (void)damage.push(hot);
      r.hot_max = std::max(r.hot_max, hot);
      r.hot_min = std::min(r.hot_min, hot);
      ++r.steps;
    }
    r.damage = damage.damage(fatigue::CycleClosure::repeating);
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
              count, first, used, N);
  long steps = 0, failed = 0;
  double total = 0;
  for (std::size_t j = 0; j < out.size(); ++j) {
    const OperatorOutcome& r = out[j];
    const int k = first + static_cast<int>(j);
    if (r.status != StepStatus::ok) {
      ++failed;
      std::fprintf(stderr, "error: operator %d: %s\n", k, to_string(r.status));
      continue;
    }
    steps += r.steps;
    total += r.damage;
    std::printf(
        "  operator %d: lift %.4f m in %.3f s, hot spot %.3f to %.3f MPa, damage per cycle "
        "%.6g\n",
        k, r.lift, r.duration, r.hot_min, r.hot_max, r.damage);
    csv << k << ',' << r.lift << ',' << r.duration << ',' << r.hot_max << ',' << r.hot_min << ','
        << r.damage << ',' << r.steps << '\n';
  }
  std::printf("operators: %d\n", count);
  std::printf("threads: %u\n", used);
  std::printf("batch_wall_s: %.3f\n", wall);
  std::printf("batch_steps_per_s: %.0f\n", static_cast<double>(steps) / wall);
  std::printf("damage_per_round: %.6g\n", total);
  return failed ? 1 : 0;
}

extern template int run_operators<10, fixed_storage_limit>(const RunOptions&, int, int, unsigned);

}  // namespace crane
