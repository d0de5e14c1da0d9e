// A moving ground (ModelBuilder::set_ground_motion). References: a pendulum whose pivot
// accelerates upward at a swings as under gravity g + a (d'Alembert: in the pivot's frame the
// inertial force -m a adds to the weight), its small-amplitude period
// T = 2 pi sqrt(I_pivot / (m (g + a) L)) (1 + theta0^2 / 16); and a body welded to a ground that
// turns at a constant rate w about z at radius r follows the circle, turns with w and is held
// by the centripetal force m w^2 r.
#include <cmath>
#include <vector>

#include <doctest/doctest.h>

#include <flexstress/model/all.hpp>

namespace test_ground_motion {

using namespace flexstress;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kG = 9.81, kLength = 1.0, kMass = 1.0, kInertia = 1e-6, kTheta0 = 0.05;

// The period of the pendulum (from its upward zero crossings over `duration`) with its pivot on
// a ground that accelerates upward at `a`.
double pendulum_period(double a, double duration) {
  ModelBuilder<double> b;
  const BodyId bob =
      b.add_rigid_body("bob", kMass, Vector3d::Zero(), Matrix3d::Identity() * kInertia);
  b.set_initial_pose(bob, Vector3d(kLength * std::sin(kTheta0), -kLength * std::cos(kTheta0), 0),
                     from_axis_angle<double>(Vector3d::UnitZ(), kTheta0));
  b.add_joint("pivot", JointKind::revolute, b.add_marker("pivot", b.ground(), -1),
              b.add_marker("rod end", bob, -1, Vector3d(0, kLength, 0)));
  b.set_gravity(Vector3d(0, -kG, 0));
  using Law = MotionLaw<double>;
  if (a != 0.0)
    b.set_ground_motion(Law::constant_acceleration(0), Law::constant_acceleration(0, 0, a),
                        Law::constant_acceleration(0), Law::constant_acceleration(0));
  auto model = b.finalize();
  REQUIRE_MESSAGE(model.ok(), model.error().what());
  Data<double> d(*model);
  REQUIRE(initialize(*model, d).ok());
  std::vector<double> up;
  double x_prev = body_position(*model, d, bob).x(), t_prev = d.t;
  while (d.t < duration) {
    REQUIRE(step(*model, d) == StepStatus::ok);
    const double x = body_position(*model, d, bob).x();
    if (x_prev < 0 && x >= 0) up.push_back(t_prev + (d.t - t_prev) * (-x_prev) / (x - x_prev));
    x_prev = x;
    t_prev = d.t;
  }
  REQUIRE(up.size() >= 3);
  return (up.back() - up.front()) / static_cast<double>(up.size() - 1);
}

double analytic_period(double a) {
  const double pivot_inertia = kMass * kLength * kLength + kInertia;
  return 2 * kPi * std::sqrt(pivot_inertia / (kMass * (kG + a) * kLength)) *
         (1 + kTheta0 * kTheta0 / 16);
}

}  // namespace

TEST_CASE("a pendulum on an upward-accelerating pivot swings as under g + a") {
  for (double a : {0.0, 5.0}) {
    CAPTURE(a);
    const double measured = pendulum_period(a, 20.0), expected = analytic_period(a);
    MESSAGE("pivot acceleration " << a << " m/s^2: period " << measured << " s, analytic "
                                  << expected << " s");
    // The amplitude correction's next term (theta0^4) is below 1e-7; generalized-alpha's period
    // error at h = 1 ms and T = 1.6-2 s is of the order (w h)^2, 1e-5.
    CHECK(measured == doctest::Approx(expected).epsilon(1e-4));
  }
  // The base's acceleration is what changed it.
  CHECK(analytic_period(5.0) < 0.85 * analytic_period(0.0));
}

TEST_CASE("a body welded to a turning ground follows it, held by the centripetal force") {
  const double w = 2.0, r = 0.5;
  ModelBuilder<double> b;
  const BodyId body =
      b.add_rigid_body("block", kMass, Vector3d::Zero(), Matrix3d::Identity() * 0.01);
  b.set_initial_pose(body, Vector3d(r, 0, 0));
  const JointId weld =
      b.add_joint("weld", JointKind::fixed, b.add_marker("seat", b.ground(), -1, Vector3d(r, 0, 0)),
                  b.add_marker("base", body, -1));
  using Law = MotionLaw<double>;
  b.set_ground_motion(Law::constant_acceleration(0), Law::constant_acceleration(0),
                      Law::constant_acceleration(0), Law::constant_acceleration(0, w),
                      Vector3d::UnitZ());
  auto model = b.finalize();
  REQUIRE_MESSAGE(model.ok(), model.error().what());
  Data<double> d(*model);
  REQUIRE(initialize(*model, d).ok());
  for (int i = 0; i < 1000; ++i) REQUIRE(step(*model, d) == StepStatus::ok);
  const Vector3d expected(r * std::cos(w * d.t), r * std::sin(w * d.t), 0);
  const Vector3d position = body_position(*model, d, body);
  const Vector3d spin = body_angular_velocity(*model, d, body);
  // The reaction is in the joint frame (marker i's, turning with the ground): there the
  // centripetal force points from the seat to the axis, along -x.
  const Reaction<double> held = joint_reaction(*model, d, weld);
  MESSAGE("after " << d.t << " s: position error " << (position - expected).norm() << " m, spin "
                   << spin.transpose() << " rad/s, force on the block " << held.force.transpose()
                   << " N");
  CHECK((position - expected).norm() < 1e-9);
  CHECK((spin - Vector3d(0, 0, w)).norm() < 1e-9);
  // The multipliers are as accurate as the accelerations, which Newton leaves within its
  // tolerance (1e-5 m/s^2 on the corrections) of the equations': 1e-5 N on this 1 kg block.
  const Vector3d centripetal(-kMass * w * w * r, 0, 0);
  CHECK((held.force - centripetal).norm() < 5e-5);
  CHECK(held.moment.norm() < 5e-5);  // turning steadily about its centre of mass: no moment
}

}  // namespace test_ground_motion
