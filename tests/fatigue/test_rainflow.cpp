// Batch rainflow (ASTM E1049-85 sections 5.4.4 and 5.4.5): the published example, properties on
// random histories, bad input.
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include <doctest/doctest.h>

#include <flexstress/fatigue/rainflow.hpp>

#include "fatigue/fatigue_test_helpers.hpp"

namespace test_rainflow {

using namespace flexstress;
using namespace flexstress::fatigue;

namespace {
// The example history of ASTM E1049-85, Fig. 6 (rainflow counting) and Fig. 7 (simplified
// rainflow counting for repeating histories), as listed in shared/reference/validation.md.
template <class T>
std::vector<T> astm_example() {
  return {-2, 1, -3, 5, -1, 3, -4, 4, -2};
}

// Total count per range.
template <class T>
std::map<T, T> count_by_range(const std::vector<Cycle<T>>& cycles) {
  std::map<T, T> m;
  for (const auto& c : cycles) m[c.range()] += c.count;
  return m;
}
}  // namespace

TEST_CASE_TEMPLATE("ASTM E1049-85 5.4.4 example gives the published half-cycle table", T, float,
                   double) {
  // Reference: ASTM E1049-85 Fig. 6(f), counts by range: 3 -> 0.5, 4 -> 1.5, 6 -> 0.5,
  // 8 -> 1.0, 9 -> 0.5 (also validation.md).
  auto cycles = rainflow_half_cycles(astm_example<T>());
  REQUIRE(cycles.ok());
  const std::map<T, T> expected = {{3, 0.5}, {4, 1.5}, {6, 0.5}, {8, 1.0}, {9, 0.5}};
  CHECK(count_by_range(*cycles) == expected);
  // The order of events, worked out by hand from the steps of 5.4.4: half cycle -2..1 (step 5),
  // half cycle 1..-3 (step 5), cycle -1..3 (step 4), half cycle -3..5 (step 5), then the
  // residue 5..-4, -4..4, 4..-2 (step 6).
  const std::vector<std::pair<std::pair<T, T>, T>> events = {
      {{-2, 1}, 0.5}, {{1, -3}, 0.5}, {{-1, 3}, 1.0}, {{-3, 5}, 0.5},
      {{5, -4}, 0.5}, {{-4, 4}, 0.5}, {{4, -2}, 0.5}};
  REQUIRE(cycles->size() == events.size());
  for (std::size_t i = 0; i < events.size(); ++i) {
    CHECK((*cycles)[i].from == events[i].first.first);
    CHECK((*cycles)[i].to == events[i].first.second);
    CHECK((*cycles)[i].count == events[i].second);
  }
}

TEST_CASE_TEMPLATE("ASTM E1049-85 5.4.5 example as a repeating block gives the published cycles", T,
                   float, double) {
  // Reference: ASTM E1049-85 Fig. 7, one full cycle each of ranges 3, 4, 7 and 9.
  auto cycles = rainflow_repeating(astm_example<T>());
  REQUIRE(cycles.ok());
  const std::map<T, T> expected = {{3, 1}, {4, 1}, {7, 1}, {9, 1}};
  CHECK(count_by_range(*cycles) == expected);
  for (const auto& c : *cycles) CHECK(c.count == T(1));
  // Means follow from the loops of the rearranged history 5 -1 3 -4 4 -2 1 -3 5:
  // -1..3 (mean 1), -2..1 (-0.5), 4..-3 (0.5), 5..-4 (0.5).
  const auto rows = aggregate_cycles(*cycles);
  REQUIRE(rows.size() == 4);
  CHECK(rows[0].mean == T(-0.5));
  CHECK(rows[1].mean == T(1));
  CHECK(rows[2].mean == T(0.5));
  CHECK(rows[3].mean == T(0.5));
}

TEST_CASE_TEMPLATE("rainflow conserves range content and counts every segment once", T, float,
                   double) {
  // Identity (no external reference needed): a full cycle covers its range twice, a half cycle
  // once, so sum 2 n range = the path length between reversals; open path for a finished
  // history, closed loop for a repeating block. Integer histories make it exact.
  std::mt19937 rng(1049);
  for (int trial = 0; trial < 200; ++trial) {
    const auto x = trial % 2 == 0 ? test::random_integer_history<T>(rng, 1 + rng() % 400, -9, 9)
                                  : test::random_walk_history<T>(rng, 1 + rng() % 400, -60, 60, 9);
    auto r = extract_reversals(x);
    REQUIRE(r.ok());
    auto half = rainflow_half_cycles(*r);
    auto rep = rainflow_repeating(*r);
    REQUIRE(half.ok());
    REQUIRE(rep.ok());
    CHECK(range_content(*half) == test::path_length(*r, false));
    CHECK(range_content(*rep) == test::path_length(*r, true));
    if (!r->empty()) CHECK(T(2) * total_count(*half) == T(r->size() - 1));
  }
}

TEST_CASE_TEMPLATE("shifting a history by a constant shifts means, not ranges or counts", T, float,
                   double) {
  std::mt19937 rng(42);
  for (int trial = 0; trial < 100; ++trial) {
    const auto x = test::random_walk_history<T>(rng, 300, -40, 40, 7);
    const T shift = T(static_cast<int>(rng() % 201) - 100);
    std::vector<T> y = x;
    for (T& v : y) v += shift;
    for (CycleClosure closure : {CycleClosure::half_cycles, CycleClosure::repeating}) {
      auto cx = count_cycles(x, {T(0), closure});
      auto cy = count_cycles(y, {T(0), closure});
      REQUIRE(cx.ok());
      REQUIRE(cy.ok());
      // Compare the (range, mean, count) rows: the repeating closure starts the loop at the
      // value of greatest magnitude, which a shift can move, so the order of cycles may differ.
      const auto rx = aggregate_cycles(*cx);
      const auto ry = aggregate_cycles(*cy);
      REQUIRE(rx.size() == ry.size());
      for (std::size_t i = 0; i < rx.size(); ++i) {
        CHECK(ry[i].range == rx[i].range);
        CHECK(ry[i].count == rx[i].count);
        CHECK(ry[i].mean == rx[i].mean + shift);
      }
    }
  }
}

TEST_CASE_TEMPLATE("a repeating block counts as the increment of one more repetition", T, float,
                   double) {
  // Independent check of ASTM 5.4.5 against 5.4.4: counting the block twice in a row as a
  // finished history, minus counting it once, leaves exactly the cycles of one repetition.
  std::mt19937 rng(5);
  for (int trial = 0; trial < 300; ++trial) {
    const auto x = test::random_integer_history<T>(rng, 2 + rng() % 60, 0, 1 + trial % 6);
    std::vector<T> xx = x;
    xx.insert(xx.end(), x.begin(), x.end());
    auto once = count_cycles(x);
    auto twice = count_cycles(xx);
    auto rep = count_cycles(x, {T(0), CycleClosure::repeating});
    REQUIRE(once.ok());
    REQUIRE(twice.ok());
    REQUIRE(rep.ok());
    std::map<std::pair<T, T>, T> diff;
    for (const auto& row : aggregate_cycles(*twice)) diff[{row.range, row.mean}] += row.count;
    for (const auto& row : aggregate_cycles(*once)) diff[{row.range, row.mean}] -= row.count;
    std::map<std::pair<T, T>, T> expected;
    for (const auto& row : aggregate_cycles(*rep)) expected[{row.range, row.mean}] += row.count;
    for (auto it = diff.begin(); it != diff.end();) it = it->second == T(0) ? diff.erase(it) : ++it;
    CHECK(diff == expected);
  }
}

TEST_CASE("bad reversal sequences are rejected with the point named") {
  auto rising = rainflow_half_cycles(std::vector<double>{0, 1, 2, -1});
  REQUIRE_FALSE(rising.ok());
  CHECK(rising.error().message ==
        "reversal 1 (1) is not a peak or valley: the history keeps rising through it");
  auto repeated = rainflow_repeating(std::vector<double>{0, 1, 1});
  REQUIRE_FALSE(repeated.ok());
  CHECK(repeated.error().message == "reversal 2 (1) repeats reversal 1; reversals must alternate");
  auto nan = rainflow_half_cycles(std::vector<double>{0, std::numeric_limits<double>::quiet_NaN()});
  REQUIRE_FALSE(nan.ok());
  CHECK(nan.error().message == "reversal 1 is NaN");
  auto none = rainflow_half_cycles(std::vector<double>{});
  REQUIRE(none.ok());
  CHECK(none->empty());
  auto empty_history = count_cycles(std::vector<double>{});
  REQUIRE_FALSE(empty_history.ok());
  CHECK(empty_history.error().message == "stress history is empty");
}

TEST_CASE("class-bin batch counting rejects samples outside the window") {
  auto grid = ClassGrid<double>::create(-10, 10, 20);
  REQUIRE(grid.ok());
  auto out = count_cycles_classed(std::vector<double>{0, 5, 10.5, 0}, *grid);
  REQUIRE_FALSE(out.ok());
  CHECK(out.error().message ==
        "stress history: sample 2 (10.5) is outside the class window [-10, 10]");
  auto bad_gate = count_cycles_classed(std::vector<double>{0, 5}, *grid, -1);
  REQUIRE_FALSE(bad_gate.ok());
  auto bad_grid = ClassGrid<double>::create(1, 1, 8);
  REQUIRE_FALSE(bad_grid.ok());
  CHECK(bad_grid.error().message == "class window needs lower < upper, got [1, 1]");
}

}  // namespace test_rainflow
