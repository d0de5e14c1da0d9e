// Runtime changes that need no reallocation: a payload released and then flying free (with the
// implicit and the explicit integrator), a free body captured by another, and a brake between
// two links locked and freed (Scene::set_joint_active, Scene::anchor_joint_at).
//
// References are laws no one here wrote: a released body follows the ballistic parabola
// x0 + v0 t + g t^2 / 2; a capture (a perfectly plastic impact) keeps the total linear and
// angular momentum; locking a hinge of a pendulum keeps the angular momentum about its fixed
// pivot (the impulse at the pivot has no moment about it), and a locked or freed conservative
// system keeps its energy.
#include <cmath>

#include <doctest/doctest.h>

#include <flexstress/dynamics/explicit_integrator.hpp>
#include <flexstress/dynamics/implicit_integrator.hpp>

namespace test_runtime_changes {

using namespace flexstress;

namespace {

/// A rigid body's mass, centre of mass (body frame) and inertia about it, kept for momenta.
struct RigidData {
  double mass;
  Vector3d com;
  Matrix3d inertia;
  RigidBody model() const { return RigidBody::rigid(mass, com, inertia); }
};

/// Linear and angular momentum (about the global origin) of a rigid body at its kinematics.
struct Momentum {
  Vector3d linear = Vector3d::Zero(), angular = Vector3d::Zero();
  Momentum& operator+=(const Momentum& o) {
    linear += o.linear;
    angular += o.angular;
    return *this;
  }
};
Momentum momentum(const RigidData& b, const BodyKinematics<double, 0>& k) {
  const Vector3d c = k.position + k.rotation * b.com;
  const Vector3d vc = k.velocity + k.rotation * k.omega.cross(b.com);
  Momentum m;
  m.linear = b.mass * vc;
  m.angular = c.cross(m.linear) + k.rotation * (b.inertia * k.omega);
  return m;
}

// One scene type serves the three cases, each switching off the joints it does not use (so the
// test also shows that a compiled scene can change its topology at runtime): two rigid bodies, a
// hinge of body 0 to the ground (joint 0), a hook (spherical, 1), a hinge between the bodies (2)
// and a weld between them (3).
using Switchable = Scene<double, Bodies<RigidBody, RigidBody>,
                         Joints<Revolute<ground, 0>, Spherical<0, 1>, Revolute<0, 1>, Fixed<0, 1>>,
                         Effects<Gravity, QuadraticVelocity>>;

// A 1 m rod of 2 kg hinged at the origin about z (frame at the hinge, along x) carrying a 1 kg
// payload on a hook at its tip.
const RigidData rod{2.0, Vector3d(0.5, 0, 0), Vector3d(1e-4, 2.0 / 12, 2.0 / 12).asDiagonal()};
const RigidData payload{1.0, Vector3d::Zero(), Matrix3d::Identity() * 1e-3};

Switchable make_crane() {
  Switchable scene;
  scene.body<0>() = rod.model();
  scene.body<1>() = payload.model();
  scene.joint<0>().marker_i = fixed_marker<double>(Vector3d::Zero());
  scene.joint<0>().marker_j = make_marker(scene.body<0>(), -1, Vector3d::Zero());
  scene.joint<1>().marker_i = make_marker(scene.body<0>(), -1, Vector3d(1, 0, 0));
  scene.joint<1>().marker_j = make_marker(scene.body<1>(), -1, Vector3d::Zero());
  scene.set_joint_active<2>(false);
  scene.set_joint_active<3>(false);
  return scene;
}

// Two free rigid bodies in space (no gravity), joined by the weld when one catches the other.
const RigidData chaser{2.0, Vector3d(0.05, 0, 0), Vector3d(0.1, 0.2, 0.3).asDiagonal()};
const RigidData target{3.0, Vector3d(0, 0.02, 0), Vector3d(0.2, 0.25, 0.15).asDiagonal()};

// A double pendulum (two 1 m links of 1 kg, hinged about z) with a brake on the middle hinge: the
// weld in parallel with the hinge (redundant with it, which the augmented Lagrangian takes).
const RigidData link{1.0, Vector3d(0.5, 0, 0), Vector3d(1e-4, 1.0 / 12, 1.0 / 12).asDiagonal()};

/// Angle about z from the frame of link 0 to that of link 1.
double relative_angle(const Switchable::State& s) {
  const Matrix3d a = rotation_matrix(s.coordinates<0>().theta).transpose() *
                     rotation_matrix(s.coordinates<1>().theta);
  return std::atan2(a(1, 0), a(0, 0));
}

/// What the trapezoidal rule's energy error on a nonlinear swing is measured against: its
/// order, (h w)^2 of the energy exchanged m g L (links of L = 1 m), with w^2 = w2 g / L.
double energy_error_scale(double h, double mass, double w2) {
  const double g = 9.81, length = 1.0;
  return h * h * w2 * g / length * mass * g * length;
}
// The rod about its hinge: w^2 = m g (L/2) / (m L^2 / 3) = 1.5 g / L.
constexpr double rod_w2 = 1.5;
// The double pendulum's faster normal mode (equal uniform links, absolute angles: mass matrix
// m L^2 [4/3 1/2; 1/2 1/3], stiffness m g L diag(3/2, 1/2)): 7 l^2 - 42 l + 27 = 0 for
// l = w^2 L / g, l = 5.27. Locking the hinge adds a constraint, whose frequency lies between
// the free ones, so this bounds both phases.
constexpr double double_pendulum_w2 = 5.27;

}  // namespace

TEST_CASE("a released payload flies the ballistic parabola; the rod keeps its own energy") {
  Switchable scene = make_crane();
  ImplicitIntegrator<Switchable>::Settings settings;
  settings.step = 1e-3;
  settings.spectral_radius = 1.0;  // no numerical dissipation: energy is a sharp check
  ImplicitIntegrator<Switchable> integrator(scene, settings);
  Switchable::State s;
  s.coordinates<1>().position = Vector3d(1, 0, 0);
  REQUIRE(integrator.initialize(s).ok());
  for (int i = 0; i < 300; ++i) REQUIRE(integrator.step(s) == StepStatus::ok);
  // Swinging down through about 60 degrees: the payload moves fast and the hook pulls on it.
  auto& ws = integrator.workspace();
  CHECK(s.lambda.segment<3>(5).norm() > 1.0);
  scene.set_joint_active<1>(false);
  CHECK_FALSE(scene.joint_active<1>());
  const Vector3d x0 = s.coordinates<1>().position, v0 = s.velocity<1>().head<3>();
  scene.update_kinematics(s, ws);
  const double rod_energy0 = scene.body<0>().kinetic_energy(std::get<0>(ws.kin)) -
                             rod.mass * scene.gravity.dot(std::get<0>(ws.kin).rotation * rod.com);
  const double t0 = s.t;
  double worst_position = 0, worst_rod_energy = 0;
  for (int i = 0; i < 500; ++i) {
    REQUIRE(integrator.step(s) == StepStatus::ok);
    const double tau = s.t - t0;
    const Vector3d ballistic = x0 + v0 * tau + 0.5 * scene.gravity * tau * tau;
    worst_position = std::max(worst_position, (s.coordinates<1>().position - ballistic).norm());
    scene.update_kinematics(s, ws);
    const double rod_energy = scene.body<0>().kinetic_energy(std::get<0>(ws.kin)) -
                              rod.mass * scene.gravity.dot(std::get<0>(ws.kin).rotation * rod.com);
    worst_rod_energy = std::max(worst_rod_energy, std::abs(rod_energy - rod_energy0));
  }
  // The released hook carries no reaction.
  CHECK(s.lambda.segment<3>(5).norm() == 0.0);
  // The payload drops 1.2 m in 0.5 s. Generalized-alpha integrates a constant acceleration
  // exactly once it starts from the true one, which the restart after the switch gives it
  // (without the restart, the release smeared over one step left 4 mm).
  MESSAGE("ballistic error " << worst_position << " m; rod energy drift " << worst_rod_energy
                             << " J");
  CHECK(worst_position < 1e-12);
  // The rod swings alone, conservatively, to the order of the trapezoidal rule's energy error.
  CHECK(worst_rod_energy < energy_error_scale(settings.step, rod.mass, rod_w2));
}

TEST_CASE("the explicit integrator (RK4) flies the released payload on the parabola too") {
  Switchable scene = make_crane();
  ExplicitIntegrator<Switchable>::Settings settings;
  settings.step = 1e-3;
  ExplicitIntegrator<Switchable> rk4(scene, settings);
  Switchable::State s;
  s.coordinates<1>().position = Vector3d(1, 0, 0);
  for (int i = 0; i < 300; ++i) REQUIRE(rk4.step(s) == StepStatus::ok);
  scene.set_joint_active<1>(false);
  const Vector3d x0 = s.coordinates<1>().position, v0 = s.velocity<1>().head<3>();
  const double t0 = s.t;
  double worst = 0;
  for (int i = 0; i < 500; ++i) {
    REQUIRE(rk4.step(s) == StepStatus::ok);
    const double tau = s.t - t0;
    worst = std::max(
        worst,
        (s.coordinates<1>().position - (x0 + v0 * tau + 0.5 * scene.gravity * tau * tau)).norm());
  }
  // RK4 integrates a constant acceleration exactly (a cubic in time at most), and the
  // projection after each step does not touch a body no active joint holds.
  MESSAGE("RK4 ballistic error " << worst << " m");
  CHECK(worst < 1e-12);
  CHECK(s.lambda.segment<3>(5).norm() == 0.0);
}

TEST_CASE("a capture keeps linear and angular momentum and loses kinetic energy") {
  Switchable scene;
  scene.gravity.setZero();
  scene.body<0>() = chaser.model();
  scene.body<1>() = target.model();
  // The weld's markers: on the chaser's nose (0.3 m ahead), and (until the capture anchors it)
  // anywhere on the target. No other joint.
  scene.joint<3>().marker_i = make_marker(scene.body<0>(), -1, Vector3d(0.3, 0, 0));
  scene.joint<3>().marker_j = make_marker(scene.body<1>(), -1, Vector3d::Zero());
  scene.set_joint_active<0>(false);
  scene.set_joint_active<1>(false);
  scene.set_joint_active<2>(false);
  scene.set_joint_active<3>(false);
  ImplicitIntegrator<Switchable>::Settings settings;
  settings.step = 1e-3;
  settings.spectral_radius = 1.0;
  ImplicitIntegrator<Switchable> integrator(scene, settings);
  Switchable::State s;
  s.coordinates<1>().position = Vector3d(0.6, 0.1, 0.05);
  s.velocity<0>() << 1.0, 0.5, -0.2, 0.3, -0.4, 2.0;  // R_dot and w (body frame)
  s.velocity<1>() << 0.0, 0.0, 0.1, 0.0, 0.5, 0.0;
  REQUIRE(integrator.initialize(s).ok());
  for (int i = 0; i < 200; ++i) REQUIRE(integrator.step(s) == StepStatus::ok);
  auto& ws = integrator.workspace();
  const auto total = [&]() {
    scene.update_kinematics(s, ws);
    Momentum m = momentum(chaser, std::get<0>(ws.kin));
    m += momentum(target, std::get<1>(ws.kin));
    return m;
  };
  const Momentum before = total();
  const double energy_before = scene.energy(ws).kinetic;
  // Capture: the weld holds the two bodies where they are, then the velocities are projected
  // onto the joint in the mass metric.
  scene.anchor_joint_at<3>(s, ws);
  scene.set_joint_active<3>(true);
  REQUIRE(integrator.initialize(s).ok());
  const Momentum after = total();
  const double energy_after = scene.energy(ws).kinetic;
  scene.update_constraints(s, ws);
  CHECK(ws.phi.cwiseAbs().maxCoeff() < 1e-12);         // no jump in positions
  CHECK((ws.jac * s.v).cwiseAbs().maxCoeff() < 1e-9);  // moving as one body
  MESSAGE("momentum change: linear " << (after.linear - before.linear).norm() << ", angular "
                                     << (after.angular - before.angular).norm()
                                     << "; kinetic energy " << energy_before << " -> "
                                     << energy_after << " J");
  // The projection's velocity change is M^-1 B^T mu exactly (equal and opposite impulses at the
  // weld), so the momenta change only by round-off in summing them up.
  CHECK((after.linear - before.linear).norm() < 1e-10 * before.linear.norm());
  CHECK((after.angular - before.angular).norm() < 1e-10 * before.angular.norm());
  CHECK(energy_after < 0.99 * energy_before);
  // Joined, they tumble on as one free rigid body: the weld stays closed, the energy stays.
  for (int i = 0; i < 500; ++i) REQUIRE(integrator.step(s) == StepStatus::ok);
  const Momentum later = total();
  scene.update_constraints(s, ws);
  MESSAGE("after 0.5 s joined: weld violation " << ws.phi.cwiseAbs().maxCoeff()
                                                << ", linear momentum change "
                                                << (later.linear - after.linear).norm());
  CHECK(ws.phi.cwiseAbs().maxCoeff() < 1e-9);
  CHECK(scene.energy(ws).kinetic == doctest::Approx(energy_after).epsilon(1e-7));
}

TEST_CASE("a brake locked and freed: pivot momentum at the lock, a rigid swing, energy") {
  Switchable scene;
  scene.body<0>() = link.model();
  scene.body<1>() = link.model();
  scene.joint<0>().marker_i = fixed_marker<double>(Vector3d::Zero());
  scene.joint<0>().marker_j = make_marker(scene.body<0>(), -1, Vector3d::Zero());
  scene.joint<2>().marker_i = make_marker(scene.body<0>(), -1, Vector3d(1, 0, 0));
  scene.joint<2>().marker_j = make_marker(scene.body<1>(), -1, Vector3d::Zero());
  scene.joint<3>().marker_i = scene.joint<2>().marker_i;
  scene.joint<3>().marker_j = scene.joint<2>().marker_j;
  scene.set_joint_active<1>(false);  // no hook
  scene.set_joint_active<3>(false);  // the brake starts free
  ImplicitIntegrator<Switchable>::Settings settings;
  settings.step = 1e-3;
  settings.spectral_radius = 1.0;
  ImplicitIntegrator<Switchable> integrator(scene, settings);
  Switchable::State s;
  s.coordinates<1>().position = Vector3d(1, 0, 0);
  REQUIRE(integrator.initialize(s).ok());
  auto& ws = integrator.workspace();
  const auto pivot_momentum = [&]() {
    scene.update_kinematics(s, ws);
    return momentum(link, std::get<0>(ws.kin)).angular.z() +
           momentum(link, std::get<1>(ws.kin)).angular.z();
  };
  const auto energy = [&]() {
    scene.update_kinematics(s, ws);
    return scene.energy(ws).total();
  };
  for (int i = 0; i < 400; ++i) REQUIRE(integrator.step(s) == StepStatus::ok);
  const double relative_rate = s.velocity<1>()(5) - s.velocity<0>()(5);
  REQUIRE(std::abs(relative_rate) > 0.1);  // the lower link swings relative to the upper one
  const double momentum_before = pivot_momentum(), energy_before = energy();

  // Lock: the brake welds the links at their current angle, an impact.
  scene.anchor_joint_at<3>(s, ws);
  scene.set_joint_active<3>(true);
  REQUIRE(integrator.initialize(s).ok());
  const double locked_angle = relative_angle(s);
  CHECK(std::abs(s.velocity<1>()(5) - s.velocity<0>()(5)) < 1e-9);
  MESSAGE("pivot momentum " << momentum_before << " -> " << pivot_momentum() << "; energy "
                            << energy_before << " -> " << energy() << " J");
  CHECK(pivot_momentum() == doctest::Approx(momentum_before).epsilon(1e-12));
  CHECK(energy() < energy_before - 1e-3);  // the lock dissipates the relative motion's energy
  const double energy_locked = energy();
  double worst_angle = 0, worst_energy = 0;
  for (int i = 0; i < 1000; ++i) {
    REQUIRE(integrator.step(s) == StepStatus::ok);
    worst_angle = std::max(worst_angle, std::abs(relative_angle(s) - locked_angle));
    worst_energy = std::max(worst_energy, std::abs(energy() - energy_locked));
  }
  MESSAGE("locked: relative angle moved " << worst_angle << " rad, energy drift " << worst_energy
                                          << " J");
  CHECK(worst_angle < 1e-9);
  CHECK(worst_energy < energy_error_scale(settings.step, 2 * link.mass, double_pendulum_w2));

  // Free: the links swing apart again, and the energy stays.
  scene.set_joint_active<3>(false);
  double largest_angle = 0;
  worst_energy = 0;
  for (int i = 0; i < 1000; ++i) {
    REQUIRE(integrator.step(s) == StepStatus::ok);
    largest_angle = std::max(largest_angle, std::abs(relative_angle(s) - locked_angle));
    worst_energy = std::max(worst_energy, std::abs(energy() - energy_locked));
  }
  CHECK(largest_angle > 0.1);
  CHECK(worst_energy < energy_error_scale(settings.step, 2 * link.mass, double_pendulum_w2));
  CHECK(s.lambda.segment<6>(13).norm() == 0.0);  // the freed brake carries nothing
}

}  // namespace test_runtime_changes
