// Closed loops with redundant constraints. References: IFToMM benchmark A04, Bricard's mechanism
// (Gonzalez, Dopico, Lugris, Cuadrado, Multibody Syst. Dyn. 16 (2006)): 0 DOF by Grubler's
// count, 1 in reality, energy conserved; and a planar loop modelled in 3D (the crane's
// support-boom-rod-cylinder loop), whose redundant revolute version must move exactly like a
// non-redundant version (spherical + universal joint).
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <doctest/doctest.h>

#include <flexstress/model/all.hpp>

namespace test_mechanisms {

using namespace flexstress;

namespace {

// A slender rod of mass m and length l along body x, frame at its centre of mass, square section
// a: its mass and its inertia about the centre of mass.
struct Rod {
  double mass;
  Matrix3d inertia;
};
Rod rod_along_x(double m, double l, double a) {
  const double t = m * (l * l + a * a) / 12, ax = m * a * a / 6;
  return {m, Vector3d(ax, t, t).asDiagonal()};
}

// A rod from point p to point q: body frame with x along q - p, at the centre.
struct Placed {
  Vector3d center;
  Matrix3d axes;
};
Placed place_rod(const Vector3d& p, const Vector3d& q) {
  Placed r;
  r.center = 0.5 * (p + q);
  const Vector3d x = (q - p).normalized();
  const Vector3d helper = std::abs(x.z()) < 0.9 ? Vector3d::UnitZ() : Vector3d::UnitY();
  r.axes.col(0) = x;
  r.axes.col(1) = helper.cross(x).normalized();
  r.axes.col(2) = x.cross(r.axes.col(1));
  return r;
}

// finalize(), failing with its message (error() is valid only on failure, so not as a
// REQUIRE_MESSAGE argument: doctest -s evaluates that on success too).
Model<double> finalized(const ModelBuilder<double>& b) {
  auto m = b.finalize();
  if (!m.ok()) FAIL(m.error().what());
  return std::move(*m);
}

}  // namespace

TEST_CASE("A04 Bricard mechanism: redundant constraints, runs, energy conserved") {
  // Joint points and axes (derived from the benchmark's figure): O (0,0,0) axis y, A (1,0,0) z,
  // B (1,-1,0) x, C (1,-1,1) y, D (0,-1,1) z, E (0,0,1) x; rods O-A, A-B, B-C, C-D, D-E.
  const Vector3d pts[6] = {{0, 0, 0}, {1, 0, 0}, {1, -1, 0}, {1, -1, 1}, {0, -1, 1}, {0, 0, 1}};
  const Vector3d axes[6] = {Vector3d::UnitY(), Vector3d::UnitZ(), Vector3d::UnitX(),
                            Vector3d::UnitY(), Vector3d::UnitZ(), Vector3d::UnitX()};
  ModelBuilder<double> b;
  Placed rods[5];
  BodyId body[5];
  for (int i = 0; i < 5; ++i) {
    rods[i] = place_rod(pts[i], pts[i + 1]);
    const Rod rod = rod_along_x(1.0, 1.0, 0.1);
    body[i] = b.add_rigid_body("rod " + std::to_string(i), rod.mass, Vector3d::Zero(), rod.inertia);
    b.set_initial_pose(body[i], rods[i].center, from_rotation_matrix<double>(rods[i].axes));
  }
  // Joint k at point k: between rod k-1 (or ground) and rod k (or ground); marker z = joint axis.
  auto local = [&](int rod, const Vector3d& p) {
    return Vector3d(rods[rod].axes.transpose() * (p - rods[rod].center));
  };
  auto local_axes = [&](int rod, const Vector3d& a) {
    return Matrix3d(rods[rod].axes.transpose() * frame_with_z_axis<double>(a));
  };
  auto marker = [&](int rod, int k) {
    const std::string name = "joint " + std::to_string(k) + " on rod " + std::to_string(rod);
    return b.add_marker(name, body[rod], -1, local(rod, pts[k]), local_axes(rod, axes[k]));
  };
  auto fixed = [&](int k) {
    return b.add_marker("joint " + std::to_string(k) + " on ground", b.ground(), -1, pts[k],
                        frame_with_z_axis<double>(axes[k]));
  };
  b.add_joint("O", JointKind::revolute, fixed(0), marker(0, 0));
  MarkerId on_c = {};
  for (int k = 1; k < 5; ++k) {
    const MarkerId mi = marker(k - 1, k);
    const MarkerId mj = marker(k, k);
    if (k == 3) on_c = mi;  // point C on rod 2
    b.add_joint("joint " + std::to_string(k), JointKind::revolute, mi, mj);
  }
  b.add_joint("E", JointKind::revolute, marker(4, 5), fixed(5));
  b.set_gravity(Vector3d(0, -9.81, 0));
  b.settings().step = 1e-3;  // default rho = 0.8
  const Model<double> m = finalized(b);
  Data<double> d(m);
  REQUIRE(initialize(m, d).ok());
  const double e0 = energy(m, d).total();
  double drift = 0, travel = 0;
  const Vector3d p3_0 = pts[3];
  for (int i = 0; i < 10000; ++i) {  // 10 s
    const StepStatus st = step(m, d);
    REQUIRE(st == StepStatus::ok);
    drift = std::max(drift, std::abs(energy(m, d).total() - e0));
    const Vector3d p3 = marker_frame(m, d, on_c).origin;
    travel = std::max(travel, (p3 - p3_0).norm());
  }
  MESSAGE("Bricard: energy drift " << drift << " J over 10 s (m g L = 9.81 J), point C moved up to "
                                   << travel << " m, iterations/step "
                                   << double(d.statistics.iterations) / 10000);
  CHECK(travel > 0.1);  // it really moves (1 DOF despite Grubler's 0)
  CHECK(drift < 1e-5 * 9.81);
}

namespace {

// The crane's hydraulic loop with rigid bodies: boom on revolute A at the origin, piston rod on
// the boom at B, cylinder on the ground at C, rod sliding in the cylinder, stroke driven. Points
// from the paper's Table 1.
struct CraneLoop {
  Model<double> model;
  BodyId boom, cylinder, rod;
};

CraneLoop build_crane_loop(JointKind joint_b, JointKind joint_c) {
  ModelBuilder<double> mb;
  CraneLoop loop;
  const Vector3d a(0, 0, 0), b(0.32, -0.125, 0), c(0, -0.925, 0);
  // Boom: 4.5 m, 67 kg, plus 100 kg at 2.5 m: centre of mass and inertia about it.
  const double m_boom = 67.0, m_payload = 100.0, l = 4.5;
  const double m = m_boom + m_payload;
  const Vector3d com((m_boom * l / 2 + m_payload * 2.5) / m, 0, 0);
  const double iz = m_boom * l * l / 12 + m_boom * std::pow(l / 2 - com.x(), 2) +
                    m_payload * std::pow(2.5 - com.x(), 2);
  loop.boom = mb.add_rigid_body("boom", m, com, Vector3d(1.0, iz, iz).asDiagonal());
  const Vector3d cb = (b - c).normalized();
  const Matrix3d frame = frame_with_z_axis<double>(cb);  // marker z along the cylinder
  const Matrix3d planar = frame_with_z_axis<double>(Vector3d::UnitZ());
  loop.cylinder = mb.add_rigid_body("cylinder", 20.0, Vector3d(0, 0, 0.3),
                                    Vector3d(2.0, 2.0, 0.02).asDiagonal());
  loop.rod =
      mb.add_rigid_body("rod", 10.0, Vector3d(0, 0, -0.3), Vector3d(1.0, 1.0, 0.01).asDiagonal());
  // Cylinder and rod frames: z along C -> B, origin at C (cylinder) and at B (rod).
  mb.set_initial_pose(loop.cylinder, c, from_rotation_matrix<double>(frame));
  mb.set_initial_pose(loop.rod, b, from_rotation_matrix<double>(frame));
  const Matrix3d to_local = frame.transpose();
  mb.add_joint("A", JointKind::revolute, mb.add_marker("A on ground", mb.ground(), -1, a, planar),
               mb.add_marker("A on boom", loop.boom, -1, a, planar));
  // C: revolute about z, or a universal joint with cross axes z and the cylinder's in-plane normal.
  // Universal: z_i (global z) perpendicular to z_j, so the body's cross axis must be in-plane.
  const Matrix3d c_axes =
      joint_c == JointKind::universal
          ? Matrix3d(to_local * frame_with_z_axis<double>(Vector3d(cb.y(), -cb.x(), 0)))
          : Matrix3d(to_local * planar);
  mb.add_joint("C", joint_c, mb.add_marker("C on ground", mb.ground(), -1, c, planar),
               mb.add_marker("C on cylinder", loop.cylinder, -1, Vector3d::Zero(), c_axes));
  mb.add_joint("B", joint_b, mb.add_marker("B on boom", loop.boom, -1, b, planar),
               mb.add_marker("B on rod", loop.rod, -1, Vector3d::Zero(), to_local * planar));
  const MarkerId cylinder_axis = mb.add_marker("cylinder axis", loop.cylinder, -1);
  const MarkerId rod_axis = mb.add_marker("rod axis", loop.rod, -1);
  mb.add_joint("slide", JointKind::prismatic, cylinder_axis, rod_axis);
  // Stroke from the initial length, extending at 0.05 m/s with 0.1 m/s^2.
  mb.add_driver("stroke", JointKind::prismatic_driver, cylinder_axis, rod_axis,
                MotionLaw<double>::constant_acceleration((b - c).norm(), 0.05, 0.1));
  mb.set_gravity(Vector3d(0, -9.81, 0));
  loop.model = finalized(mb);
  return loop;
}

double boom_angle(const CraneLoop& loop, const Data<double>& d) {
  const Matrix3d r = rotation_matrix(body_orientation(loop.model, d, loop.boom));
  return std::atan2(r(1, 0), r(0, 0));
}

std::vector<double> run_crane_loop(const CraneLoop& loop) {
  Data<double> d(loop.model);
  set_step_size(d, 1e-3);
  REQUIRE(initialize(loop.model, d).ok());
  std::vector<double> angle;
  for (int i = 0; i < 2000; ++i) {
    REQUIRE(step(loop.model, d) == StepStatus::ok);
    angle.push_back(boom_angle(loop, d));
  }
  return angle;
}

}  // namespace

TEST_CASE("a planar loop with redundant revolutes moves like the same loop made non-redundant") {
  const CraneLoop redundant = build_crane_loop(JointKind::revolute, JointKind::revolute);
  const CraneLoop determinate = build_crane_loop(JointKind::spherical, JointKind::universal);
  // 3 redundant equations; the other loop exactly determinate.
  REQUIRE(redundant.model.num_constraints() == 21);
  REQUIRE(redundant.model.num_velocities() == 18);
  REQUIRE(determinate.model.num_constraints() == 18);
  const auto a = run_crane_loop(redundant);
  const auto b = run_crane_loop(determinate);
  double diff = 0, range = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    diff = std::max(diff, std::abs(a[i] - b[i]));
    range = std::max(range, std::abs(a[i] - a[0]));
  }
  MESSAGE("boom angle travel " << range << " rad, largest difference " << diff << " rad");
  CHECK(range > 0.05);
  CHECK(diff < 1e-8 * (1 + range));
}

