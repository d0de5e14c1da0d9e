// Effects and force elements a model does not name are not evaluated, so the only honest check
// that nothing is lost or added by leaving one out is to compare with the same model naming it
// with the effect switched to zero: the motions must agree to round-off. A point-load callback
// is checked against a reference it must reproduce exactly: a point force m g at the centre of
// mass of a rigid pendulum is gravity. And the energy balance of a driven, damped flexible beam.
#include <cmath>

#include <doctest/doctest.h>

#include <flexstress/model/all.hpp>

#include "support/beam_fixtures.hpp"

namespace test_effects {

using namespace flexstress;

namespace {

// The hinged beam of test_flexible_models: 2 m steel RHS 40 x 20 x 2, revolute about z at x = 0.
testing::BeamBody hinged_beam(int fixed_modes) {
  return testing::make_beam_body(2.0, fe::rectangular_hollow_section(0.04, 0.02, 0.002), 24, {0.0},
                                 fixed_modes);
}

constexpr int kModes = 2;
constexpr int kSteps = 300;  // 0.3 s at h = 1 ms: the beam swings and flexes visibly

/// What a variant of the hinged beam adds to the base model (gravity, 0 % damping unless set).
struct Variant {
  bool gravity = true;
  Vector3d g = Vector3d(0, -9.81, 0);
  double zeta = 0.0;
  bool spring = false;
  double spring_stiffness = 0.0;
  PointLoadFunction load = nullptr;
};

// Runs `steps` implicit steps from the given initial spin about the hinge and returns the
// coordinates and velocities stacked, for comparison.
Eigen::VectorXd run_implicit(const testing::BeamBody& beam, const Variant& v, double spin,
                             int steps) {
  ModelBuilder<double> b;
  const BodyId body = b.add_flexible_body("beam", beam.data, kModes);
  b.set_damping_ratio(body, v.zeta);
  b.add_joint("hinge", JointKind::revolute, b.add_marker("pivot", b.ground(), -1),
              b.add_marker("root", body, beam.interface_nodes[0]));
  if (v.gravity) b.set_gravity(v.g);
  if (v.spring) {
    SpringDamperParams<double> p;
    p.stiffness = v.spring_stiffness;
    b.add_spring_damper("spring", b.add_marker("anchor", b.ground(), -1, Vector3d(2.0, 1.0, 0.0)),
                        b.add_marker("tip", body, beam.line.node_at(2.0)), p);
  }
  if (v.load != nullptr)
    b.add_point_load("load", b.add_marker("middle", body, beam.line.node_at(1.0)), v.load);
  auto model = b.finalize();
  REQUIRE_MESSAGE(model.ok(), model.error().what());
  Data<double> d(*model);
  set_body_velocity(*model, d, body, Vector3d::Zero(), Vector3d(0, 0, spin));
  REQUIRE(initialize(*model, d).ok());
  for (int i = 0; i < steps; ++i) REQUIRE(step(*model, d) == StepStatus::ok);
  const Eigen::VectorXd p = modal_coordinates(*model, d, body);
  Eigen::VectorXd out(3 + 4 + p.size() + 6);
  out << body_position(*model, d, body), Eigen::Vector4d(body_orientation(*model, d, body)), p,
      body_velocity(*model, d, body), body_angular_velocity(*model, d, body);
  return out;
}

double relative_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).lpNorm<Eigen::Infinity>() / std::max(1e-30, b.lpNorm<Eigen::Infinity>());
}

}  // namespace

TEST_CASE("a model without an effect moves exactly like one with that effect switched to zero") {
  const auto beam = hinged_beam(kModes);
  SUBCASE("gravity: left out vs g = 0") {
    Variant without, with;
    without.gravity = false;
    with.g.setZero();
    const double d = relative_difference(run_implicit(beam, without, 3.0, kSteps),
                                         run_implicit(beam, with, 3.0, kSteps));
    MESSAGE("relative difference " << d);
    CHECK(d < 1e-13);
  }
  SUBCASE("modal damping: left out vs zeta = 0") {
    // A body whose damping ratios are all zero has no damping stage; the data's own ratios are
    // zero too, so compare against 2 % to show that the comparison can fail.
    Variant without, damped;
    damped.zeta = 0.02;
    const auto a = run_implicit(beam, without, 0.0, kSteps);
    CHECK(relative_difference(a, run_implicit(beam, damped, 0.0, kSteps)) > 1e-9);
  }
  SUBCASE("spring-dampers: left out vs a spring-damper with k = c = preload = 0") {
    Variant without, with;
    with.spring = true;
    const auto zero = run_implicit(beam, with, 0.0, kSteps);
    const double d = relative_difference(run_implicit(beam, without, 0.0, kSteps), zero);
    MESSAGE("relative difference " << d);
    CHECK(d < 1e-13);
    with.spring_stiffness = 50.0;  // a real spring changes the motion
    CHECK(relative_difference(run_implicit(beam, with, 0.0, kSteps), zero) > 1e-6);
  }
  SUBCASE("point loads: left out vs a callback that adds nothing") {
    Variant without, with;
    with.load = [](double, const double*, const double*, double*, double*, void*) {};
    const auto a = run_implicit(beam, without, 0.0, kSteps);
    CHECK(relative_difference(a, run_implicit(beam, with, 0.0, kSteps)) < 1e-13);
  }
}

