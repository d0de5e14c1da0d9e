// IFToMM benchmark A02, the N four-bar mechanism (Gonzalez, Dopico, Lugris, Cuadrado, Multibody
// Syst. Dyn. 16 (2006) 179-190), with N = 4 so it runs in every build; the benchmark's N = 40
// is examples/four_bar_chain (docs/dynamics.md has its figures). References: the exact motion
// (every crank parallel to the first, every coupler horizontal), conservation of energy, and
// the benchmark's accepted error for high-precision solutions, 1e-3.
#include <cmath>
#include <string>

#include <doctest/doctest.h>

#include "../../examples/four_bar_chain/four_bar_chain.hpp"

namespace test_four_bar_chain {

using namespace flexstress;

TEST_CASE("A02 N four-bar (N = 4): 20 s through 20 singular configurations without a jump") {
  const auto chain = four_bar_chain::make_chain(4, 2e-3);
  if (!chain.ok()) FAIL(chain.error().what());
  const Model<double>& model = chain->model;
  Data<double> d(model);
  REQUIRE(four_bar_chain::start(*chain, d).ok());
  const double e0 = energy(model, d).total();
  four_bar_chain::Monitor monitor;
  monitor.record(*chain, d, e0, e0, false);
  const int steps = 10000;  // 20 s
  long over_budget = 0;
  for (int i = 0; i < steps; ++i) {
    const StepStatus st = step(model, d);
    if (st != StepStatus::ok && st != StepStatus::budget_reached)
      FAIL("step " << i << " at t = " << d.t << ": " << to_string(st));
    const bool kept = st == StepStatus::budget_reached;
    over_budget += kept ? 1 : 0;
    monitor.record(*chain, d, energy(model, d).total(), e0, kept);
  }
  MESSAGE("singular configurations "
          << monitor.singular_passes << ", energy error " << monitor.energy_error << " J of " << e0
          << " J, crank spread " << monitor.crank_spread << " rad, coupler tilt "
          << monitor.coupler_tilt << " rad, " << over_budget << " steps kept at the budget, within "
          << monitor.budget_angle << " rad of the horizontal");
  // The tip's initial 1 m/s carries the chain over the top: 20 passes of the horizontal in 20 s.
  CHECK(monitor.singular_passes >= 20);
  // No branch jump: a folded parallelogram would put a crank about pi away from the first.
  CHECK(monitor.crank_spread < 1e-3);
  CHECK(monitor.coupler_tilt < 1e-3);
  CHECK(monitor.energy_error < 1e-3 * std::abs(e0));
  // The budget is spent only where the Jacobian loses rank, not along the way.
  CHECK(over_budget < steps / 100);
  CHECK(monitor.budget_angle < 0.01);
}

}  // namespace test_four_bar_chain