TEST_CASE(
    "a step without the workspace refresh moves the same; with it, the workspace is current") {
  const CraneLoop loop = build_crane_loop(JointKind::spherical, JointKind::universal);
  const Model<double>& m = loop.model;
  Data<double> refreshed(m), skipped(m);
  skipped.settings.refresh_workspace = false;
  REQUIRE(initialize(m, refreshed).ok());
  REQUIRE(initialize(m, skipped).ok());
  // Evaluated from the refreshed state alone, in a Data of its own.
  Data<double> fresh(m);
  for (int i = 0; i < 300; ++i) {
    REQUIRE(step(m, refreshed) == StepStatus::ok);
    REQUIRE(step(m, skipped) == StepStatus::ok);
    // The refresh only re-evaluates: the next step's first iteration evaluates anyway.
    CHECK(skipped.v == refreshed.v);
    CHECK(skipped.v_dot == refreshed.v_dot);
    CHECK(skipped.lambda == refreshed.lambda);
    CHECK(body_orientation(m, skipped, loop.boom) == body_orientation(m, refreshed, loop.boom));
    CHECK(body_position(m, skipped, loop.rod) == body_position(m, refreshed, loop.rod));
    fresh.t = refreshed.t;
    fresh.q = refreshed.q;
    fresh.v = refreshed.v;
    update_kinematics(m, fresh);
    update_markers(m, fresh);
    update_constraints(m, fresh);
    CHECK(refreshed.phi == fresh.phi);
    CHECK(refreshed.jacobian == fresh.jacobian);
    CHECK(refreshed.phi_t == fresh.phi_t);
    CHECK(refreshed.conv == fresh.conv);
  }
}

