// S-N curves at their defining points. References:
//   EN 1993-1-9:2005 section 7.1, Figs. 7.1 and 7.2: Delta_sigma_C at 2e6 cycles, m = 3 to
//   N_D = 5e6 with Delta_sigma_D = (2/5)^(1/3) Delta_sigma_C (0.7368), m = 5 to N_L = 1e8 with
//   Delta_sigma_L = (5/100)^(1/5) Delta_sigma_D (0.4047 Delta_sigma_C); shear m = 5 to 1e8 with
//   Delta_tau_L = (2/100)^(1/5) Delta_tau_C (0.4573); values as in validation.md.
//   IIW-2259-15 chapter 3: FAT at 2e6, m = 3 to the knee at 1e7, then m = 22 or Haibach
//   2m - 1 = 5; shear m = 5 to 1e8. Thickness factor (25 / t)^n.
#include <cmath>
#include <limits>
#include <vector>

#include <doctest/doctest.h>

#include <flexstress/fatigue/sn_curve.hpp>

namespace test_sn_curve {

using namespace flexstress;
using namespace flexstress::fatigue;

namespace {
// Relative tolerance for a few pow / division roundings in the Scalar type.
template <class T>
T rel_tol() {
  return sizeof(T) == sizeof(float) ? T(2e-5) : T(1e-12);
}
template <class T>
void check_rel(T actual, T expected) {
  CHECK(std::abs(actual - expected) <= rel_tol<T>() * std::abs(expected));
}
}  // namespace

TEST_CASE_TEMPLATE("EN 1993-1-9 direct-stress curves at 2e6, N_D and N_L", T, float, double) {
  for (T c : {T(36), T(50), T(71), T(80), T(90), T(100), T(112), T(125), T(160)}) {
    CAPTURE(c);
    auto curve = en1993_normal_curve(c);
    REQUIRE(curve.ok());
    const T d = c * std::cbrt(T(2) / T(5));       // constant-amplitude fatigue limit
    const T l = d * std::pow(T(0.05), T(1) / 5);  // cut-off limit
    check_rel(curve->stress_range_at(T(2e6)), c);
    check_rel(curve->cycles_to_failure(c), T(2e6));
    check_rel(curve->stress_range_at(T(5e6)), d);
    check_rel(curve->cycles_to_failure(d), T(5e6));
    check_rel(curve->stress_range_at(T(1e8)), l);
    check_rel(curve->cutoff_range(), l);
    // The rounded ratios printed in the standard.
    CHECK(std::abs(d / c - T(0.7368)) < T(5e-5));
    CHECK(std::abs(l / c - T(0.4047)) < T(5e-5));
    // Slopes: m = 3 above N_D, m = 5 between N_D and N_L.
    check_rel(curve->cycles_to_failure(T(2) * c), T(2e6) / T(8));
    check_rel(curve->cycles_to_failure(T(0.9) * d), T(5e6) * std::pow(T(1) / T(0.9), T(5)));
    // Below the cut-off no damage; at it, 1 / N_L. (At the curve's own cut-off: l computed
    // here may round to one ulp either side of it, depending on the compiler's pow.)
    CHECK(curve->damage_per_cycle(T(0.999) * l) == T(0));
    CHECK(std::isinf(curve->cycles_to_failure(T(0.999) * l)));
    check_rel(curve->damage_per_cycle(curve->cutoff_range()), T(1e-8));
    CHECK(curve->slope_at(T(1e6)) == T(3));
    CHECK(curve->slope_at(T(1e7)) == T(5));
    CHECK(std::isinf(curve->slope_at(T(2e8))));
  }
}

TEST_CASE_TEMPLATE("EN 1993-1-9 shear curves at 2e6 and N_L", T, float, double) {
  for (T c : {T(80), T(100)}) {
    auto curve = en1993_shear_curve(c);
    REQUIRE(curve.ok());
    const T l = c * std::pow(T(0.02), T(1) / 5);
    check_rel(curve->stress_range_at(T(2e6)), c);
    check_rel(curve->cutoff_range(), l);
    CHECK(std::abs(l / c - T(0.4573)) < T(5e-5));
    check_rel(curve->cycles_to_failure(T(2) * c), T(2e6) / T(32));
    CHECK(curve->damage_per_cycle(T(0.99) * l) == T(0));
  }
}

TEST_CASE_TEMPLATE("IIW FAT curves: 2e6, knee at 1e7, slope beyond the knee", T, float, double) {
  for (T fat : {T(71), T(90), T(100), T(112)}) {
    CAPTURE(fat);
    auto standard = iiw_normal_curve(fat);
    auto haibach = iiw_normal_curve(fat, IiwBeyondKnee::haibach);
    REQUIRE(standard.ok());
    REQUIRE(haibach.ok());
    const T knee = fat * std::cbrt(T(0.2));  // (2e6 / 1e7)^(1/3)
    for (const auto* curve : {&*standard, &*haibach}) {
      check_rel(curve->stress_range_at(T(2e6)), fat);
      check_rel(curve->stress_range_at(T(1e7)), knee);
      check_rel(curve->cycles_to_failure(knee), T(1e7));
      CHECK(curve->cutoff_range() == T(0));                // no cut-off: every range does damage
      CHECK(curve->damage_per_cycle(knee / T(3)) > T(0));  // still damaging far below the knee
    }
    check_rel(standard->stress_range_at(T(1e8)), knee * std::pow(T(0.1), T(1) / 22));
    check_rel(haibach->stress_range_at(T(1e8)), knee * std::pow(T(0.1), T(1) / 5));
    CHECK(standard->slope_at(T(1e9)) == T(22));
    CHECK(haibach->slope_at(T(1e9)) == T(5));
  }
  // Shear: m = 5 to the knee at 1e8.
  auto shear = iiw_shear_curve(T(100));
  REQUIRE(shear.ok());
  check_rel(shear->stress_range_at(T(2e6)), T(100));
  check_rel(shear->stress_range_at(T(1e8)), T(100) * std::pow(T(0.02), T(1) / 5));
  CHECK(shear->slope_at(T(1e9)) == T(22));
  auto shear_haibach = iiw_shear_curve(T(100), IiwBeyondKnee::haibach);
  REQUIRE(shear_haibach.ok());
  CHECK(shear_haibach->slope_at(T(1e9)) == T(9));
}

TEST_CASE_TEMPLATE("user curves are continuous at their knees and pass their reference", T, float,
                   double) {
  // Reference point in the second segment: knees are found backwards too.
  auto curve = SnCurve<T>::create(T(50), T(1e8), {{T(3), T(1e7)}, {T(5), T(1e9)}, {T(9)}});
  REQUIRE(curve.ok());
  const T s1 = T(50) * std::pow(T(10), T(1) / 5);   // at 1e7, up the m = 5 segment
  const T s2 = T(50) * std::pow(T(0.1), T(1) / 5);  // at 1e9, down the m = 5 segment
  check_rel(curve->stress_range_at(T(1e8)), T(50));
  check_rel(curve->end_range(0), s1);
  check_rel(curve->end_range(1), s2);
  check_rel(curve->cycles_to_failure(s1), T(1e7));
  check_rel(curve->cycles_to_failure(s2), T(1e9));
  check_rel(curve->cycles_to_failure(T(2) * s1), T(1e7) / T(8));
  check_rel(curve->cycles_to_failure(s2 / T(2)), T(1e9) * T(512));
  check_rel(curve->damage_per_cycle(T(60)), T(1) / curve->cycles_to_failure(T(60)));
  CHECK(curve->damage_per_cycle(T(0)) == T(0));
  CHECK(curve->damage_per_cycle(T(-5)) == T(0));
}

TEST_CASE_TEMPLATE("partial safety factor and thickness scale the resistance", T, float, double) {
  auto curve = en1993_normal_curve(T(90));
  REQUIRE(curve.ok());
  auto design = curve->scaled(T(1) / T(1.35));  // gamma_Mf = 1.35 (EN 1993-1-9 Table 3.1)
  REQUIRE(design.ok());
  check_rel(design->stress_range_at(T(2e6)), T(90) / T(1.35));
  check_rel(design->cutoff_range(), curve->cutoff_range() / T(1.35));
  // IIW thickness correction (25 / t)^n, only above t_ref = 25 mm.
  auto f50 = iiw_thickness_factor(T(50), T(0.3));
  REQUIRE(f50.ok());
  check_rel(*f50, std::pow(T(0.5), T(0.3)));
  auto f20 = iiw_thickness_factor(T(20), T(0.3));
  REQUIRE(f20.ok());
  CHECK(*f20 == T(1));
}

TEST_CASE("bad S-N input is rejected with a message naming it") {
  auto neg = iiw_normal_curve(-3.0);
  REQUIRE_FALSE(neg.ok());
  CHECK(neg.error().message == "FAT must be positive, got -3");
  auto zero = en1993_normal_curve(0.0);
  REQUIRE_FALSE(zero.ok());
  CHECK(zero.error().message == "detail category Delta_sigma_C must be positive, got 0");
  auto nan = en1993_shear_curve(std::numeric_limits<double>::quiet_NaN());
  REQUIRE_FALSE(nan.ok());
  auto order = SnCurve<double>::create(100, 2e6, {{3, 1e7}, {5, 1e6}});
  REQUIRE_FALSE(order.ok());
  CHECK(order.error().message ==
        "S-N segment 1: end cycle count 1e+06 must exceed the previous one");
  auto open = SnCurve<double>::create(100, 2e6, {{3}, {5, 1e8}});
  REQUIRE_FALSE(open.ok());
  auto beyond = SnCurve<double>::create(100, 2e9, {{3, 1e8}});
  REQUIRE_FALSE(beyond.ok());
  CHECK(beyond.error().message ==
        "S-N reference point at 2e+09 cycles lies beyond the cut-off at 1e+08");
  auto slope = SnCurve<double>::create(100, 2e6, {{0, 1e8}});
  REQUIRE_FALSE(slope.ok());
  auto thick = iiw_thickness_factor(-3.0, 0.3);
  REQUIRE_FALSE(thick.ok());
  CHECK(thick.error().message == "plate thickness must be positive, got -3");
  auto exponent = iiw_thickness_factor(30.0, 1.5);
  REQUIRE_FALSE(exponent.ok());
  auto scale = en1993_normal_curve(80.0)->scaled(0.0);
  REQUIRE_FALSE(scale.ok());
}

}  // namespace test_sn_curve
