// Per-step timing for the dynamics benchmarks (bench_dynamics.cpp, bench_crane.cpp,
// bench_geometric_stiffening.cpp).
#pragma once

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <vector>

#include <benchmark/benchmark.h>

#include <flexstress/core/status.hpp>

namespace flexstress::bench_support {

/// Times `steps` calls of step_once() (returning a StepStatus) one by one; reports median, worst
/// and mean (us) as counters.
template <class StepOnce>
void time_steps(benchmark::State& bench, StepOnce&& step_once, int steps) {
  using Clock = std::chrono::steady_clock;
  std::vector<double> us;
  us.reserve(static_cast<std::size_t>(steps));
  for (auto _ : bench) {
    for (int i = 0; i < steps; ++i) {
      const auto a = Clock::now();
      const StepStatus st = step_once();
      const auto b = Clock::now();
      if (st != StepStatus::ok) {
        bench.SkipWithError(to_string(st));
        return;
      }
      us.push_back(std::chrono::duration<double, std::micro>(b - a).count());
    }
  }
  double mean = 0;
  for (double u : us) mean += u;
  mean /= static_cast<double>(us.size());
  const auto mid = us.begin() + static_cast<std::ptrdiff_t>(us.size() / 2);
  std::nth_element(us.begin(), mid, us.end());
  bench.counters["median_us"] = *mid;
  bench.counters["worst_us"] = *std::max_element(us.begin(), us.end());
  bench.counters["mean_us"] = mean;
}

}  // namespace flexstress::bench_support
