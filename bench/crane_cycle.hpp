// The crane's 11 s work cycle as a benchmark body (examples/crane: 10 boom modes, 5 joints,
// 18 equations, h = 1 ms), shared by bench_crane's units. Each unit instantiates one or two
// scene types only: in a unit of a dozen scenes GCC stops inlining the small fixed-size
// products (bench_crane.cpp says more), which would bias a comparison of effect lists.
#pragma once

#include <cmath>
#include <vector>

#include <benchmark/benchmark.h>

#include <flexstress/dynamics/implicit_integrator.hpp>

#include "../examples/crane/crane_scene.hpp"
#include "step_timing.hpp"

namespace flexstress::bench_support {

/// L: the scene's storage limit (64: fixed-size, 0: dynamic); ToleranceExponent E: Newton
/// tolerance 10^-E m/s^2 (5: the default; 3: the accuracy study's pick, which gives the same
/// stress history, docs/accuracy-vs-time.md); EffectList: the scene's effects (the crane's:
/// gravity, quadratic velocity terms, modal damping). Reports median, worst and mean step (us),
/// Newton iterations and factorizations per step.
template <int L, int ToleranceExponent = 5, class EffectList = crane::CraneEffects>
void crane_cycle(benchmark::State& bench) {
  std::vector<double> t, ds;
  crane::synthetic_cycle(t, ds);
  auto made = crane::make_crane<10, L, double, EffectList>(crane::CraneSpec{}, t, ds);
  if (!made) return bench.SkipWithError(made.error().what().c_str());
  using S = crane::CraneScene<10, L, double, EffectList>;
  typename ImplicitIntegrator<S>::Settings settings;
  settings.acceleration_tolerance = std::pow(10.0, -ToleranceExponent);
  settings.refresh_workspace = false;  // as examples/crane: no reader of the workspace
  ImplicitIntegrator<S> integ(made->scene, settings);
  auto s = made->initial;
  if (Status st = integ.initialize(s); !st) return bench.SkipWithError(st.error().what().c_str());
  time_steps(bench, integ, s, 11000);
  const auto steps = static_cast<double>(integ.statistics().steps);
  bench.counters["newton_its"] = static_cast<double>(integ.statistics().iterations) / steps;
  bench.counters["factorizations"] = static_cast<double>(integ.statistics().factorizations) / steps;
}

}  // namespace flexstress::bench_support

/// Registers a benchmark that runs its body once (the body times its own 11 000 steps).
#define FLEXSTRESS_CRANE_ONCE(b) b->Iterations(1)->Unit(benchmark::kMillisecond)
