// Closed loops with redundant constraints. References: IFToMM benchmark A04, Bricard's mechanism
// (Gonzalez, Dopico, Lugris, Cuadrado, Multibody Syst. Dyn. 16 (2006)): 0 DOF by Grubler's
// count, 1 in reality, energy conserved; and a planar loop modelled in 3D (the crane's
// support-boom-rod-cylinder loop), whose redundant revolute version must move exactly like a
// non-redundant version (spherical + universal joint).
#include <cmath>

#include <doctest/doctest.h>

#include <flexstress/dynamics/implicit_integrator.hpp>

namespace test_mechanisms {

using namespace flexstress;

namespace {

// A slender rod of mass m and length l along body x, frame at its centre of mass, square section a.
RigidBody rod_along_x(double m, double l, double a) {
  const double t = m * (l * l + a * a) / 12, ax = m * a * a / 6;
  return RigidBody::rigid(m, Vector3d::Zero(), Vector3d(ax, t, t).asDiagonal());
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

using Bricard = Scene<double, Bodies<RigidBody, RigidBody, RigidBody, RigidBody, RigidBody>,
                      Joints<Revolute<ground, 0>, Revolute<0, 1>, Revolute<1, 2>, Revolute<2, 3>,
                             Revolute<3, 4>, Revolute<4, ground>>,
                      Effects<Gravity, QuadraticVelocity>>;

}  // namespace

TEST_CASE("A04 Bricard mechanism: redundant constraints, runs, energy conserved") {
  // Joint points and axes (derived from the benchmark's figure): O (0,0,0) axis y, A (1,0,0) z,
  // B (1,-1,0) x, C (1,-1,1) y, D (0,-1,1) z, E (0,0,1) x; rods O-A, A-B, B-C, C-D, D-E.
  const Vector3d pts[6] = {{0, 0, 0}, {1, 0, 0}, {1, -1, 0}, {1, -1, 1}, {0, -1, 1}, {0, 0, 1}};
  const Vector3d axes[6] = {Vector3d::UnitY(), Vector3d::UnitZ(), Vector3d::UnitX(),
                            Vector3d::UnitY(), Vector3d::UnitZ(), Vector3d::UnitX()};
  Bricard scene;
  Placed rods[5];
  Bricard::State s;
  for (int i = 0; i < 5; ++i) rods[i] = place_rod(pts[i], pts[i + 1]);
  auto set_body = [&](auto k) {
    constexpr int K = decltype(k)::value;
    scene.body<K>() = rod_along_x(1.0, 1.0, 0.1);
    s.coordinates<K>().position = rods[K].center;
    s.coordinates<K>().theta = from_rotation_matrix<double>(rods[K].axes);
  };
  detail::for_each_index(set_body, std::make_index_sequence<5>{});
  // Joint k at point k: between rod k-1 (or ground) and rod k (or ground); marker z = joint axis.
  auto local = [&](int rod, const Vector3d& p) {
    return Vector3d(rods[rod].axes.transpose() * (p - rods[rod].center));
  };
  auto local_axes = [&](int rod, const Vector3d& a) {
    return Matrix3d(rods[rod].axes.transpose() * frame_with_z_axis<double>(a));
  };
  scene.joint<0>().marker_i = fixed_marker<double>(pts[0], frame_with_z_axis<double>(axes[0]));
  scene.joint<0>().marker_j =
      make_marker(scene.body<0>(), -1, local(0, pts[0]), local_axes(0, axes[0]));
  auto inner = [&](auto k) {
    constexpr int K = decltype(k)::value + 1;  // joints 1..4 between rods K-1 and K
    scene.joint<K>().marker_i =
        make_marker(scene.body<K - 1>(), -1, local(K - 1, pts[K]), local_axes(K - 1, axes[K]));
    scene.joint<K>().marker_j =
        make_marker(scene.body<K>(), -1, local(K, pts[K]), local_axes(K, axes[K]));
  };
  detail::for_each_index(inner, std::make_index_sequence<4>{});
  scene.joint<5>().marker_i =
      make_marker(scene.body<4>(), -1, local(4, pts[5]), local_axes(4, axes[5]));
  scene.joint<5>().marker_j = fixed_marker<double>(pts[5], frame_with_z_axis<double>(axes[5]));

  ImplicitIntegrator<Bricard>::Settings set;
  set.step = 1e-3;
  ImplicitIntegrator<Bricard> integ(scene, set);  // default rho = 0.8
  REQUIRE(integ.initialize(s).ok());
  auto& w = integ.workspace();
  scene.update_kinematics(s, w);
  const double e0 = scene.energy(w).total();
  double drift = 0, travel = 0;
  const Vector3d p3_0 = pts[3];
  for (int i = 0; i < 10000; ++i) {  // 10 s
    const StepStatus st = integ.step(s);
    REQUIRE(st == StepStatus::ok);
    scene.update_kinematics(s, w);
    drift = std::max(drift, std::abs(scene.energy(w).total() - e0));
    const Vector3d p3 =
        s.coordinates<2>().position + rotation_matrix(s.coordinates<2>().theta) * local(2, pts[3]);
    travel = std::max(travel, (p3 - p3_0).norm());
  }
  MESSAGE("Bricard: energy drift " << drift << " J over 10 s (m g L = 9.81 J), point C moved up to "
                                   << travel << " m, iterations/step "
                                   << double(integ.statistics().iterations) / 10000);
  CHECK(travel > 0.1);  // it really moves (1 DOF despite Grubler's 0)
  CHECK(drift < 1e-5 * 9.81);
}

namespace {

// The crane's hydraulic loop with rigid bodies: boom (0) on revolute A at the origin, piston rod
// (2) on the boom at B, cylinder (1) on the ground at C, rod sliding in the cylinder, stroke
// driven. Points from the paper's Table 1.
template <class S>
using Stroke = PolynomialLaw<S>;
template <template <int, int> class JointB, template <int, int> class JointC>
using CraneLoop = Scene<double, Bodies<RigidBody, RigidBody, RigidBody>,
                        Joints<Revolute<ground, 0>, JointC<ground, 1>, JointB<0, 2>,
                               Prismatic<1, 2>, PrismaticDriver<1, 2, Stroke>>,
                        Effects<Gravity, QuadraticVelocity>>;

template <class SceneT>
void build_crane_loop(SceneT& scene, typename SceneT::State& s) {
  const Vector3d a(0, 0, 0), b(0.32, -0.125, 0), c(0, -0.925, 0);
  // Boom: 4.5 m, 67 kg, plus 100 kg at 2.5 m: centre of mass and inertia about it.
  const double mb = 67.0, mp = 100.0, l = 4.5;
  const double m = mb + mp;
  const Vector3d com((mb * l / 2 + mp * 2.5) / m, 0, 0);
  const double iz =
      mb * l * l / 12 + mb * std::pow(l / 2 - com.x(), 2) + mp * std::pow(2.5 - com.x(), 2);
  scene.template body<0>() = RigidBody::rigid(m, com, Vector3d(1.0, iz, iz).asDiagonal());
  const Vector3d cb = (b - c).normalized();
  const Matrix3d frame = frame_with_z_axis<double>(cb);  // marker z along the cylinder
  const Matrix3d planar = frame_with_z_axis<double>(Vector3d::UnitZ());
  scene.template body<1>() =
      RigidBody::rigid(20.0, Vector3d(0, 0, 0.3), Vector3d(2.0, 2.0, 0.02).asDiagonal());
  scene.template body<2>() =
      RigidBody::rigid(10.0, Vector3d(0, 0, -0.3), Vector3d(1.0, 1.0, 0.01).asDiagonal());
  // Cylinder and rod frames: z along C -> B, origin at C (cylinder) and at B (rod).
  s.template coordinates<1>().position = c;
  s.template coordinates<1>().theta = from_rotation_matrix<double>(frame);
  s.template coordinates<2>().position = b;
  s.template coordinates<2>().theta = from_rotation_matrix<double>(frame);
  const Matrix3d to_local = frame.transpose();
  scene.template joint<0>().marker_i = fixed_marker<double>(a, planar);
  scene.template joint<0>().marker_j = make_marker(scene.template body<0>(), -1, a, planar);
  // C: revolute about z, or a universal joint with cross axes z and the cylinder's in-plane normal.
  scene.template joint<1>().marker_i = fixed_marker<double>(c, planar);
  scene.template joint<1>().marker_j =
      make_marker(scene.template body<1>(), -1, Vector3d::Zero(), Matrix3d(to_local * planar));
  if constexpr (SceneT::template joint_equations<1> == 4) {
    // Universal: z_i (global z) perpendicular to z_j, so the body's cross axis must be in-plane.
    const Matrix3d cross = frame_with_z_axis<double>(Vector3d(cb.y(), -cb.x(), 0));
    scene.template joint<1>().marker_j =
        make_marker(scene.template body<1>(), -1, Vector3d::Zero(), Matrix3d(to_local * cross));
  }
  scene.template joint<2>().marker_i = make_marker(scene.template body<0>(), -1, b, planar);
  scene.template joint<2>().marker_j =
      make_marker(scene.template body<2>(), -1, Vector3d::Zero(), Matrix3d(to_local * planar));
  scene.template joint<3>().marker_i = make_marker(scene.template body<1>(), -1, Vector3d::Zero());
  scene.template joint<3>().marker_j = make_marker(scene.template body<2>(), -1, Vector3d::Zero());
  scene.template joint<4>().marker_i = make_marker(scene.template body<1>(), -1, Vector3d::Zero());
  scene.template joint<4>().marker_j = make_marker(scene.template body<2>(), -1, Vector3d::Zero());
  // Stroke from the initial length, extending at 0.05 m/s with 0.1 m/s^2.
  scene.template joint<4>().params.law = Stroke<double>{(b - c).norm(), 0.05, 0.1};
}

template <class State>
double boom_angle(const State& s) {
  const Matrix3d r = rotation_matrix(s.template coordinates<0>().theta);
  return std::atan2(r(1, 0), r(0, 0));
}

template <class SceneT>
std::vector<double> run_crane_loop() {
  SceneT scene;
  typename SceneT::State s;
  build_crane_loop(scene, s);
  typename ImplicitIntegrator<SceneT>::Settings set;
  set.step = 1e-3;
  ImplicitIntegrator<SceneT> integ(scene, set);
  REQUIRE(integ.initialize(s).ok());
  std::vector<double> angle;
  for (int i = 0; i < 2000; ++i) {
    REQUIRE(integ.step(s) == StepStatus::ok);
    angle.push_back(boom_angle(s));
  }
  return angle;
}

}  // namespace

TEST_CASE("a planar loop with redundant revolutes moves like the same loop made non-redundant") {
  using Redundant = CraneLoop<Revolute, Revolute>;
  using Determinate = CraneLoop<Spherical, Universal>;
  static_assert(Redundant::nc == 21 && Redundant::nv == 18, "3 redundant equations");
  static_assert(Determinate::nc == 18, "exactly determinate");
  const auto a = run_crane_loop<Redundant>();
  const auto b = run_crane_loop<Determinate>();
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
  using Loop = CraneLoop<Spherical, Universal>;
  Loop scene;
  Loop::State refreshed;
  build_crane_loop(scene, refreshed);
  ImplicitIntegrator<Loop>::Settings set;
  ImplicitIntegrator<Loop> with(scene, set);
  set.refresh_workspace = false;
  ImplicitIntegrator<Loop> without(scene, set);
  REQUIRE(with.initialize(refreshed).ok());
  Loop::State skipped = refreshed;
  REQUIRE(without.initialize(skipped).ok());
  Loop::Workspace fresh;
  for (int i = 0; i < 300; ++i) {
    REQUIRE(with.step(refreshed) == StepStatus::ok);
    REQUIRE(without.step(skipped) == StepStatus::ok);
    // The refresh only re-evaluates: the next step's first iteration evaluates anyway.
    CHECK(skipped.v == refreshed.v);
    CHECK(skipped.v_dot == refreshed.v_dot);
    CHECK(skipped.lambda == refreshed.lambda);
    CHECK(skipped.coordinates<0>().theta == refreshed.coordinates<0>().theta);
    CHECK(skipped.coordinates<2>().position == refreshed.coordinates<2>().position);
    scene.update_kinematics(refreshed, fresh);
    scene.update_constraints(refreshed, fresh);
    CHECK(with.workspace().phi == fresh.phi);
    CHECK(with.workspace().jac == fresh.jac);
    CHECK(with.workspace().phi_t == fresh.phi_t);
    CHECK(with.workspace().conv == fresh.conv);
  }
}

TEST_CASE("extrapolated multipliers start Newton elsewhere but reach the same motion") {
  // The predictor's multipliers are a starting guess: the converged step solves the same
  // equations to the Newton tolerance either way, so the motions may differ only by that.
  // (What the guess saves is checked on a flexible body, test_flexible_scenes.cpp: on this
  // rigid loop the multipliers change little per step and it saves nothing.)
  using Loop = CraneLoop<Spherical, Universal>;
  Loop scene;
  Loop::State held;
  build_crane_loop(scene, held);
  ImplicitIntegrator<Loop>::Settings set;
  ImplicitIntegrator<Loop> extrapolating(scene, set);
  set.extrapolate_multipliers = false;
  ImplicitIntegrator<Loop> holding(scene, set);
  REQUIRE(holding.initialize(held).ok());
  Loop::State extrapolated = held;
  REQUIRE(extrapolating.initialize(extrapolated).ok());
  double diff = 0, range = 0;
  const double angle0 = boom_angle(held);
  for (int i = 0; i < 2000; ++i) {
    REQUIRE(holding.step(held) == StepStatus::ok);
    REQUIRE(extrapolating.step(extrapolated) == StepStatus::ok);
    diff = std::max(diff, std::abs(boom_angle(held) - boom_angle(extrapolated)));
    range = std::max(range, std::abs(boom_angle(held) - angle0));
  }
  const auto& a = extrapolating.statistics();
  const auto& b = holding.statistics();
  MESSAGE("iterations/step " << double(a.iterations) / a.steps
                             << " (held: " << double(b.iterations) / b.steps
                             << "), factorizations/step " << double(a.factorizations) / a.steps
                             << " (" << double(b.factorizations) / b.steps
                             << "), largest angle difference " << diff << " rad of " << range);
  CHECK(range > 0.05);
  CHECK(diff < 1e-8 * (1 + range));
}

}  // namespace test_mechanisms
