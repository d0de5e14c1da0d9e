// Point-to-point table laws (TableInterpolation::rest_to_rest): the quintic between rows, its
// rate and acceleration zero at every row, no overshoot; a driver that follows one needs no jolt
// to start, and a checkpoint keeps the interpolation. References: the closed form
// s_i + (s_i+1 - s_i)(10u^3 - 15u^4 + 6u^5) and its derivatives, and Newton's law for a rigid
// bar turned about one end (torque = m L^2 / 3 times the angular acceleration).
#include <algorithm>
#include <cmath>
#include <vector>

#include <doctest/doctest.h>

#include <flexstress/model/all.hpp>

namespace test_motion_laws {

using namespace flexstress;

namespace {

// An elbow's move: hold 0 until 0.3 s, turn to -60 degrees by 1.2 s, hold until 1.6 s.
const std::vector<double> elbow_times{0.0, 0.3, 1.2, 1.6};
const std::vector<double> elbow_angles{0.0, 0.0, -M_PI / 3, -M_PI / 3};

constexpr double bar_mass = 2.0, bar_length = 1.0;

struct DrivenBar {
  Model<double> model;
  JointId drive;
};

/// A rigid bar (2 kg, 1 m) hinged at one end to the ground and turned about z by a revolute
/// driver following `law`; no gravity, so the driver's torque is the bar's inertia alone.
DrivenBar make_driven_bar(const MotionLaw<double>& law) {
  ModelBuilder<double> b;
  const double j_centre = bar_mass * bar_length * bar_length / 12;
  const BodyId bar = b.add_rigid_body("bar", bar_mass, Vector3d::Zero(),
                                      Vector3d(1e-6, j_centre, j_centre).asDiagonal());
  b.set_initial_pose(bar, Vector3d(bar_length / 2, 0, 0));
  const MarkerId pivot = b.add_marker("pivot", b.ground(), -1, Vector3d::Zero());
  const MarkerId end = b.add_marker("end", bar, -1, Vector3d(-bar_length / 2, 0, 0));
  b.add_joint("hinge", JointKind::revolute, pivot, end);
  const JointId drive = b.add_driver("drive", JointKind::revolute_driver, pivot, end, law);
  b.set_gravity(Vector3d::Zero());
  auto m = b.finalize();
  if (!m.ok()) FAIL(m.error().what());
  return {std::move(*m), drive};
}

MotionLaw<double> elbow_law(TableInterpolation interpolation) {
  auto table = TableLaw<double>::create(elbow_times, elbow_angles, interpolation);
  REQUIRE(table.ok());
  return MotionLaw<double>::from_table(std::move(*table));
}

}  // namespace

TEST_CASE("a point-to-point table is the quintic between rows, at rest at every row") {
  const auto law =
      TableLaw<double>::create(elbow_times, elbow_angles, TableInterpolation::rest_to_rest);
  REQUIRE(law.ok());
  CHECK(law->interpolation() == TableInterpolation::rest_to_rest);
  double lowest = 0, highest = -M_PI, peak_acceleration = 0;
  for (std::size_t i = 0; i + 1 < elbow_times.size(); ++i) {
    const double t0 = elbow_times[i], period = elbow_times[i + 1] - t0;
    const double rise = elbow_angles[i + 1] - elbow_angles[i];
    for (int k = 0; k <= 600; ++k) {
      const double u = k / 600.0, t = t0 + period * u;
      const MotionValue<double> m = (*law)(t);
      CHECK(m.value ==
            doctest::Approx(elbow_angles[i] +
                            rise * (10 * std::pow(u, 3) - 15 * std::pow(u, 4) + 6 * std::pow(u, 5)))
                .epsilon(1e-12)
                .scale(1));
      CHECK(
          m.rate ==
          doctest::Approx(rise * 30 * u * u * (1 - u) * (1 - u) / period).epsilon(1e-12).scale(1));
      CHECK(m.acceleration ==
            doctest::Approx(rise * 60 * u * (1 - u) * (1 - 2 * u) / (period * period))
                .epsilon(1e-12)
                .scale(1));
      lowest = std::min(lowest, m.value);
      highest = std::max(highest, m.value);
      if (i == 1) peak_acceleration = std::max(peak_acceleration, std::abs(m.acceleration));
    }
    // At the rows themselves, rate and acceleration are zero (no jump to or from a hold).
    for (const double t : {elbow_times[i], elbow_times[i + 1]}) {
      CHECK((*law)(t).rate == doctest::Approx(0.0).scale(1e-12));
      CHECK((*law)(t).acceleration == doctest::Approx(0.0).scale(1e-12));
    }
  }
  // No overshoot: the motion stays within the rows' values.
  CHECK(highest == 0.0);
  CHECK(lowest == doctest::Approx(-M_PI / 3).epsilon(1e-14));
  // The turn's peak acceleration, 10 / sqrt(3) rise / T^2 (at u = 1/2 -+ sqrt(3) / 6), sampled.
  CHECK(peak_acceleration ==
        doctest::Approx(10 / std::sqrt(3.0) * (M_PI / 3) / (0.9 * 0.9)).epsilon(1e-4));

  // The spline through the same rows passes them without stopping: it swings above the first
  // hold before the turn (the reason for a point-to-point table).
  const auto spline = TableLaw<double>::create(elbow_times, elbow_angles);
  REQUIRE(spline.ok());
  double spline_highest = 0;
  for (int k = 0; k <= 1600; ++k)
    spline_highest = std::max(spline_highest, (*spline)(k * 1e-3).value);
  MESSAGE("the spline's overshoot above the first hold: " << spline_highest << " rad");
  CHECK(spline_highest > 0.01);

  // A jump between close rows is refused for steps that cannot follow it, as a spline's is.
  const auto jump = TableLaw<double>::create({0.0, 1.0, 1.0 + 1e-9, 2.0}, {0.0, 0.0, 0.05, 0.05},
                                             TableInterpolation::rest_to_rest);
  REQUIRE(jump.ok());
  CHECK(jump->row_too_fast(1e-3) == 2);
  CHECK(law->row_too_fast(1e-3) == 0);
}

TEST_CASE("a driver on a point-to-point table turns a bar without a jolt, torque = J alpha") {
  // The bar's torque about the hinge is J theta'' with J = m L^2 / 3; the driver's effort reads
  // it. A step of size h follows the law's acceleration within about J s''' h (the multiplier of
  // an index-3 step lags by a fraction of a step), s''' at most 60 rise / T^3 for the quintic:
  // the torque is checked to twice that, and to converge as h halves. The law starts the turn
  // from zero acceleration, so the torque at its first step is a small part of its peak (a
  // spline's two rows would jump to 6 rise / T^2 there, 1.04 times the quintic's peak).
  const double j_hinge = bar_mass * bar_length * bar_length / 3, rise = M_PI / 3, turn = 0.9;
  const double peak_torque = j_hinge * 10 / std::sqrt(3.0) * rise / (turn * turn);
  const double jerk = 60 * rise / (turn * turn * turn);
  const DrivenBar bar = make_driven_bar(elbow_law(TableInterpolation::rest_to_rest));
  double worst_torque[2] = {0, 0};
  for (const int halvings : {0, 1}) {
    const double h = 1e-3 / (1 << halvings);
    const int steps = static_cast<int>(std::lround(1.6 / h));
    Data<double> d(bar.model);
    d.settings.step = h;
    REQUIRE(initialize(bar.model, d).ok());
    double worst_angle = 0, first_torque = 0;
    for (int i = 0; i < steps; ++i) {
      REQUIRE(step(bar.model, d) == StepStatus::ok);
      const MotionValue<double> prescribed = driver_motion(bar.model, d, bar.drive);
      const auto angle = joint_coordinate(bar.model, d, bar.drive);
      worst_angle = std::max(worst_angle, std::abs(angle.value - prescribed.value));
      const double torque = driver_effort(bar.model, d, bar.drive);
      worst_torque[halvings] =
          std::max(worst_torque[halvings], std::abs(torque - j_hinge * prescribed.acceleration));
      if (first_torque == 0 && d.t > 0.3 + 1e-12) first_torque = torque;  // the turn's first step
    }
    MESSAGE("h " << h << ": angle off the law by " << worst_angle
                 << " rad at most; torque off J alpha by " << worst_torque[halvings]
                 << " N m (J s''' h " << j_hinge * jerk * h << ", peak " << peak_torque
                 << "); first torque of the turn " << first_torque);
    CHECK(worst_angle < 1e-6);
    CHECK(worst_torque[halvings] < 2 * j_hinge * jerk * h);
    CHECK(std::abs(first_torque) < 0.05 * peak_torque);
    CHECK(joint_coordinate(bar.model, d, bar.drive).value == doctest::Approx(-rise).epsilon(1e-9));
  }
  CHECK(worst_torque[1] < 0.6 * worst_torque[0]);
}

TEST_CASE("a checkpoint keeps a point-to-point law swapped in at run time") {
  // The model's law is the spline; the run swaps in the point-to-point table. A Data restored
  // from the checkpoint must continue on the swapped law, bit for bit (a restore that made the
  // law a spline again would turn the bar another way).
  const DrivenBar bar = make_driven_bar(elbow_law(TableInterpolation::spline));
  Data<double> a(bar.model);
  REQUIRE(set_law(bar.model, a, bar.drive, elbow_law(TableInterpolation::rest_to_rest)).ok());
  REQUIRE(initialize(bar.model, a).ok());
  std::vector<unsigned char> bytes;
  for (int i = 0; i < 1600; ++i) {
    if (i == 600) {
      auto saved = save_checkpoint(bar.model, a);
      REQUIRE(saved.ok());
      bytes = *saved;
    }
    REQUIRE(step(bar.model, a) == StepStatus::ok);
  }
  Data<double> b(bar.model);
  REQUIRE(restore_checkpoint(bar.model, b, bytes.data(), bytes.size()).ok());
  // At 0.6 s, within the turn, where the two laws differ.
  CHECK(driver_motion(bar.model, b, bar.drive).acceleration ==
        elbow_law(TableInterpolation::rest_to_rest)(b.t, nullptr).acceleration);
  CHECK(driver_motion(bar.model, b, bar.drive).acceleration !=
        elbow_law(TableInterpolation::spline)(b.t, nullptr).acceleration);
  for (int i = 600; i < 1600; ++i) REQUIRE(step(bar.model, b) == StepStatus::ok);
  CHECK(b.t == a.t);
  CHECK(b.q == a.q);
  CHECK(b.v == a.v);
  CHECK(b.lambda == a.lambda);
}

}  // namespace test_motion_laws
