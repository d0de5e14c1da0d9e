// Interaction of normal and shear stress ranges. References: EN 1993-1-9:2005 section 8(3),
// eq. (8.3); the IIW Gough-Pollard ellipse (Delta_sigma / Delta_sigma_R)^2 +
// (Delta_tau / Delta_tau_R)^2 <= CV, CV = 1 for proportional loading. Expected values are the
// equations evaluated at points chosen so the terms come out round.
#include <cmath>

#include <doctest/doctest.h>

#include <flexstress/fatigue/damage.hpp>
#include <flexstress/fatigue/multiaxial.hpp>

namespace test_multiaxial {

using namespace flexstress;
using namespace flexstress::fatigue;

namespace {
void check_close(double a, double b, double tol) {
  CHECK(std::abs(a - b) <= tol * std::abs(b));
}
}  // namespace

TEST_CASE("EN 1993-1-9 eq. (8.3) at its limit") {
  // Normal stress alone at the category: 1. Half of each: 0.5 + 0.5.
  auto alone = en1993_interaction(80.0, 0.0, 80.0, 100.0);
  REQUIRE(alone.ok());
  CHECK(alone->value == 1.0);
  CHECK(alone->passed());
  auto halves = en1993_interaction(80.0 * std::cbrt(0.5), 100.0 * std::pow(0.5, 0.2), 80.0, 100.0);
  REQUIRE(halves.ok());
  check_close(halves->normal_term, 0.5, 1e-15);
  check_close(halves->shear_term, 0.5, 1e-15);
  // Partial factors: (gamma_Ff Delta_sigma / (Delta_sigma_C / gamma_Mf))^3.
  auto factored = en1993_interaction(40.0, 0.0, 80.0, 100.0, 1.1, 1.35);
  REQUIRE(factored.ok());
  check_close(factored->value, std::pow(1.1 * 1.35 * 0.5, 3), 1e-15);
}

TEST_CASE("EN 1993-1-9 eq. (8.3) equals the damage sum D_sigma + D_tau") {
  // Each term of (8.3) is the Miner damage of its equivalent range at 2e6 cycles.
  auto sigma_curve = en1993_normal_curve(71.0);
  auto tau_curve = en1993_shear_curve(80.0);
  REQUIRE(sigma_curve.ok());
  REQUIRE(tau_curve.ok());
  DamageOptions<double> options;
  options.gamma_ff = 1.0;
  options.gamma_mf = 1.15;
  auto ms = DamageModel<double>::create(*sigma_curve, options);
  auto mt = DamageModel<double>::create(*tau_curve, options);
  REQUIRE(ms.ok());
  REQUIRE(mt.ok());
  // 1.5e6 cycles of 75 (normal) and 3e6 cycles of 45 (shear), both on the first slope.
  const double d_sigma = 1.5e6 * ms->damage(Cycle<double>{0, 75, 1});
  const double d_tau = 3e6 * mt->damage(Cycle<double>{0, 45, 1});
  auto es = equivalent_stress_range(d_sigma, *ms);
  auto et = equivalent_stress_range(d_tau, *mt);
  REQUIRE(es.ok());
  REQUIRE(et.ok());
  auto by_range = en1993_interaction(*es, *et, 71.0, 80.0, 1.0, 1.15);
  auto by_damage = en1993_interaction_from_damage(d_sigma, d_tau);
  REQUIRE(by_range.ok());
  REQUIRE(by_damage.ok());
  check_close(by_range->normal_term, d_sigma, 1e-13);
  check_close(by_range->shear_term, d_tau, 1e-13);
  check_close(by_range->value, by_damage->value, 1e-13);
}

TEST_CASE("IIW Gough-Pollard ellipse with the comparison value") {
  // 0.6^2 + 0.8^2 = 1: on the ellipse for CV = 1, twice the limit for CV = 0.5.
  auto r = iiw_interaction(0.6 * 90, 0.8 * 80, 90.0, 80.0, 1.0);
  REQUIRE(r.ok());
  check_close(r->value, 1.0, 1e-15);
  auto half = iiw_interaction(0.6 * 90, 0.8 * 80, 90.0, 80.0, 0.5);
  REQUIRE(half.ok());
  CHECK_FALSE(half->passed());
  check_close(half->utilization(), 2.0, 1e-15);
  // Resistances read on the IIW curves at 1e6 cycles: FAT 90 (m = 3), shear FAT 80 (m = 5).
  auto normal = iiw_normal_curve(90.0);
  auto shear = iiw_shear_curve(80.0);
  REQUIRE(normal.ok());
  REQUIRE(shear.ok());
  const double sr = 90 * std::cbrt(2.0), tr = 80 * std::pow(2.0, 0.2);
  auto at_n = iiw_interaction(0.6 * sr, 0.8 * tr, 1e6, *normal, *shear, 1.0);
  REQUIRE(at_n.ok());
  check_close(at_n->value, 1.0, 1e-13);
  // Damage form: D = (ratio)^m on each slope gives back the same value.
  auto by_damage = iiw_interaction_from_damage(std::pow(0.6, 3), std::pow(0.8, 5), 3.0, 5.0, 1.0);
  REQUIRE(by_damage.ok());
  check_close(by_damage->value, 1.0, 1e-14);
}

TEST_CASE("bad interaction input is rejected") {
  auto cv = iiw_interaction(10.0, 10.0, 90.0, 80.0, 1.5);
  REQUIRE_FALSE(cv.ok());
  CHECK(cv.error().message == "comparison value CV must be in (0, 1], got 1.5");
  auto neg = en1993_interaction(-1.0, 0.0, 80.0, 100.0);
  REQUIRE_FALSE(neg.ok());
  CHECK(neg.error().message == "Delta_sigma_E,2 must be finite and >= 0, got -1");
  auto cat = en1993_interaction(10.0, 0.0, 0.0, 100.0);
  REQUIRE_FALSE(cat.ok());
  CHECK(cat.error().message == "Delta_sigma_C must be positive, got 0");
  auto dmg = en1993_interaction_from_damage(0.1, -0.2);
  REQUIRE_FALSE(dmg.ok());
}

}  // namespace test_multiaxial
