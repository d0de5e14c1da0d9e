// IFToMM benchmark A02, the N four-bar mechanism (Gonzalez, Dopico, Lugris, Cuadrado, Multibody
// Syst. Dyn. 16 (2006) 179-190), with N = 4 so it runs in every build; the benchmark's N = 40
// is examples/four_bar_chain (docs/dynamics.md has its figures). References: the exact motion
// (every crank parallel to the first, every coupler horizontal), conservation of energy, and
// the benchmark's accepted error for high-precision solutions, 1e-3.
#include <algorithm>
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

// Near a singular configuration the augmented Lagrangian's multiplier updates contract slowly
// (by about 1 / (1 + penalty sigma^2) per iteration for a Jacobian singular value sigma), even
// with a fresh matrix; the step then raises the penalty (ImplicitSettings::max_penalty_factor)
// and keeps it raised (penalty_hold_steps). The N = 40 chain's long loops give its Jacobian
// small singular values away from the singular configuration too. On the defaults, up to
// 0.70 s, 22 ms before the cranks first lie flat: with the raise its steps converge whole
// (measured: 2.3 iterations per step, within the at most 3 on average that the defaults are to
// need on every mechanism; the first crank 2e-6 rad off the exact motion, two orders below the
// benchmark's 1e-3); without it Newton stalls in pieces of the step and the run stops at
// 0.659 s.
TEST_CASE("A02 N four-bar (N = 40) on the defaults: the penalty rises near the singular position" *
          doctest::test_suite("long")) {
  const auto chain = four_bar_chain::make_chain(40, 1e-3);
  if (!chain.ok()) FAIL(chain.error().what());
  const auto run = [&](double max_penalty_factor, double& worst) {
    ImplicitSettings<double> settings;  // the defaults, not the example's tuned settings
    settings.max_penalty_factor = max_penalty_factor;
    Data<double> d(chain->model);
    REQUIRE(set_settings(chain->model, d, settings).ok());
    REQUIRE(four_bar_chain::start(*chain, d).ok());
    four_bar_chain::ExactMotion exact(40);
    worst = 0;
    for (int k = 0; k < 700; ++k) {
      exact.advance(1e-3);
      if (step(chain->model, d) != StepStatus::ok) return d;
      const double heading = four_bar_chain::heading(*chain, d, chain->cranks.front());
      worst = std::max(worst, std::abs(std::remainder(heading - exact.angle(), 6.283185307179586)));
    }
    return d;
  };
  double worst_raised = 0, worst_fixed = 0;
  const Data<double> raised = run(ImplicitSettings<double>().max_penalty_factor, worst_raised);
  const Data<double> fixed = run(0.0, worst_fixed);
  const auto per_step = [](const Data<double>& d, long count) {
    return double(count) / double(std::max(1L, d.statistics.steps));
  };
  MESSAGE("raised: t = " << raised.t << ", " << per_step(raised, raised.statistics.iterations)
                         << " iterations and " << per_step(raised, raised.statistics.factorizations)
                         << " factorizations per step, " << raised.statistics.split_steps
                         << " steps split, crank angle within " << worst_raised
                         << " rad; fixed penalty: t = " << fixed.t << ", "
                         << per_step(fixed, fixed.statistics.iterations) << " iterations per step, "
                         << fixed.statistics.split_steps << " steps split");
  CHECK(raised.t == doctest::Approx(0.7));
  CHECK(per_step(raised, raised.statistics.iterations) <= 3.0);
  CHECK(raised.statistics.split_steps == 0);
  CHECK(worst_raised < 1e-5);
  CHECK(fixed.t < 0.69);
}

// A checkpoint holds the raised penalty and the steps since it was raised
// (model/checkpoint.hpp): a run restored from one taken while the N = 40 chain's penalty is
// raised continues bit for bit, its penalty falling at the same step (with the age not
// restored it would fall 67 steps later: measured by leaving it out). Settings out of range in
// a checkpoint (it stores them as bytes) are refused, naming the setting.
TEST_CASE("A02 N four-bar (N = 40): a checkpoint keeps the raised penalty and its age") {
  const auto chain = four_bar_chain::make_chain(40, 1e-3);
  if (!chain.ok()) FAIL(chain.error().what());
  const Model<double>& model = chain->model;
  Data<double> a(model), b(model);
  REQUIRE(set_settings(model, a, ImplicitSettings<double>()).ok());
  REQUIRE(four_bar_chain::start(*chain, a).ok());
  for (int k = 0; k < 120; ++k) REQUIRE(step(model, a) == StepStatus::ok);
  REQUIRE(a.integrator.penalty_boost > 1.0);  // raised from step 52 on (measured)
  const auto saved = save_checkpoint(model, a);
  REQUIRE(saved.ok());
  REQUIRE(restore_checkpoint(model, b, saved->data(), saved->size()).ok());
  CHECK(b.integrator.penalty_boost == a.integrator.penalty_boost);
  CHECK(b.integrator.boost_age == a.integrator.boost_age);
  bool fell = false;
  for (int k = 0; k < 150; ++k) {
    CAPTURE(k);
    const double before = a.integrator.penalty_boost;
    REQUIRE(step(model, a) == StepStatus::ok);
    REQUIRE(step(model, b) == StepStatus::ok);
    fell = fell || a.integrator.penalty_boost < before;
    REQUIRE(a.integrator.penalty_boost == b.integrator.penalty_boost);
  }
  CHECK(fell);
  CHECK(a.q == b.q);
  CHECK(a.v == b.v);
  CHECK(a.statistics.iterations - b.statistics.iterations == 0);

  Data<double> damaged(model);
  damaged.settings.penalty_hold_steps = -1;  // as a damaged file's bytes could read
  const auto bad = save_checkpoint(model, damaged);
  REQUIRE(bad.ok());
  const Status refused = restore_checkpoint(model, b, bad->data(), bad->size(), "run.ckpt");
  REQUIRE_FALSE(refused.ok());
  CHECK(std::string(refused.error().what()).find("penalty_hold_steps") != std::string::npos);
  CHECK(std::string(refused.error().what()).find("run.ckpt") != std::string::npos);
}

}  // namespace test_four_bar_chain
