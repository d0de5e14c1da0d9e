// Per-step cost of the crane (examples/crane: 10 boom modes, 5 joints, 18 equations) over its
// 11 s synthetic work cycle at h = 1 ms (Google Benchmark; build Release):
//   crane_cycle/tol:E   Newton tolerance 10^-E m/s^2 (E = 5: the default; 3: the accuracy
//                       study's pick, which gives the same stress history); reports median,
//                       worst and mean step (us), Newton iterations and factorizations per step
//   crane_effects_*     the same cycle (E = 5) with one effect taken from the crane's list or
//                       geometric stiffening added, or none at all: the cost of each effect
// The effects are builder choices (CraneOptions) of one runtime model, so every row runs the
// same compiled step. Results: docs/performance.md.
//
// Run: ./build/bench/bench_crane --benchmark_counters_tabular=true
#include <cmath>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "../examples/crane/crane_model.hpp"
#include "step_timing.hpp"

using namespace flexstress;

namespace {

void crane_cycle(benchmark::State& bench, const crane::CraneOptions& options,
                 int tolerance_exponent) {
  std::vector<double> t, ds;
  crane::synthetic_cycle(t, ds);
  auto made = crane::make_crane(crane::CraneSpec{}, options, t, ds);
  if (!made) return bench.SkipWithError(made.error().what().c_str());
  const Model<double>& model = made->model;
  Data<double> d = made->initial;
  d.settings.acceleration_tolerance = std::pow(10.0, -tolerance_exponent);
  d.settings.relative_acceleration_tolerance = 0;  // the absolute tolerance alone
  d.settings.refresh_workspace = false;            // as examples/crane: no reader of the workspace
  if (Status st = initialize(model, d); !st) return bench.SkipWithError(st.error().what().c_str());
  bench_support::time_steps(
      bench, [&] { return step(model, d); }, 11000);
  const auto steps = static_cast<double>(d.statistics.steps);
  bench.counters["newton_its"] = static_cast<double>(d.statistics.iterations) / steps;
  bench.counters["factorizations"] = static_cast<double>(d.statistics.factorizations) / steps;
}

void crane_cycle_at(benchmark::State& bench) {
  crane_cycle(bench, crane::CraneOptions{}, static_cast<int>(bench.range(0)));
}

// The crane's effects (gravity, quadratic velocity terms, modal damping) changed one at a time.
struct EffectRow {
  const char* name;
  bool gravity, quadratic_velocity, modal_damping, geometric_stiffening;
};
constexpr EffectRow kEffectRows[] = {
    {"crane_effects_without_gravity", false, true, true, false},
    {"crane_effects_without_quadratic_velocity", true, false, true, false},
    {"crane_effects_without_modal_damping", true, true, false, false},
    {"crane_effects_none", false, false, false, false},
    {"crane_effects_with_geometric_stiffening", true, true, true, true},
};

}  // namespace

// Runs its body once (the body times its own 11 000 steps).
#define FLEXSTRESS_CRANE_ONCE(b) b->Iterations(1)->Unit(benchmark::kMillisecond)
FLEXSTRESS_CRANE_ONCE(
    BENCHMARK(crane_cycle_at)->Name("crane_cycle")->ArgName("tol")->Arg(5)->Arg(3));

int main(int argc, char** argv) {
  for (const EffectRow& row : kEffectRows) {
    crane::CraneOptions o;
    o.gravity = row.gravity;
    o.quadratic_velocity = row.quadratic_velocity;
    o.modal_damping = row.modal_damping;
    o.geometric_stiffening = row.geometric_stiffening;
    FLEXSTRESS_CRANE_ONCE(benchmark::RegisterBenchmark(
        row.name, [o](benchmark::State& bench) { crane_cycle(bench, o, 5); }));
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
