// Streaming class-bin rainflow: the ASTM example, streaming == batch within the class-bin rule,
// the residue bound 2N - 1, refused samples leave the counter unchanged.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <vector>

#include <doctest/doctest.h>

#include <flexstress/fatigue/rainflow.hpp>
#include <flexstress/fatigue/streaming_rainflow.hpp>

#include "fatigue/fatigue_test_helpers.hpp"

namespace test_streaming_rainflow {

using namespace flexstress;
using namespace flexstress::fatigue;

namespace {

// Streams x through a fresh counter; returns closed cycles plus the closure cycles.
template <class T, int N>
std::vector<Cycle<T>> stream_count(StreamingRainflow<T, N> counter, const std::vector<T>& x,
                                   CycleClosure closure) {
  std::vector<Cycle<T>> cycles;
  auto sink = [&cycles](const Cycle<T>& c) { cycles.push_back(c); };
  for (T v : x) REQUIRE(counter.push(v, sink) == StepStatus::ok);
  if (closure == CycleClosure::repeating) {
    counter.visit_repeating_closure(sink);
  } else {
    counter.visit_half_cycle_closure(sink);
  }
  return cycles;
}

template <class T>
std::map<T, T> count_by_range(const std::vector<Cycle<T>>& cycles) {
  std::map<T, T> m;
  for (const auto& c : cycles) m[c.range()] += c.count;
  return m;
}

}  // namespace

TEST_CASE_TEMPLATE("streaming counter reproduces the ASTM E1049-85 example", T, float, double) {
  // Classes of width 1 centred on the integers -10..10, so the example is not quantized.
  // References: ASTM E1049-85 Fig. 6 (half-cycle table 3: 0.5, 4: 1.5, 6: 0.5, 8: 1, 9: 0.5)
  // and Fig. 7 (repeating: one cycle each of 3, 4, 7, 9), as in validation.md.
  auto grid = ClassGrid<T>::create(T(-10.5), T(10.5), 21);
  REQUIRE(grid.ok());
  auto counter = StreamingRainflow<T, 21>::create(*grid);
  REQUIRE(counter.ok());
  const std::vector<T> x = {-2, 1, -3, 5, -1, 3, -4, 4, -2};
  const std::map<T, T> half = {{3, 0.5}, {4, 1.5}, {6, 0.5}, {8, 1.0}, {9, 0.5}};
  const std::map<T, T> rep = {{3, 1}, {4, 1}, {7, 1}, {9, 1}};
  CHECK(count_by_range(stream_count(*counter, x, CycleClosure::half_cycles)) == half);
  CHECK(count_by_range(stream_count(*counter, x, CycleClosure::repeating)) == rep);
}

TEST_CASE_TEMPLATE("streaming equals batch class-bin counting on random histories", T, float,
                   double) {
  // The documented capacity rule: on the same grid and gate, StreamingRainflow and
  // count_cycles_classed (ASTM E1049-85 5.4.4 / 5.4.5 on class indices) give the same
  // (range, mean, count) rows, for both closures.
  constexpr int N = 32;
  auto grid = ClassGrid<T>::create(T(-160), T(160), N);
  REQUIRE(grid.ok());
  std::mt19937 rng(2718);
  for (int trial = 0; trial < 120; ++trial) {
    const int gate = trial % 3;
    auto counter = StreamingRainflow<T, N>::create(*grid, gate);
    REQUIRE(counter.ok());
    const std::size_t n = 1 + rng() % 3000;
    const auto x = trial % 2 == 0 ? test::random_walk_history<T>(rng, n, -160, 160, 25)
                                  : test::random_integer_history<T>(rng, n, -160, 160);
    for (CycleClosure closure : {CycleClosure::half_cycles, CycleClosure::repeating}) {
      auto batch = count_cycles_classed(x, *grid, gate, closure);
      REQUIRE(batch.ok());
      test::check_same_rows(stream_count(*counter, x, closure), *batch);
    }
  }
}

TEST_CASE("the residue never exceeds 2N - 1 reversals, however long the history") {
  // Bound of the class-bin rule (streaming_rainflow.hpp): ranges in the residue rise strictly
  // then fall strictly, and on N classes they are integers 1..N-1.
  constexpr int N = 16;
  auto grid = ClassGrid<double>::create(0, 16, N);
  REQUIRE(grid.ok());
  auto counter = StreamingRainflow<double, N>::create(*grid);
  REQUIRE(counter.ok());
  // Worst case: an oscillation that grows from the middle to the full window, then decays back:
  // every reversal stays in the residue.
  std::vector<double> x;
  for (int a = 0; a < N / 2; ++a) {
    x.push_back(7.5 - a);
    x.push_back(8.5 + a);
  }
  for (int a = N / 2 - 2; a >= 0; --a) {
    x.push_back(7.5 - a);
    x.push_back(8.5 + a);
  }
  int largest = 0;
  for (double v : x) {
    REQUIRE(counter->push(v) == StepStatus::ok);
    largest = std::max(largest, counter->residue_size());
  }
  CHECK(largest <= 2 * N - 1);
  CHECK(largest >= 2 * N - 3);  // the bound is nearly reached: it is the real limit
  // Random histories of a million samples stay within it too.
  std::mt19937 rng(99);
  counter->reset();
  largest = 0;
  int refused = 0;
  for (int i = 0; i < 1000000; ++i) {
    refused += counter->push(double(rng() % 1600) / 100.0) != StepStatus::ok;
    largest = std::max(largest, counter->residue_size());
  }
  CHECK(refused == 0);
  CHECK(largest <= 2 * N - 1);
}

TEST_CASE_TEMPLATE("refused samples leave the counter unchanged", T, float, double) {
  constexpr int N = 40;
  auto grid = ClassGrid<T>::create(T(-100), T(100), N);
  REQUIRE(grid.ok());
  auto made = StreamingRainflow<T, N>::create(*grid, 1);
  REQUIRE(made.ok());
  std::mt19937 rng(3);
  const auto x = test::random_walk_history<T>(rng, 2000, -100, 100, 20);
  StreamingRainflow<T, N> clean = *made;
  StreamingRainflow<T, N> dirty = *made;
  std::vector<Cycle<T>> clean_cycles, dirty_cycles;
  auto clean_sink = [&](const Cycle<T>& c) { clean_cycles.push_back(c); };
  auto dirty_sink = [&](const Cycle<T>& c) { dirty_cycles.push_back(c); };
  const T bad[] = {std::numeric_limits<T>::quiet_NaN(), std::numeric_limits<T>::infinity(),
                   -std::numeric_limits<T>::infinity(), T(100.5), T(-250)};
  for (std::size_t i = 0; i < x.size(); ++i) {
    REQUIRE(clean.push(x[i], clean_sink) == StepStatus::ok);
    REQUIRE(dirty.push(x[i], dirty_sink) == StepStatus::ok);
    if (i % 97 == 0) {
      const T b = bad[i % 5];
      const int size = dirty.residue_size();
      const auto samples = dirty.samples();
      const StepStatus s = dirty.push(b, dirty_sink);
      CHECK(s == (std::isfinite(b) ? StepStatus::capacity_exceeded : StepStatus::invalid_input));
      CHECK(dirty.residue_size() == size);
      CHECK(dirty.samples() == samples);
    }
  }
  CHECK(dirty.closed_cycles() == clean.closed_cycles());
  clean.visit_half_cycle_closure(clean_sink);
  dirty.visit_half_cycle_closure(dirty_sink);
  REQUIRE(clean_cycles.size() == dirty_cycles.size());
  for (std::size_t i = 0; i < clean_cycles.size(); ++i) {
    CHECK(clean_cycles[i].from == dirty_cycles[i].from);
    CHECK(clean_cycles[i].to == dirty_cycles[i].to);
    CHECK(clean_cycles[i].count == dirty_cycles[i].count);
  }
}

TEST_CASE("closure queries do not change the counter") {
  constexpr int N = 24;
  auto grid = ClassGrid<double>::create(-12, 12, N);
  REQUIRE(grid.ok());
  auto a = StreamingRainflow<double, N>::create(*grid);
  REQUIRE(a.ok());
  auto b = *a;
  std::mt19937 rng(11);
  const auto x = test::random_integer_history<double>(rng, 500, -12, 12);
  std::vector<Cycle<double>> ca, cb;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const StepStatus sa = a->push(x[i], [&](const Cycle<double>& c) { ca.push_back(c); });
    const StepStatus sb = b.push(x[i], [&](const Cycle<double>& c) { cb.push_back(c); });
    REQUIRE(sa == StepStatus::ok);
    REQUIRE(sb == StepStatus::ok);
    if (i % 13 == 0) {  // query a in the middle of the stream; b is never queried
      a->visit_repeating_closure([](const Cycle<double>&) {});
      a->visit_half_cycle_closure([](const Cycle<double>&) {});
    }
  }
  CHECK(ca.size() == cb.size());
  CHECK(a->residue_size() == b.residue_size());
  for (int i = 0; i < a->residue_size(); ++i) CHECK(a->residue(i) == b.residue(i));
}

TEST_CASE("streaming counter setup errors") {
  auto grid = ClassGrid<double>::create(-1, 1, 10);
  REQUIRE(grid.ok());
  auto wrong_size = StreamingRainflow<double, 16>::create(*grid);
  REQUIRE_FALSE(wrong_size.ok());
  CHECK(wrong_size.error().code == ErrorCode::size_mismatch);
  CHECK(wrong_size.error().message ==
        "class grid has 10 classes, the streaming counter was compiled for 16");
  auto bad_gate = StreamingRainflow<double, 10>::create(*grid, 10);
  REQUIRE_FALSE(bad_gate.ok());
  CHECK(bad_gate.error().message == "class gate must be in [0, 9], got 10");
}

}  // namespace test_streaming_rainflow
