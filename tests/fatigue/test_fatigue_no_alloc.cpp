// The streaming (per-sample) path allocates nothing: a counting global operator new
// (tests/support/counting_new.hpp). Eigen allocates through malloc, not operator new, but the
// streaming path creates no Eigen object at run time (fixed-size arrays only).
#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <limits>
#include <new>
#include <random>
#include <vector>

#include <doctest/doctest.h>
#include <Eigen/Core>

#include <flexstress/fatigue/cycle_matrix.hpp>
#include <flexstress/fatigue/streaming_damage.hpp>
#include <flexstress/fatigue/weld_line.hpp>

#include "fatigue/fatigue_test_helpers.hpp"

#include "support/counting_new.hpp"

namespace test_fatigue_no_alloc {

using flexstress::testing::g_allocations;
using namespace flexstress;
using namespace flexstress::fatigue;

TEST_CASE("the counting operator new sees allocations") {
  const long long before = g_allocations.load();
  std::vector<int>* v = new std::vector<int>(100);
  const long long after = g_allocations.load();
  delete v;
  CHECK(after - before >= 2);  // the vector object and its buffer
}

TEST_CASE_TEMPLATE("streaming rainflow + damage allocates nothing per sample", T, float, double) {
  constexpr int N = 128;
  auto grid = ClassGrid<T>::create(T(-400), T(400), N);
  REQUIRE(grid.ok());
  auto curve = en1993_normal_curve(T(71));
  REQUIRE(curve.ok());
  DamageOptions<T> options;
  options.mean_stress = MeanStressCorrection::iiw_stress_relieved;
  auto model = DamageModel<T>::create(*curve, options);
  REQUIRE(model.ok());
  auto meter = StreamingDamage<T, N>::create(*grid, 1, *model);
  REQUIRE(meter.ok());
  auto range_bins = Bins<T>::uniform(T(0), T(800), 40);
  auto mean_bins = Bins<T>::uniform(T(-400), T(400), 40);
  REQUIRE(range_bins.ok());
  REQUIRE(mean_bins.ok());
  auto matrix = RangeMeanMatrix<T>::create(*range_bins, *mean_bins);
  auto counter = StreamingRainflow<T, N>::create(*grid, 0);
  REQUIRE(counter.ok());
  std::mt19937 rng(1);
  const auto x = test::random_walk_history<T>(rng, 200000, -400, 400, 60);
  const T bad[] = {std::numeric_limits<T>::quiet_NaN(), T(1000)};

  const long long before = g_allocations.load();
  T live = 0;
  int refused = 0;
  int bad_accepted = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    refused += meter->push(x[i]) != StepStatus::ok;
    refused += counter->push(x[i], matrix) != StepStatus::ok;
    if (i % 1000 == 0) {
      // Refused samples, closure queries and block pushes stay allocation-free too.
      bad_accepted += meter->push(bad[(i / 1000) % 2]) == StepStatus::ok;
      live += meter->damage(CycleClosure::half_cycles) + meter->damage(CycleClosure::repeating);
      counter->visit_repeating_closure(matrix);
    }
  }
  refused += meter->push_block(x.data(), 1000) != StepStatus::ok;
  const long long after = g_allocations.load();

  CHECK(after - before == 0);
  CHECK(refused == 0);
  CHECK(bad_accepted == 0);
  CHECK(live > T(0));
  CHECK(matrix.total() > T(0));
}

TEST_CASE("streaming weld line allocates nothing per step") {
  constexpr int N = 64;
  auto grid = ClassGrid<double>::create(-300, 300, N);
  REQUIRE(grid.ok());
  auto curve = iiw_normal_curve(90.0);
  REQUIRE(curve.ok());
  auto model = DamageModel<double>::create(*curve);
  REQUIRE(model.ok());
  auto line = StreamingWeldLine<double, N>::create(12, *grid, 1, *model);
  REQUIRE(line.ok());
  std::mt19937 rng(2);
  Eigen::Matrix<double, 12, 1> stresses = Eigen::Matrix<double, 12, 1>::Zero();
  const long long before = g_allocations.load();
  int refused = 0;
  for (int i = 0; i < 50000; ++i) {
    for (int j = 0; j < 12; ++j) stresses(j) = double(int(rng() % 501) - 250);
    refused += line->push(stresses) != StepStatus::ok;
    if (i % 500 == 0) static_cast<void>(line->critical(CycleClosure::repeating));
  }
  const auto critical = line->critical_closed();
  const long long after = g_allocations.load();
  CHECK(after - before == 0);
  CHECK(refused == 0);
  CHECK(critical.damage > 0);
}

}  // namespace test_fatigue_no_alloc
