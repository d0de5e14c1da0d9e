// Reversal extraction: peaks and valleys, plateaus, the hysteresis gate, bad input.
// Reference values are read off the test histories by hand (a reversal is where the direction
// changes, ASTM E1049-85 section 3); the gate rule is the one stated in reversals.hpp.
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include <flexstress/fatigue/reversals.hpp>

#include "fatigue/fatigue_test_helpers.hpp"

namespace test_reversals {

using namespace flexstress;
using namespace flexstress::fatigue;

TEST_CASE_TEMPLATE("reversals keep peaks and valleys, drop intermediate points and plateaus", T,
                   float, double) {
  // 0 rises through 1 to 3 (peak), plateau at 3, falls to -2 (valley), rises to 4 (end).
  const std::vector<T> x = {0, 1, 3, 3, 3, 2, -2, -2, 1, 4};
  auto r = extract_reversals(x);
  REQUIRE(r.ok());
  CHECK(*r == std::vector<T>{0, 3, -2, 4});
}

TEST_CASE_TEMPLATE("a history that starts on a plateau or never moves", T, float, double) {
  auto flat_start = extract_reversals(std::vector<T>{5, 5, 5, 7, 6});
  REQUIRE(flat_start.ok());
  CHECK(*flat_start == std::vector<T>{5, 7, 6});
  auto constant = extract_reversals(std::vector<T>{2, 2, 2});
  REQUIRE(constant.ok());
  CHECK(constant->empty());  // no reversals, hence no cycles
  auto single = extract_reversals(std::vector<T>{1});
  REQUIRE(single.ok());
  CHECK(single->empty());
}

TEST_CASE_TEMPLATE("the hysteresis gate removes ranges up to the gate and keeps larger ones", T,
                   float, double) {
  // Small wiggles of 0.5 around a big cycle 0 -> 10 -> 0 vanish with a gate of 1; the reversal
  // values that remain are the true extremes (10 and 0), not shifted by the gate.
  const std::vector<T> x = {0, 0.5, 0.25, 4, 3.5, 10, 9.5, 9.75, 5, 5.5, 0};
  auto gated = extract_reversals(x, T(1));
  REQUIRE(gated.ok());
  CHECK(*gated == std::vector<T>{0, 10, 0});
  auto plain = extract_reversals(x);
  REQUIRE(plain.ok());
  CHECK(*plain == std::vector<T>{0, 0.5, 0.25, 4, 3.5, 10, 9.5, 9.75, 5, 5.5, 0});
  // A range equal to the gate is removed (the rule is "more than the gate").
  auto equal = extract_reversals(std::vector<T>{0, 1, 0, 3}, T(1));
  REQUIRE(equal.ok());
  CHECK(*equal == std::vector<T>{0, 3});
}

TEST_CASE_TEMPLATE("gated reversals are more than the gate apart (random histories)", T, float,
                   double) {
  std::mt19937 rng(20240601);
  for (int trial = 0; trial < 50; ++trial) {
    const auto x = test::random_walk_history<T>(rng, 500, -50, 50, 6);
    const T gate = T(trial % 7);
    auto r = extract_reversals(x, gate);
    REQUIRE(r.ok());
    for (std::size_t i = 0; i + 1 < r->size(); ++i) {
      CHECK(std::abs((*r)[i + 1] - (*r)[i]) > gate);
      if (i + 2 < r->size())  // strictly alternating
        CHECK(((*r)[i + 1] > (*r)[i]) != ((*r)[i + 2] > (*r)[i + 1]));
    }
  }
}

TEST_CASE("streaming filter and batch extraction agree sample by sample") {
  std::mt19937 rng(7);
  const auto x = test::random_integer_history<double>(rng, 1000, -20, 20);
  ReversalFilter<double> filter(2.0);
  std::vector<double> streamed;
  for (double v : x) filter.push(v, [&](double r) { streamed.push_back(r); });
  filter.finish([&](double r) { streamed.push_back(r); });
  auto batch = extract_reversals(x, 2.0);
  REQUIRE(batch.ok());
  CHECK(streamed == *batch);
}

TEST_CASE("bad input to extract_reversals names what and where") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  auto with_nan = extract_reversals(std::vector<double>{0, 1, nan, 2});
  REQUIRE_FALSE(with_nan.ok());
  CHECK(with_nan.error().code == ErrorCode::invalid_argument);
  CHECK(with_nan.error().message == "stress history: sample 2 is NaN");
  auto with_inf = extract_reversals(std::vector<double>{0, -inf});
  REQUIRE_FALSE(with_inf.ok());
  CHECK(with_inf.error().message == "stress history: sample 1 is -inf");
  auto empty = extract_reversals(std::vector<double>{});
  REQUIRE_FALSE(empty.ok());
  CHECK(empty.error().message == "stress history is empty");
  auto bad_gate = extract_reversals(std::vector<double>{0, 1}, -1.0);
  REQUIRE_FALSE(bad_gate.ok());
  CHECK(bad_gate.error().message == "hysteresis gate must be finite and >= 0, got -1");
}

}  // namespace test_reversals
