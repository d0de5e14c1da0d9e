// Per-step cost of the crane (examples/crane: 10 boom modes, 5 joints, 18 equations) over its
// 11 s synthetic work cycle at h = 1 ms (Google Benchmark; build Release):
//   crane_cycle<L, E>   L = 64: fixed-size storage, 0: dynamic; Newton tolerance 10^-E m/s^2
//                       (E = 5 by default); reports median, worst and mean step (us), Newton
//                       iterations and factorizations per step (crane_cycle.hpp)
//   crane_effects_*     the same cycle (L = 64, E = 5) with one effect taken from the crane's
//                       list or geometric stiffening added, or none at all: the cost of each
//                       effect (crane_effects/, one scene type per unit)
// In its own program, apart from bench_dynamics: in a unit that instantiates a dozen scenes the
// compiler stops inlining the small fixed-size products (3 x 3 matrix times vector became calls),
// and the crane stepped 10 % more instructions and 40 % slower than in examples/crane. One scene
// per unit is what an application compiles. Like bench_dynamics, CI does not build it
// (FLEXSTRESS_BENCH_DYNAMICS=OFF). Results: docs/performance.md.
//
// Run: ./build/bench/bench_crane --benchmark_counters_tabular=true
#include "crane_cycle.hpp"

using flexstress::bench_support::crane_cycle;

FLEXSTRESS_CRANE_ONCE(BENCHMARK_TEMPLATE(crane_cycle, 64));
FLEXSTRESS_CRANE_ONCE(BENCHMARK_TEMPLATE(crane_cycle, 64, 3));
FLEXSTRESS_CRANE_ONCE(BENCHMARK_TEMPLATE(crane_cycle, 0));

BENCHMARK_MAIN();
