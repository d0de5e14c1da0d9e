// Palmgren-Miner damage, equivalent range, life; streaming damage against batch damage.
// References: EN 1993-1-9:2005 section 7.1 curve definitions (N = 2e6 (Delta_sigma_C /
// Delta_sigma)^3 above Delta_sigma_D, N = 5e6 (Delta_sigma_D / Delta_sigma)^5 down to
// Delta_sigma_L, none below), written out independently of SnCurve below; section 8 for
// gamma_Ff Delta_sigma_E,2 <= Delta_sigma_C / gamma_Mf; ASTM E1049-85 section 5.4.5 for the
// work-cycle closure.
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <doctest/doctest.h>

#include <flexstress/fatigue/damage.hpp>
#include <flexstress/fatigue/streaming_damage.hpp>

#include "fatigue/fatigue_test_helpers.hpp"

namespace test_damage {

using namespace flexstress;
using namespace flexstress::fatigue;

namespace {
// EN 1993-1-9 direct-stress curve written from its definition, for category c.
double en_cycles(double ds, double c) {
  const double d = c * std::cbrt(0.4);
  const double l = d * std::pow(0.05, 0.2);
  if (ds >= d) return 2e6 * std::pow(c / ds, 3);
  if (ds >= l) return 5e6 * std::pow(d / ds, 5);
  return std::numeric_limits<double>::infinity();
}

template <class T>
DamageModel<T> en_model(T category, DamageOptions<T> options = {}) {
  auto curve = en1993_normal_curve(category);
  REQUIRE(curve.ok());
  auto model = DamageModel<T>::create(*curve, options);
  REQUIRE(model.ok());
  return *model;
}

template <class T>
void check_close(T a, T b, double tol) {
  CHECK(std::abs(double(a) - double(b)) <= tol * std::abs(double(b)));
}
}  // namespace

TEST_CASE("Miner sum of a spectrum on the EN 1993-1-9 curve of category 80") {
  // One work cycle 0 -> 120 -> 70 -> 120 -> 90 -> 120 -> 0 holds, as a repeating history, one
  // cycle of 120 (above Delta_sigma_D = 58.9), one of 50 (between D and L = 32.4) and one of 30
  // (below the cut-off: no damage).
  const std::vector<double> block = {0, 120, 70, 120, 90, 120, 0};
  const auto model = en_model(80.0);
  auto d = damage_per_work_cycle(block, model);
  REQUIRE(d.ok());
  const double expected = 1 / en_cycles(120, 80) + 1 / en_cycles(50, 80);
  check_close(*d, expected, 1e-13);  // the same powers, rounded differently
  CHECK(en_cycles(30, 80) == std::numeric_limits<double>::infinity());
}

TEST_CASE("partial factors, thickness and mean stress enter through the read range") {
  // gamma_Ff = 1.1, gamma_Mf = 1.35 (EN 1993-1-9 Table 3.1, high consequence, safe life),
  // f(t) = 0.8: a range of 100 is read at 100 * 1.1 * 1.35 / 0.8 on the characteristic curve.
  DamageOptions<double> options;
  options.gamma_ff = 1.1;
  options.gamma_mf = 1.35;
  options.thickness_factor = 0.8;
  const auto model = en_model(80.0, options);
  const Cycle<double> c{0, 100, 1};
  check_close(model.effective_range(c), 100 * 1.1 * 1.35 / 0.8, 1e-14);  // a few roundings
  check_close(model.damage(c), 1 / en_cycles(100 * 1.1 * 1.35 / 0.8, 80), 1e-13);
  // IIW stress-relieved detail, R = 0: f(R) = 1.2, so 0 -> 120 counts as a range of 100.
  DamageOptions<double> relieved;
  relieved.mean_stress = MeanStressCorrection::iiw_stress_relieved;
  const auto m2 = en_model(80.0, relieved);
  check_close(m2.damage(Cycle<double>{0, 120, 0.5}), 0.5 / en_cycles(100, 80), 1e-13);
}

TEST_CASE_TEMPLATE("equivalent range at 2e6 and the EN 1993-1-9 section 8 check", T, float,
                   double) {
  // n cycles of a constant range on the m = 3 slope: D = n (ds / c)^3 / 2e6, so the
  // equivalent range at 2e6 cycles is ds (n / 2e6)^(1/3); n = 2e6 gives ds itself.
  for (T n : {T(2e6), T(5e5), T(1e3)}) {
    const T ds = 150;
    DamageOptions<T> options;
    options.gamma_ff = T(1.1);
    options.gamma_mf = T(1.35);
    const auto model = en_model(T(90), options);
    const T d = n * model.damage(Cycle<T>{0, ds, 1});
    auto e = equivalent_stress_range(d, model);
    REQUIRE(e.ok());
    check_close(*e, ds * std::cbrt(n / T(2e6)), sizeof(T) == 4 ? 1e-5 : 1e-12);
    // D <= 1 is the same check as gamma_Ff Delta_sigma_E,2 <= Delta_sigma_C / gamma_Mf.
    check_close(T(1.1) * *e / (T(90) / T(1.35)), std::cbrt(d), sizeof(T) == 4 ? 1e-5 : 1e-12);
  }
}

TEST_CASE("life in work cycles and hours") {
  auto life = predict_life(1e-6, 120.0);
  REQUIRE(life.ok());
  check_close(life->work_cycles, 1e6, 1e-14);         // a few roundings
  check_close(life->hours, 1e6 * 120 / 3600, 1e-14);  // a few roundings
  auto half = predict_life(1e-6, 120.0, 0.5);         // a design Miner sum of 0.5
  REQUIRE(half.ok());
  check_close(half->work_cycles, 5e5, 1e-14);  // a few roundings
  auto none = predict_life(0.0, 10.0);
  REQUIRE(none.ok());
  CHECK(std::isinf(none->work_cycles));
}

TEST_CASE_TEMPLATE("damage per work cycle is the damage of one more repetition", T, float, double) {
  // ASTM E1049-85 5.4.5 closure checked against 5.4.4 on the doubled history: D(x x) - D(x).
  std::mt19937 rng(77);
  const auto model = en_model(T(36));
  for (int trial = 0; trial < 100; ++trial) {
    const auto x = test::random_walk_history<T>(rng, 50 + rng() % 500, -150, 150, 30);
    std::vector<T> xx = x;
    xx.insert(xx.end(), x.begin(), x.end());
    auto once = history_damage(x.data(), x.size(), model);
    auto twice = history_damage(xx.data(), xx.size(), model);
    auto per_cycle = damage_per_work_cycle(x, model);
    REQUIRE(once.ok());
    REQUIRE(twice.ok());
    REQUIRE(per_cycle.ok());
    // Difference of two sums of about the same size: tolerance relative to the larger one.
    CHECK(std::abs(double(*twice - *once - *per_cycle)) <=
          (sizeof(T) == 4 ? 1e-6 : 1e-14) * double(*twice));
  }
}

TEST_CASE_TEMPLATE("streaming damage equals batch damage on the same history", T, float, double) {
  constexpr int N = 64;
  auto grid = ClassGrid<T>::create(T(-200), T(200), N);
  REQUIRE(grid.ok());
  const auto model = en_model(T(71));
  std::mt19937 rng(314);
  for (int trial = 0; trial < 40; ++trial) {
    const int gate = trial % 2;
    auto meter = StreamingDamage<T, N>::create(*grid, gate, model);
    REQUIRE(meter.ok());
    const auto x = test::random_walk_history<T>(rng, 1 + rng() % 20000, -200, 200, 35);
    for (T v : x) REQUIRE(meter->push(v) == StepStatus::ok);
    for (CycleClosure closure : {CycleClosure::half_cycles, CycleClosure::repeating}) {
      auto cycles = count_cycles_classed(x, *grid, gate, closure);
      REQUIRE(cycles.ok());
      check_close(meter->damage(closure), miner_damage(*cycles, model),
                  test::sum_order_tolerance<T>());
    }
    CHECK(meter->closed_damage() <= meter->damage(CycleClosure::half_cycles));
  }
}

TEST_CASE_TEMPLATE("streaming damage does not depend on how the stream is chunked", T, float,
                   double) {
  constexpr int N = 48;
  auto grid = ClassGrid<T>::create(T(-120), T(120), N);
  REQUIRE(grid.ok());
  auto made = StreamingDamage<T, N>::create(*grid, 1, en_model(T(50)));
  REQUIRE(made.ok());
  std::mt19937 rng(12);
  const auto x = test::random_walk_history<T>(rng, 30000, -120, 120, 20);
  auto one_by_one = *made;
  for (T v : x) REQUIRE(one_by_one.push(v) == StepStatus::ok);
  for (int trial = 0; trial < 5; ++trial) {
    auto chunked = *made;
    std::size_t i = 0;
    while (i < x.size()) {
      const std::size_t len = std::min<std::size_t>(x.size() - i, rng() % 700);
      REQUIRE(chunked.push_block(x.data() + i, len) == StepStatus::ok);
      i += len;
    }
    CHECK(chunked.closed_damage() == one_by_one.closed_damage());
    CHECK(chunked.damage(CycleClosure::half_cycles) ==
          one_by_one.damage(CycleClosure::half_cycles));
    CHECK(chunked.damage(CycleClosure::repeating) == one_by_one.damage(CycleClosure::repeating));
  }
}

TEST_CASE("a block with a bad sample is refused whole") {
  constexpr int N = 20;
  auto grid = ClassGrid<double>::create(-100, 100, N);
  REQUIRE(grid.ok());
  auto meter = StreamingDamage<double, N>::create(*grid, 0, en_model(80.0));
  REQUIRE(meter.ok());
  const double first[] = {0, 90, -90, 80, -80};
  REQUIRE(meter->push_block(first, 5) == StepStatus::ok);
  const double before = meter->damage(CycleClosure::half_cycles);
  const auto samples = meter->counter().samples();
  const double with_nan[] = {50, -50, std::numeric_limits<double>::quiet_NaN(), 10};
  CHECK(meter->push_block(with_nan, 4) == StepStatus::invalid_input);
  const double outside[] = {50, -50, 150};
  CHECK(meter->push_block(outside, 3) == StepStatus::capacity_exceeded);
  CHECK(meter->counter().samples() == samples);
  CHECK(meter->damage(CycleClosure::half_cycles) == before);
}

TEST_CASE("bad damage input is rejected with a message naming it") {
  auto curve = en1993_normal_curve(80.0);
  REQUIRE(curve.ok());
  DamageOptions<double> options;
  options.gamma_mf = 0;
  auto model = DamageModel<double>::create(*curve, options);
  REQUIRE_FALSE(model.ok());
  CHECK(model.error().message == "gamma_Mf must be positive, got 0");
  auto life = predict_life(1e-3, 0.0);
  REQUIRE_FALSE(life.ok());
  CHECK(life.error().message == "work cycle duration must be positive, got 0 s");
  const auto good = en_model(80.0);
  auto eq = equivalent_stress_range(-1.0, good);
  REQUIRE_FALSE(eq.ok());
  auto beyond = equivalent_stress_range(0.5, good, 1e9);
  REQUIRE_FALSE(beyond.ok());
  auto empty = history_damage<double>(nullptr, 0, good);
  REQUIRE_FALSE(empty.ok());
  CHECK(empty.error().message == "stress history is empty");
}

}  // namespace test_damage
