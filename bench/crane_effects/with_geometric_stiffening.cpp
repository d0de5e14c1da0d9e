// A bench_crane row: the crane with the boom's geometric stiffening added.
// One scene type per unit (crane_cycle.hpp says why); compare with crane_cycle<64>, the
// crane's own effect list (gravity, quadratic velocity terms, modal damping).
#include "../crane_cycle.hpp"

namespace {

void crane_effects_with_geometric_stiffening(benchmark::State& bench) {
  using namespace flexstress;
  bench_support::crane_cycle<
      64, 5, Effects<Gravity, QuadraticVelocity, ModalDamping, GeometricStiffening>>(bench);
}

}  // namespace

FLEXSTRESS_CRANE_ONCE(BENCHMARK(crane_effects_with_geometric_stiffening));
