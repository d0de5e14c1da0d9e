// Damage along a weld-toe line and its critical hot spot. Reference: on the m = 3 part of an IIW
// FAT curve (IIW-2259-15 chapter 3) damage scales with the cube of the stress, so hot spots
// whose histories are multiples a_j of one history have damages in the ratio a_j^3.
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <doctest/doctest.h>
#include <Eigen/Core>

#include <flexstress/fatigue/weld_line.hpp>

#include "fatigue/fatigue_test_helpers.hpp"

namespace test_weld_line {

using namespace flexstress;
using namespace flexstress::fatigue;

namespace {
DamageModel<double> iiw_model(double fat) {
  auto curve = iiw_normal_curve(fat);
  REQUIRE(curve.ok());
  auto model = DamageModel<double>::create(*curve);
  REQUIRE(model.ok());
  return *model;
}
}  // namespace

TEST_CASE("batch weld line: damages scale with the cube of the stress, critical spot found") {
  // Base history alternating between peaks in [150, 300] and valleys in [-300, -150]: every
  // range is at least 300, so scaled by 0.5 it still lies above the FAT 90 knee (52.6 MPa).
  std::mt19937 rng(6);
  const Eigen::Index samples = 400;
  Eigen::VectorXd base(samples);
  for (Eigen::Index i = 0; i < samples; ++i)
    base(i) = (i % 2 == 0 ? 1.0 : -1.0) * (150.0 + double(rng() % 151));
  const std::vector<double> a = {0.5, 0.8, 1.0, 0.9, 0.6};
  Eigen::MatrixXd histories(samples, Eigen::Index(a.size()));
  for (std::size_t j = 0; j < a.size(); ++j) histories.col(Eigen::Index(j)) = a[j] * base;
  const auto model = iiw_model(90);
  auto line = weld_line_damage<double>(histories, model, {0.0, CycleClosure::repeating});
  REQUIRE(line.ok());
  CHECK(line->critical.index == 2);
  CHECK(line->critical.damage == line->damage(2));
  for (std::size_t j = 0; j < a.size(); ++j)
    CHECK(std::abs(line->damage(Eigen::Index(j)) / line->damage(2) - std::pow(a[j], 3)) <= 1e-13);
}

TEST_CASE("streaming weld line equals the batch line on the same class grid") {
  constexpr int N = 64;
  auto grid = ClassGrid<double>::create(-320, 320, N);
  REQUIRE(grid.ok());
  const auto model = iiw_model(71);
  const Eigen::Index spots = 7, samples = 5000;
  std::mt19937 rng(21);
  Eigen::MatrixXd histories(samples, spots);
  for (Eigen::Index j = 0; j < spots; ++j) {
    const auto h =
        test::random_walk_history<double>(rng, std::size_t(samples), -300, 300, 25 + 5 * int(j));
    for (Eigen::Index i = 0; i < samples; ++i) histories(i, j) = h[std::size_t(i)];
  }
  auto line = StreamingWeldLine<double, N>::create(spots, *grid, 1, model);
  REQUIRE(line.ok());
  for (Eigen::Index i = 0; i < samples; ++i)
    REQUIRE(line->push(histories.row(i)) == StepStatus::ok);
  // Batch per hot spot with the class-bin twin of the streaming counter.
  Eigen::VectorXd batch(spots);
  for (Eigen::Index j = 0; j < spots; ++j) {
    auto cycles = count_cycles_classed(histories.col(j).data(), std::size_t(samples), *grid, 1,
                                       CycleClosure::repeating);
    REQUIRE(cycles.ok());
    batch(j) = miner_damage(*cycles, model);
  }
  Eigen::Index expected = 0;
  batch.maxCoeff(&expected);
  const auto critical = line->critical(CycleClosure::repeating);
  CHECK(critical.index == expected);
  CHECK(std::abs(critical.damage - batch(expected)) <= 1e-14 * batch(expected));
  CHECK(line->critical_closed().damage <= critical.damage);
}

TEST_CASE("weld line bad input") {
  const auto model = iiw_model(90);
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(30, 4);
  h(17, 3) = std::numeric_limits<double>::quiet_NaN();
  auto line = weld_line_damage<double>(h, model);
  REQUIRE_FALSE(line.ok());
  CHECK(line.error().message == "hot spot 3: stress history: sample 17 is NaN");
  auto none = weld_line_damage<double>(Eigen::MatrixXd(10, 0), model);
  REQUIRE_FALSE(none.ok());
  auto grid = ClassGrid<double>::create(-100, 100, 16);
  REQUIRE(grid.ok());
  auto zero = StreamingWeldLine<double, 16>::create(0, *grid, 0, model);
  REQUIRE_FALSE(zero.ok());
  // A step with one bad stress changes no hot spot.
  auto stream = StreamingWeldLine<double, 16>::create(3, *grid, 0, model);
  REQUIRE(stream.ok());
  REQUIRE(stream->push(Eigen::Vector3d(10, 20, 30)) == StepStatus::ok);
  REQUIRE(stream->push(Eigen::Vector3d(-10, -20, -30)) == StepStatus::ok);
  const double before = stream->meter(0).damage(CycleClosure::half_cycles);
  CHECK(stream->push(Eigen::Vector3d(90, std::numeric_limits<double>::infinity(), 0)) ==
        StepStatus::invalid_input);
  CHECK(stream->push(Eigen::Vector3d(90, 0, 101)) == StepStatus::capacity_exceeded);
  CHECK(stream->meter(0).counter().samples() == 2);
  CHECK(stream->meter(0).damage(CycleClosure::half_cycles) == before);
}

}  // namespace test_weld_line