TEST_CASE("extrapolated multipliers start Newton elsewhere but reach the same motion") {
  // The predictor's multipliers are a starting guess: the converged step solves the same
  // equations to the Newton tolerance either way, so the motions may differ only by that.
  // (What the guess saves is checked on a flexible body, test_flexible_models.cpp: on this
  // rigid loop the multipliers change little per step and it saves nothing.)
  const CraneLoop loop = build_crane_loop(JointKind::spherical, JointKind::universal);
  const Model<double>& m = loop.model;
  Data<double> held(m), extrapolated(m);
  held.settings.extrapolate_multipliers = false;
  REQUIRE(initialize(m, held).ok());
  REQUIRE(initialize(m, extrapolated).ok());
  double diff = 0, range = 0;
  const double angle0 = boom_angle(loop, held);
  for (int i = 0; i < 2000; ++i) {
    REQUIRE(step(m, held) == StepStatus::ok);
    REQUIRE(step(m, extrapolated) == StepStatus::ok);
    diff = std::max(diff, std::abs(boom_angle(loop, held) - boom_angle(loop, extrapolated)));
    range = std::max(range, std::abs(boom_angle(loop, held) - angle0));
  }
  const auto& a = extrapolated.statistics;
  const auto& b = held.statistics;
  MESSAGE("iterations/step " << double(a.iterations) / a.steps
                             << " (held: " << double(b.iterations) / b.steps
                             << "), factorizations/step " << double(a.factorizations) / a.steps
                             << " (" << double(b.factorizations) / b.steps
                             << "), largest angle difference " << diff << " rad of " << range);
  CHECK(range > 0.05);
  CHECK(diff < 1e-8 * (1 + range));
}

