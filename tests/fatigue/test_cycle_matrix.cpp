// Range-mean and from-to matrices with user bins. Reference cells: the ASTM E1049-85 Fig. 6
// example cycles (from test_rainflow.cpp), binned by hand in the comments below.
#include <limits>
#include <random>
#include <vector>

#include <doctest/doctest.h>

#include <flexstress/fatigue/cycle_matrix.hpp>
#include <flexstress/fatigue/rainflow.hpp>
#include <flexstress/fatigue/streaming_rainflow.hpp>

#include "fatigue/fatigue_test_helpers.hpp"

namespace test_cycle_matrix {

using namespace flexstress;
using namespace flexstress::fatigue;

TEST_CASE_TEMPLATE("bins are left-closed, the last bin also holds its upper edge", T, float,
                   double) {
  auto bins = Bins<T>::from_edges({0, 1, 2.5, 4});
  REQUIRE(bins.ok());
  CHECK(bins->size() == 3);
  CHECK(bins->find(T(0)) == 0);
  CHECK(bins->find(T(0.99)) == 0);
  CHECK(bins->find(T(1)) == 1);
  CHECK(bins->find(T(2.5)) == 2);
  CHECK(bins->find(T(4)) == 2);
  CHECK(bins->find(T(-0.01)) == -1);
  CHECK(bins->find(T(4.01)) == -1);
  CHECK(bins->find(std::numeric_limits<T>::quiet_NaN()) == -1);
  CHECK(bins->center(1) == T(1.75));
}

TEST_CASE_TEMPLATE("range-mean matrix of the ASTM example", T, float, double) {
  auto cycles = rainflow_half_cycles(std::vector<T>{-2, 1, -3, 5, -1, 3, -4, 4, -2});
  REQUIRE(cycles.ok());
  auto range_bins = Bins<T>::from_edges({0, 2, 4, 6, 8, 10});
  auto mean_bins = Bins<T>::from_edges({-2, -1, 0, 1, 2});
  REQUIRE(range_bins.ok());
  REQUIRE(mean_bins.ok());
  const auto m = range_mean_matrix(*cycles, *range_bins, *mean_bins);
  // Cycles (range, mean, count): (3, -0.5, .5) (4, -1, .5) (4, 1, 1) (8, 1, .5) (9, .5, .5)
  // (8, 0, .5) (6, 1, .5). Range bin of 3 is 1, of 4 is 2, of 6 is 3, of 8 and 9 is 4; mean bin
  // of -1 and -0.5 is 1, of 0 and 0.5 is 2, of 1 is 3.
  typename RangeMeanMatrix<T>::Matrix expected = RangeMeanMatrix<T>::Matrix::Zero(5, 4);
  expected(1, 1) = T(0.5);
  expected(2, 1) = T(0.5);
  expected(2, 3) = T(1);
  expected(3, 3) = T(0.5);
  expected(4, 2) = T(1);
  expected(4, 3) = T(0.5);
  CHECK(m.counts() == expected);
  CHECK(m.unbinned() == T(0));
  CHECK(m.total() == total_count(*cycles));
}

TEST_CASE_TEMPLATE("from-to matrix keeps the direction of each cycle", T, float, double) {
  auto cycles = rainflow_half_cycles(std::vector<T>{-2, 1, -3, 5, -1, 3, -4, 4, -2});
  REQUIRE(cycles.ok());
  auto bins = Bins<T>::uniform(T(-5), T(5), 10);  // bin k holds [k - 5, k - 4)
  REQUIRE(bins.ok());
  const auto m = from_to_matrix(*cycles, *bins);
  // Rising cycles -2->1 (.5), -1->3 (1), -3->5 (.5), -4->4 (.5) lie above the diagonal;
  // falling ones 1->-3 (.5), 5->-4 (.5), 4->-2 (.5) below it. 5 is the upper edge: last bin.
  CHECK(m.counts()(3, 6) == T(0.5));
  CHECK(m.counts()(4, 8) == T(1));
  CHECK(m.counts()(2, 9) == T(0.5));
  CHECK(m.counts()(1, 9) == T(0.5));
  CHECK(m.counts()(6, 2) == T(0.5));
  CHECK(m.counts()(9, 1) == T(0.5));
  CHECK(m.counts()(9, 3) == T(0.5));
  T upper = 0, lower = 0;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) (j > i ? upper : lower) += m.counts()(i, j);
  CHECK(upper == T(2.5));
  CHECK(lower == T(1.5));
}

