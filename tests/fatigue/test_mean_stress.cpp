// Mean-stress corrections. References: the IIW enhancement factor f(R) of IIW-2259-15 section
// 3.5.1 (stress-relieved: 1.6 for R < -1, -0.4 R + 1.2 for -1 <= R <= 0.5, 1 above; moderate
// residual stress: 1.3, -0.4 R + 0.9 to R = -0.25, 1 above) and the 60 % rule of EN 1993-1-9
// section 7.2.1; each expected value below is the formula evaluated by hand.
#include <doctest/doctest.h>

#include <flexstress/fatigue/mean_stress.hpp>

namespace test_mean_stress {

using namespace flexstress::fatigue;

TEST_CASE_TEMPLATE("IIW f(R) for stress-relieved details at its defining points", T, float,
                   double) {
  const auto low = IiwResidualStress::low;
  CHECK(iiw_enhancement_factor(T(-3), low) == T(1.6));
  CHECK(iiw_enhancement_factor(T(-1), low) == doctest::Approx(1.6));
  CHECK(iiw_enhancement_factor(T(0), low) == doctest::Approx(1.2));
  CHECK(iiw_enhancement_factor(T(0.5), low) == doctest::Approx(1.0));
  CHECK(iiw_enhancement_factor(T(0.8), low) == T(1));
  // Continuity at the ends of the linear part.
  CHECK(iiw_enhancement_factor(T(-1.0001), low) ==
        doctest::Approx(iiw_enhancement_factor(T(-1), low)).epsilon(1e-4));
  CHECK(iiw_enhancement_factor(T(0.5001), low) ==
        doctest::Approx(iiw_enhancement_factor(T(0.5), low)).epsilon(1e-4));
}

TEST_CASE_TEMPLATE("IIW f(R) for moderate and high residual stress", T, float, double) {
  const auto moderate = IiwResidualStress::moderate;
  CHECK(iiw_enhancement_factor(T(-2), moderate) == T(1.3));
  CHECK(iiw_enhancement_factor(T(-1), moderate) == doctest::Approx(1.3));
  CHECK(iiw_enhancement_factor(T(-0.25), moderate) == doctest::Approx(1.0));
  CHECK(iiw_enhancement_factor(T(0), moderate) == T(1));
  for (T r : {T(-5), T(-1), T(0), T(0.5), T(0.9)})
    CHECK(iiw_enhancement_factor(r, IiwResidualStress::high) == T(1));
}

TEST_CASE_TEMPLATE("f(R) of a cycle uses R = min / max; fully compressive cycles get R < -1", T,
                   float, double) {
  const auto low = IiwResidualStress::low;
  CHECK(iiw_enhancement_factor(Cycle<T>{-100, 100, 1}, low) == doctest::Approx(1.6));  // R = -1
  CHECK(iiw_enhancement_factor(Cycle<T>{0, 100, 1}, low) == doctest::Approx(1.2));     // R = 0
  CHECK(iiw_enhancement_factor(Cycle<T>{100, 50, 1}, low) == doctest::Approx(1.0));    // R = .5
  CHECK(iiw_enhancement_factor(Cycle<T>{-100, -10, 1}, low) == T(1.6));  // compression only
  CHECK(iiw_enhancement_factor(Cycle<T>{0, -100, 1}, low) == T(1.6));    // max = 0
  // corrected_range divides the range by f.
  CHECK(corrected_range(Cycle<T>{0, 120, 1}, MeanStressCorrection::iiw_stress_relieved) ==
        doctest::Approx(100));
  CHECK(corrected_range(Cycle<T>{0, 120, 1}, MeanStressCorrection::none) == T(120));
}

TEST_CASE_TEMPLATE("EN 1993-1-9 7.2.1: tensile part plus 60 % of the compressive part", T, float,
                   double) {
  CHECK(en1993_effective_range(Cycle<T>{10, 110, 1}) == T(100));                 // tensile
  CHECK(en1993_effective_range(Cycle<T>{-110, -10, 1}) == doctest::Approx(60));  // compressive
  CHECK(en1993_effective_range(Cycle<T>{40, -60, 1}) == doctest::Approx(76));    // 40 + 0.6 * 60
  CHECK(corrected_range(Cycle<T>{40, -60, 1}, MeanStressCorrection::en1993_compressive_60pct) ==
        doctest::Approx(76));
}

}  // namespace test_mean_stress