// A rigid link swinging on a pivot at its body frame, released horizontal: the matrix turned with
// the link (corotate_factorization) is the fresh one, so a reused factorization must converge
// as a fresh one does. The residual as forces rises after its good corrections (the constraint
// forces that the multiplier updates settle), which must not undo them.
TEST_CASE("a rigid link on a pivot keeps its reused factorization and follows the fresh one") {
  struct Run {
    double iterations, factorizations;
    Vector3d velocity;
    double fastest_swing;  // largest |omega| over the run (rad/s)
  };
  const auto swing = [](bool reuse) {
    ModelBuilder<double> b;
    const BodyId link = b.add_rigid_body("link", 1.0, Vector3d(0.5, 0, 0),
                                         Vector3d(1e-4, 1.0 / 12, 1.0 / 12).asDiagonal());
    b.add_joint("pivot", JointKind::revolute, b.add_marker("pivot on ground", b.ground(), -1),
                b.add_marker("pivot on link", link, -1));
    b.set_gravity(Vector3d(0, -9.81, 0));
    const Model<double> m = finalized(b);
    Data<double> d(m);
    ImplicitSettings<double> s = d.settings;
    s.reuse_factorization = reuse;
    REQUIRE(set_settings(m, d, s).ok());
    REQUIRE(initialize(m, d).ok());
    const int steps = 2000;  // 2 s at the default 1 ms: swings through the bottom and back
    StepStatus status = StepStatus::ok;
    double fastest = 0;
    for (int i = 0; i < steps && status == StepStatus::ok; ++i) {
      status = step(m, d);
      fastest = std::max(fastest, body_angular_velocity(m, d, link).norm());
    }
    REQUIRE(status == StepStatus::ok);
    return Run{double(d.statistics.iterations) / steps, double(d.statistics.factorizations) / steps,
               body_velocity(m, d, link), fastest};
  };
  const Run reused = swing(true), fresh = swing(false);
  MESSAGE("reused: " << reused.iterations << " iterations, " << reused.factorizations
                     << " factorizations per step; fresh: " << fresh.iterations);
  CHECK(reused.factorizations < 0.1);
  CHECK(reused.iterations <= fresh.iterations + 0.05);
  // Both converge to the Newton tolerance: the same motion.
  CHECK((reused.velocity - fresh.velocity).norm() < 1e-6 * (1 + fresh.velocity.norm()));
  // And the right one: energy conservation, m g L/2 = I_pivot omega^2 / 2 with I_pivot = m L^2/3,
  // gives omega = sqrt(3 g / L) as the link passes the bottom (at about 0.5 s).
  const double omega_bottom = std::sqrt(3 * 9.81 / 1.0);
  MESSAGE("fastest swing " << reused.fastest_swing << " rad/s, energy conservation "
                           << omega_bottom);
  CHECK(std::abs(reused.fastest_swing - omega_bottom) < 1e-4 * omega_bottom);
}

}  // namespace test_mechanisms
