// Cost of the GeometricStiffening effect per step (Google Benchmark; build Release): the
// spin-up beam (examples/spin_up_beam, hub-attached frame) spinning at a constant 3 rad/s, with
// N = 4, 10, 20 modes, with and without the effect; 2e4 steps at h = 1 ms, velocity projection
// on (as the example needs). Counters: median and worst step (us), Newton iterations per step.
// Results: docs/performance.md.
//
// Run: ./build/bench/bench_geometric_stiffening --benchmark_counters_tabular=true
#include <algorithm>
#include <chrono>
#include <vector>

#include <benchmark/benchmark.h>

#include <flexstress/dynamics/implicit_integrator.hpp>

#include "../examples/spin_up_beam/spin_up_model.hpp"

using namespace flexstress;

namespace {

using Clock = std::chrono::steady_clock;
constexpr int kSteps = 20000;

template <int N, bool Stiffening>
void spinning_beam(benchmark::State& bench) {
  using Eff = std::conditional_t<Stiffening, Effects<QuadraticVelocity, GeometricStiffening>,
                                 Effects<QuadraticVelocity>>;
  using S = spin_up::SpinUpScene<N, Eff>;
  spin_up::Spec spec;
  spec.spin_up_time = 0;
  spec.final_rate = 3.0;
  auto beam = spin_up::make_beam(spec, N);
  if (!beam) return bench.SkipWithError("beam setup failed");
  auto scene = spin_up::make_scene<S>(*beam, spec);
  if (!scene) return bench.SkipWithError("scene setup failed");
  typename ImplicitIntegrator<S>::Settings settings;
  settings.project_velocities = true;
  ImplicitIntegrator<S> integ(*scene, settings);
  typename S::State s;
  s.v(5) = spec.final_rate;
  s.v(6) = 0.05;  // a bending vibration to keep Newton busy
  if (!integ.initialize(s)) return bench.SkipWithError("initialize failed");
  std::vector<double> us;
  us.reserve(kSteps);
  for (auto _ : bench) {
    for (int i = 0; i < kSteps; ++i) {
      const auto a = Clock::now();
      const StepStatus st = integ.step(s);
      const auto b = Clock::now();
      if (st != StepStatus::ok) return bench.SkipWithError(to_string(st));
      us.push_back(std::chrono::duration<double, std::micro>(b - a).count());
    }
  }
  const auto mid = us.begin() + static_cast<std::ptrdiff_t>(us.size() / 2);
  std::nth_element(us.begin(), mid, us.end());
  bench.counters["median_us"] = *mid;
  bench.counters["worst_us"] = *std::max_element(us.begin(), us.end());
  bench.counters["newton_its"] = static_cast<double>(integ.statistics().iterations) /
                                 static_cast<double>(integ.statistics().steps);
}

}  // namespace

BENCHMARK_TEMPLATE(spinning_beam, 4, false)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(spinning_beam, 4, true)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(spinning_beam, 10, false)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(spinning_beam, 10, true)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(spinning_beam, 20, false)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(spinning_beam, 20, true)->Iterations(1)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
