// Runtime changes that need no reallocation: a payload released and then flying free (with the
// implicit and the explicit integrator), a free body captured by another, and a brake between
// two links locked and freed (set_joint_active, anchor_joint_at).
//
// References are laws no one here wrote: a released body follows the ballistic parabola
// x0 + v0 t + g t^2 / 2; a capture (a perfectly plastic impact) keeps the total linear and
// angular momentum; locking a hinge of a pendulum keeps the angular momentum about its fixed
// pivot (the impulse at the pivot has no moment about it), and a locked or freed conservative
// system keeps its energy.
#include <cmath>
#include <string>

#include <doctest/doctest.h>

#include <flexstress/model/all.hpp>

namespace test_runtime_changes {

using namespace flexstress;

namespace {

/// A rigid body's mass, centre of mass (body frame) and inertia about it.
struct RigidData {
  double mass;
  Vector3d com;
  Matrix3d inertia;
};

const Vector3d kGravity(0, -9.81, 0);

// One model layout serves the three cases, each switching off the joints it does not use (so the
// test also shows that a model can change its topology at runtime): two rigid bodies, a hinge of
// the first to the ground, a hook (spherical) between them, a hinge between them and a weld
// between them. Each joint has its own markers (anchor_joint_at moves the weld's marker j).
struct Layout {
  std::string first_name, second_name;
  RigidData first, second;
  Vector3d second_start = Vector3d::Zero();  ///< where the second body's frame starts
  bool gravity = true;
  Vector3d hinge_j = Vector3d::Zero();  ///< on the first body (marker i at the ground's origin)
  Vector3d hook_i = Vector3d::Zero(), hook_j = Vector3d::Zero();  ///< on the first, the second
  Vector3d link_i = Vector3d::Zero(), link_j = Vector3d::Zero();  ///< the hinge between them
  Vector3d weld_i = Vector3d::Zero(), weld_j = Vector3d::Zero();
};

struct Switchable {
  Model<double> model;
  BodyId first, second;
  JointId hinge, hook, link, weld;
};

Switchable make_switchable(const Layout& l) {
  ModelBuilder<double> b;
  Switchable s;
  s.first = b.add_rigid_body(l.first_name, l.first.mass, l.first.com, l.first.inertia);
  s.second = b.add_rigid_body(l.second_name, l.second.mass, l.second.com, l.second.inertia);
  b.set_initial_pose(s.second, l.second_start);
  s.hinge = b.add_joint("hinge", JointKind::revolute, b.add_marker("pivot", b.ground(), -1),
                        b.add_marker("hinge j", s.first, -1, l.hinge_j));
  s.hook = b.add_joint("hook", JointKind::spherical, b.add_marker("hook i", s.first, -1, l.hook_i),
                       b.add_marker("hook j", s.second, -1, l.hook_j));
  s.link = b.add_joint("link", JointKind::revolute, b.add_marker("link i", s.first, -1, l.link_i),
                       b.add_marker("link j", s.second, -1, l.link_j));
  s.weld = b.add_joint("weld", JointKind::fixed, b.add_marker("weld i", s.first, -1, l.weld_i),
                       b.add_marker("weld j", s.second, -1, l.weld_j));
  if (l.gravity) b.set_gravity(kGravity);
  auto m = b.finalize();
  if (!m.ok()) FAIL(m.error().what());
  s.model = std::move(*m);
  return s;
}

// A 1 m rod of 2 kg hinged at the origin about z (frame at the hinge, along x) carrying a 1 kg
// payload on a hook at its tip.
const RigidData rod{2.0, Vector3d(0.5, 0, 0), Vector3d(1e-4, 2.0 / 12, 2.0 / 12).asDiagonal()};
const RigidData payload{1.0, Vector3d::Zero(), Matrix3d::Identity() * 1e-3};

Switchable make_crane() {
  Layout l;
  l.first_name = "rod";
  l.second_name = "payload";
  l.first = rod;
  l.second = payload;
  l.second_start = Vector3d(1, 0, 0);
  l.hook_i = Vector3d(1, 0, 0);
  return make_switchable(l);
}

/// The crane's Data with the hinge between the bodies and the weld off.
void crane_topology(const Switchable& c, Data<double>& d) {
  set_joint_active(c.model, d, c.link, false);
  set_joint_active(c.model, d, c.weld, false);
}

// Two free rigid bodies in space (no gravity), joined by the weld when one catches the other.
const RigidData chaser{2.0, Vector3d(0.05, 0, 0), Vector3d(0.1, 0.2, 0.3).asDiagonal()};
const RigidData target{3.0, Vector3d(0, 0.02, 0), Vector3d(0.2, 0.25, 0.15).asDiagonal()};

// A double pendulum (two 1 m links of 1 kg, hinged about z) with a brake on the middle hinge: the
// weld in parallel with the hinge (redundant with it, which the augmented Lagrangian takes).
const RigidData link{1.0, Vector3d(0.5, 0, 0), Vector3d(1e-4, 1.0 / 12, 1.0 / 12).asDiagonal()};

/// Kinetic plus gravity potential energy of one rigid body of the model (energy() sums all).
double body_energy(const Switchable& s, const Data<double>& d, BodyId id, const RigidData& b) {
  const Matrix3d a = rotation_matrix(body_orientation(s.model, d, id));
  const Vector3d omega = body_angular_velocity(s.model, d, id);
  const Vector3d vc = body_velocity(s.model, d, id) + a * omega.cross(b.com);
  const Vector3d c = body_position(s.model, d, id) + a * b.com;
  return 0.5 * b.mass * vc.squaredNorm() + 0.5 * omega.dot(b.inertia * omega) -
         b.mass * kGravity.dot(c);
}

/// Angle about z from the frame of link 0 to that of link 1.
double relative_angle(const Switchable& s, const Data<double>& d) {
  const Matrix3d a = rotation_matrix(body_orientation(s.model, d, s.first)).transpose() *
                     rotation_matrix(body_orientation(s.model, d, s.second));
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
  const Switchable c = make_crane();
  Data<double> d(c.model);
  crane_topology(c, d);
  d.settings.step = 1e-3;
  d.settings.spectral_radius = 1.0;  // no numerical dissipation: energy is a sharp check
  REQUIRE(initialize(c.model, d).ok());
  for (int i = 0; i < 300; ++i) REQUIRE(step(c.model, d) == StepStatus::ok);
  // Swinging down through about 60 degrees: the payload moves fast and the hook pulls on it.
  CHECK(joint_reaction(c.model, d, c.hook).force.norm() > 1.0);
  set_joint_active(c.model, d, c.hook, false);
  CHECK_FALSE(joint_active(d, c.hook));
  const Vector3d x0 = body_position(c.model, d, c.second), v0 = body_velocity(c.model, d, c.second);
  const double rod_energy0 = body_energy(c, d, c.first, rod);
  const double t0 = d.t;
  double worst_position = 0, worst_rod_energy = 0;
  for (int i = 0; i < 500; ++i) {
    REQUIRE(step(c.model, d) == StepStatus::ok);
    const double tau = d.t - t0;
    const Vector3d ballistic = x0 + v0 * tau + 0.5 * kGravity * tau * tau;
    worst_position =
        std::max(worst_position, (body_position(c.model, d, c.second) - ballistic).norm());
    worst_rod_energy =
        std::max(worst_rod_energy, std::abs(body_energy(c, d, c.first, rod) - rod_energy0));
  }
  // The released hook carries no reaction.
  CHECK(joint_reaction(c.model, d, c.hook).force.norm() == 0.0);
  // The payload drops 1.2 m in 0.5 s. Generalized-alpha integrates a constant acceleration
  // exactly once it starts from the true one, which the restart after the switch gives it
  // (without the restart, the release smeared over one step left 4 mm).
  MESSAGE("ballistic error " << worst_position << " m; rod energy drift " << worst_rod_energy
                             << " J");
  CHECK(worst_position < 1e-12);
  // The rod swings alone, conservatively, to the order of the trapezoidal rule's energy error.
  CHECK(worst_rod_energy < energy_error_scale(d.settings.step, rod.mass, rod_w2));
}

TEST_CASE("the explicit integrator (RK4) flies the released payload on the parabola too") {
  const Switchable c = make_crane();
  Data<double> d(c.model);
  crane_topology(c, d);
  ExplicitSettings<double> settings;
  settings.step = 1e-3;
  for (int i = 0; i < 300; ++i) REQUIRE(explicit_step(c.model, d, settings) == StepStatus::ok);
  set_joint_active(c.model, d, c.hook, false);
  const Vector3d x0 = body_position(c.model, d, c.second), v0 = body_velocity(c.model, d, c.second);
  const double t0 = d.t;
  double worst = 0;
  for (int i = 0; i < 500; ++i) {
    REQUIRE(explicit_step(c.model, d, settings) == StepStatus::ok);
    const double tau = d.t - t0;
    worst = std::max(
        worst, (body_position(c.model, d, c.second) - (x0 + v0 * tau + 0.5 * kGravity * tau * tau))
                   .norm());
  }
  // RK4 integrates a constant acceleration exactly (a cubic in time at most), and the
  // projection after each step does not touch a body no active joint holds.
  MESSAGE("RK4 ballistic error " << worst << " m");
  CHECK(worst < 1e-12);
  CHECK(joint_reaction(c.model, d, c.hook).force.norm() == 0.0);
}

TEST_CASE("a capture keeps linear and angular momentum and loses kinetic energy") {
  Layout l;
  l.first_name = "chaser";
  l.second_name = "target";
  l.first = chaser;
  l.second = target;
  l.gravity = false;
  l.second_start = Vector3d(0.6, 0.1, 0.05);
  // The weld's markers: on the chaser's nose (0.3 m ahead), and (until the capture anchors it)
  // anywhere on the target. No other joint.
  l.weld_i = Vector3d(0.3, 0, 0);
  const Switchable c = make_switchable(l);
  Data<double> d(c.model);
  for (JointId j : {c.hinge, c.hook, c.link, c.weld}) set_joint_active(c.model, d, j, false);
  d.settings.step = 1e-3;
  d.settings.spectral_radius = 1.0;
  set_body_velocity(c.model, d, c.first, Vector3d(1.0, 0.5, -0.2),
                    Vector3d(0.3, -0.4, 2.0));  // R_dot and w (body frame)
  set_body_velocity(c.model, d, c.second, Vector3d(0.0, 0.0, 0.1), Vector3d(0.0, 0.5, 0.0));
  REQUIRE(initialize(c.model, d).ok());
  for (int i = 0; i < 200; ++i) REQUIRE(step(c.model, d) == StepStatus::ok);
  const Momentum<double> before = momentum(c.model, d);
  const double energy_before = energy(c.model, d).kinetic;
  // Capture: the weld holds the two bodies where they are, then the velocities are projected
  // onto the joint in the mass metric.
  REQUIRE(anchor_joint_at(c.model, d, c.weld).ok());
  set_joint_active(c.model, d, c.weld, true);
  REQUIRE(initialize(c.model, d).ok());
  const Momentum<double> after = momentum(c.model, d);
  const double energy_after = energy(c.model, d).kinetic;
  CHECK(constraint_violation(c.model, d) < 1e-12);  // no jump in positions
  CHECK((joint_equations(c.model, d, c.weld).jacobian * d.v).cwiseAbs().maxCoeff() <
        1e-9);  // moving as one body
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
  for (int i = 0; i < 500; ++i) REQUIRE(step(c.model, d) == StepStatus::ok);
  const Momentum<double> later = momentum(c.model, d);
  MESSAGE("after 0.5 s joined: weld violation " << constraint_violation(c.model, d)
                                                << ", linear momentum change "
                                                << (later.linear - after.linear).norm());
  CHECK(constraint_violation(c.model, d) < 1e-9);
  CHECK(energy(c.model, d).kinetic == doctest::Approx(energy_after).epsilon(1e-7));
}

TEST_CASE("a brake locked and freed: pivot momentum at the lock, a rigid swing, energy") {
  Layout l;
  l.first_name = "upper link";
  l.second_name = "lower link";
  l.first = l.second = link;
  l.second_start = Vector3d(1, 0, 0);
  l.link_i = l.weld_i = Vector3d(1, 0, 0);
  const Switchable c = make_switchable(l);
  Data<double> d(c.model);
  set_joint_active(c.model, d, c.hook, false);  // no hook
  set_joint_active(c.model, d, c.weld, false);  // the brake starts free
  d.settings.step = 1e-3;
  d.settings.spectral_radius = 1.0;
  REQUIRE(initialize(c.model, d).ok());
  const auto pivot_momentum = [&]() { return momentum(c.model, d).angular.z(); };
  const auto total_energy = [&]() { return energy(c.model, d).total(); };
  const auto relative_rate = [&]() {
    return body_angular_velocity(c.model, d, c.second).z() -
           body_angular_velocity(c.model, d, c.first).z();
  };
  for (int i = 0; i < 400; ++i) REQUIRE(step(c.model, d) == StepStatus::ok);
  REQUIRE(std::abs(relative_rate()) > 0.1);  // the lower link swings relative to the upper one
  const double momentum_before = pivot_momentum(), energy_before = total_energy();

  // Lock: the brake welds the links at their current angle, an impact.
  REQUIRE(anchor_joint_at(c.model, d, c.weld).ok());
  set_joint_active(c.model, d, c.weld, true);
  REQUIRE(initialize(c.model, d).ok());
  const double locked_angle = relative_angle(c, d);
  CHECK(std::abs(relative_rate()) < 1e-9);
  MESSAGE("pivot momentum " << momentum_before << " -> " << pivot_momentum() << "; energy "
                            << energy_before << " -> " << total_energy() << " J");
  CHECK(pivot_momentum() == doctest::Approx(momentum_before).epsilon(1e-12));
  CHECK(total_energy() < energy_before - 1e-3);  // the lock dissipates the relative motion's energy
  const double energy_locked = total_energy();
  double worst_angle = 0, worst_energy = 0;
  for (int i = 0; i < 1000; ++i) {
    REQUIRE(step(c.model, d) == StepStatus::ok);
    worst_angle = std::max(worst_angle, std::abs(relative_angle(c, d) - locked_angle));
    worst_energy = std::max(worst_energy, std::abs(total_energy() - energy_locked));
  }
  MESSAGE("locked: relative angle moved " << worst_angle << " rad, energy drift " << worst_energy
                                          << " J");
  CHECK(worst_angle < 1e-9);
  CHECK(worst_energy < energy_error_scale(d.settings.step, 2 * link.mass, double_pendulum_w2));

  // Free: the links swing apart again, and the energy stays.
  set_joint_active(c.model, d, c.weld, false);
  double largest_angle = 0;
  worst_energy = 0;
  for (int i = 0; i < 1000; ++i) {
    REQUIRE(step(c.model, d) == StepStatus::ok);
    largest_angle = std::max(largest_angle, std::abs(relative_angle(c, d) - locked_angle));
    worst_energy = std::max(worst_energy, std::abs(total_energy() - energy_locked));
  }
  CHECK(largest_angle > 0.1);
  CHECK(worst_energy < energy_error_scale(d.settings.step, 2 * link.mass, double_pendulum_w2));
  // The freed brake carries nothing.
  const Reaction<double> brake = joint_reaction(c.model, d, c.weld);
  CHECK(brake.force.norm() == 0.0);
  CHECK(brake.moment.norm() == 0.0);
}

}  // namespace test_runtime_changes