namespace {

// A rigid pendulum (1 kg, 1 m, released horizontal) with gravity, and with gravity applied by a
// point-load callback as a force m g at the centre of mass.
Eigen::VectorXd swing(bool callback) {
  ModelBuilder<double> b;
  const BodyId body = b.add_rigid_body("bob", 1.0, Vector3d::Zero(), Matrix3d::Identity() * 1e-3);
  b.set_initial_pose(body, Vector3d(1, 0, 0));
  b.add_joint("pivot", JointKind::revolute, b.add_marker("pivot", b.ground(), -1),
              b.add_marker("rod end", body, -1, Vector3d(-1, 0, 0)));
  static double weight[3] = {0, -9.81, 0};
  if (callback)
    b.add_point_load(
        "weight", b.add_marker("centre", body, -1),
        [](double, const double*, const double*, double* f, double*, void* user) {
          const double* w = static_cast<const double*>(user);
          for (int c = 0; c < 3; ++c) f[c] = w[c];
        },
        weight);
  else
    b.set_gravity(Vector3d(0, -9.81, 0));
  auto model = b.finalize();
  REQUIRE_MESSAGE(model.ok(), model.error().what());
  Data<double> d(*model);
  REQUIRE(initialize(*model, d).ok());
  for (int i = 0; i < 500; ++i) REQUIRE(step(*model, d) == StepStatus::ok);
  Eigen::VectorXd out(13);
  out << body_position(*model, d, body), Eigen::Vector4d(body_orientation(*model, d, body)),
      body_velocity(*model, d, body), body_angular_velocity(*model, d, body);
  return out;
}

}  // namespace

TEST_CASE("a point-load callback applying m g at the centre of mass reproduces gravity") {
  const auto reference = swing(false);
  const auto result = swing(true);
  const double d = relative_difference(result, reference);
  MESSAGE("callback vs gravity after 0.5 s: " << d);
  CHECK(d < 1e-12);
  CHECK(result(1) < -0.5);  // it did swing down (released horizontal, 0.5 s)
}

namespace {

struct Audit {
  double residual, change, work, dissipated;
};

// The hinged beam spun up by a revolute driver (constant angular acceleration from rest, so the
// sudden inertial load sets the beam vibrating) in the vertical plane, with gravity, the
// quadratic velocity terms and 5 % modal damping.
Audit audit_spin_up(double h) {
  const auto beam = hinged_beam(kModes);
  ModelBuilder<double> b;
  const BodyId body = b.add_flexible_body("beam", beam.data, kModes);
  b.set_damping_ratio(body, 0.05);
  const MarkerId pivot = b.add_marker("pivot", b.ground(), -1);
  const MarkerId root = b.add_marker("root", body, beam.interface_nodes[0]);
  b.add_joint("hinge", JointKind::revolute, pivot, root);
  b.add_driver(
      "spin-up", JointKind::revolute_driver, pivot, root,
      MotionLaw<double>::constant_acceleration(0.0, 0.0, 40.0));  // rad/s^2: 8 rad/s after 0.2 s
  b.set_gravity(Vector3d(0, -9.81, 0));
  b.settings().step = h;
  auto model = b.finalize();
  REQUIRE_MESSAGE(model.ok(), model.error().what());
  Data<double> d(*model);
  REQUIRE(initialize(*model, d).ok());
  EnergyBalance<double> audit;
  audit.start(*model, d);
  const int steps = static_cast<int>(std::lround(0.2 / h));
  for (int i = 0; i < steps; ++i) {
    REQUIRE(step(*model, d) == StepStatus::ok);
    audit.record(*model, d);
  }
  return {audit.max_abs_residual(), audit.max_energy_change(), audit.driver_work(),
          audit.dissipated()};
}

}  // namespace

// Reference: the work-energy theorem, E(t) - E(0) = W_driver - D_damping for ideal joints
// (Shabana, Dynamics of Multibody Systems, sec. 3.8), with E the kinetic, gravity and elastic
// energy. The kinetic energy gained is about I w^2 / 2 = 140 J (beam 3.5 kg, 2 m, 8 rad/s).
TEST_CASE("energy audit: a driven, damped flexible beam balances driver work and dissipation") {
  const Audit coarse = audit_spin_up(2e-3), fine = audit_spin_up(1e-3);
  MESSAGE("h = 2 ms: max |r| " << coarse.residual << " J; h = 1 ms: " << fine.residual
                               << " J; W = " << fine.work << " J, D = " << fine.dissipated
                               << " J, max |E - E0| = " << fine.change << " J");
  CHECK(fine.work > 100.0);                      // the driver did the spin-up's work
  CHECK(fine.dissipated > 0.0);                  // damping only takes energy out
  CHECK(fine.residual < 1e-3 * fine.change);     // the bound on the crane, here too
  CHECK(fine.residual < 0.1 * fine.dissipated);  // leaving out D would fail the balance
  CHECK(fine.residual < coarse.residual);        // and the balance improves with h
}

}  // namespace test_effects
