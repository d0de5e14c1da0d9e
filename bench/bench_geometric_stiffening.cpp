// Cost of geometric stiffening per step (Google Benchmark; build Release): the spin-up beam
// (examples/spin_up_beam, hub-attached frame) spinning at a constant 3 rad/s, with N = 4, 10, 20
// modes, with and without the effect; 2e4 steps at h = 1 ms, velocity projection on (as the
// example needs). Counters: median and worst step (us), Newton iterations per step.
// Results: docs/performance.md.
//
// Run: ./build/bench/bench_geometric_stiffening --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include "../examples/spin_up_beam/spin_up_model.hpp"
#include "step_timing.hpp"

using namespace flexstress;

namespace {

constexpr int kSteps = 20000;

void spinning_beam(benchmark::State& bench) {
  const int modes = static_cast<int>(bench.range(0));
  const bool stiffening = bench.range(1) != 0;
  spin_up::Spec spec;
  spec.spin_up_time = 0;
  spec.final_rate = 3.0;
  auto beam = spin_up::make_beam(spec, modes);
  if (!beam) return bench.SkipWithError("beam setup failed");
  auto made = spin_up::make_model(*beam, spec, stiffening, modes);
  if (!made) return bench.SkipWithError(made.error().what().c_str());
  const Model<double>& model = made->model;
  Data<double> d(model);
  set_body_velocity(model, d, made->beam, Vector3d::Zero(), Vector3d(0, 0, spec.final_rate));
  Eigen::VectorXd p_dot = Eigen::VectorXd::Zero(modes);
  p_dot(0) = 0.05;  // a bending vibration to keep Newton busy
  if (!set_modal_state(model, d, made->beam, Eigen::VectorXd::Zero(modes), p_dot))
    return bench.SkipWithError("modal state refused");
  if (!initialize(model, d)) return bench.SkipWithError("initialize failed");
  bench_support::time_steps(
      bench, [&] { return step(model, d); }, kSteps);
  bench.counters["newton_its"] =
      static_cast<double>(d.statistics.iterations) / static_cast<double>(d.statistics.steps);
}

}  // namespace

BENCHMARK(spinning_beam)
    ->ArgNames({"modes", "stiffening"})
    ->ArgsProduct({{4, 10, 20}, {0, 1}})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
