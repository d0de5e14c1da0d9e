// Per-step cost of the crane (examples/crane: 10 boom modes, 5 joints, 18 equations) over its
// 11 s synthetic work cycle at h = 1 ms (Google Benchmark; build Release):
//   crane_cycle<L, E>   L = 64: fixed-size storage, 0: dynamic; Newton tolerance 10^-E m/s^2
//                       (E = 5 by default); reports median, worst and mean step (us), Newton
//                       iterations and factorizations per step
// In its own program, apart from bench_dynamics: in a unit that instantiates a dozen scenes the
// compiler stops inlining the small fixed-size products (3 x 3 matrix times vector became calls),
// and the crane stepped 10 % more instructions and 40 % slower than in examples/crane. One scene
// per unit is what an application compiles. Like bench_dynamics, CI does not build it
// (FLEXSTRESS_BENCH_DYNAMICS=OFF). Results: docs/performance.md.
//
// Run: ./build/bench/bench_crane --benchmark_counters_tabular=true
#include <cmath>
#include <vector>

#include <benchmark/benchmark.h>

#include <flexstress/dynamics/implicit_integrator.hpp>

#include "../examples/crane/crane_model.hpp"
#include "step_timing.hpp"

using namespace flexstress;

namespace {

// ToleranceExponent E: Newton tolerance 10^-E m/s^2 (5: the default; 3: the accuracy study's
// pick, which gives the same stress history, docs/accuracy-vs-time.md).
template <int L, int ToleranceExponent = 5>
void crane_cycle(benchmark::State& bench) {
  std::vector<double> t, ds;
  crane::synthetic_cycle(t, ds);
  auto made = crane::make_crane<10, L>(crane::CraneSpec{}, t, ds);
  if (!made) return bench.SkipWithError(made.error().what().c_str());
  using S = crane::CraneScene<10, L>;
  typename ImplicitIntegrator<S>::Settings settings;
  settings.acceleration_tolerance = std::pow(10.0, -ToleranceExponent);
  settings.refresh_workspace = false;  // as examples/crane: no reader of the workspace
  ImplicitIntegrator<S> integ(made->scene, settings);
  auto s = made->initial;
  if (!integ.initialize(s)) return bench.SkipWithError("initialize failed");
  bench_support::time_steps(bench, integ, s, 11000);
  const auto steps = static_cast<double>(integ.statistics().steps);
  bench.counters["newton_its"] = static_cast<double>(integ.statistics().iterations) / steps;
  bench.counters["factorizations"] = static_cast<double>(integ.statistics().factorizations) / steps;
}

}  // namespace

#define FLEXSTRESS_ONCE(b) b->Iterations(1)->Unit(benchmark::kMillisecond)
FLEXSTRESS_ONCE(BENCHMARK_TEMPLATE(crane_cycle, 64));
FLEXSTRESS_ONCE(BENCHMARK_TEMPLATE(crane_cycle, 64, 3));
FLEXSTRESS_ONCE(BENCHMARK_TEMPLATE(crane_cycle, 0));

BENCHMARK_MAIN();