TEST_CASE("cycles outside the bins are counted as unbinned, not lost") {
  auto cycles = rainflow_half_cycles(std::vector<double>{-2, 1, -3, 5, -1, 3, -4, 4, -2});
  REQUIRE(cycles.ok());
  auto range_bins = Bins<double>::from_edges({0, 4, 8});  // range 9 is outside
  auto mean_bins = Bins<double>::from_edges({-1, 1});
  REQUIRE(range_bins.ok());
  REQUIRE(mean_bins.ok());
  const auto m = range_mean_matrix(*cycles, *range_bins, *mean_bins);
  CHECK(m.unbinned() == 0.5);  // the half cycle 5 -> -4
  // Range bin 0 = [0, 4): the range-3 half cycle. Range bin 1 = [4, 8], upper edge included:
  // ranges 4 (.5 + 1), 6 (.5) and 8 (.5 + .5). The single mean bin [-1, 1] holds every mean.
  CHECK(m.counts()(0, 0) == 0.5);
  CHECK(m.counts()(1, 0) == 3.0);
  CHECK(m.total() == total_count(*cycles));
}

TEST_CASE("a cycle matrix is a sink of the streaming counter") {
  // Streaming into a matrix equals binning the batch class-bin cycles (capacity rule of
  // streaming_rainflow.hpp).
  constexpr int N = 50;
  auto grid = ClassGrid<double>::create(-250, 250, N);
  REQUIRE(grid.ok());
  auto counter = StreamingRainflow<double, N>::create(*grid);
  REQUIRE(counter.ok());
  auto range_bins = Bins<double>::uniform(0, 500, 25);
  auto mean_bins = Bins<double>::uniform(-250, 250, 25);
  REQUIRE(range_bins.ok());
  REQUIRE(mean_bins.ok());
  auto streamed = RangeMeanMatrix<double>::create(*range_bins, *mean_bins);
  std::mt19937 rng(8);
  const auto x = test::random_walk_history<double>(rng, 20000, -250, 250, 40);
  for (double v : x) REQUIRE(counter->push(v, streamed) == StepStatus::ok);
  counter->visit_half_cycle_closure(streamed);
  auto batch = count_cycles_classed(x, *grid);
  REQUIRE(batch.ok());
  const auto expected = range_mean_matrix(*batch, *range_bins, *mean_bins);
  CHECK(streamed.counts() == expected.counts());
  CHECK(streamed.unbinned() == expected.unbinned());
}

TEST_CASE("bad bins are rejected with the edge named") {
  auto few = Bins<double>::from_edges({1});
  REQUIRE_FALSE(few.ok());
  CHECK(few.error().message == "bins need at least 2 edges, got 1");
  auto unsorted = Bins<double>::from_edges({0, 2, 2});
  REQUIRE_FALSE(unsorted.ok());
  CHECK(unsorted.error().message == "bin edge 2 (2) must be greater than edge 1 (2)");
  auto nan = Bins<double>::from_edges({0, std::numeric_limits<double>::quiet_NaN()});
  REQUIRE_FALSE(nan.ok());
  CHECK(nan.error().message == "bin edge 1 is not finite");
  auto none = Bins<double>::uniform(0, 1, 0);
  REQUIRE_FALSE(none.ok());
}

}  // namespace test_cycle_matrix
