// Compile-time effects and storage. An effect a scene does not name generates no code, so the
// only honest check that nothing is lost or added by leaving it out is to compare with the same
// scene naming the effect but with the effect switched to zero: the motions must agree to
// round-off. Likewise fixed-size and dynamic storage run the same arithmetic and must agree.
// The external-force callback is checked against a reference it must reproduce exactly: a
// point force m g at the centre of mass of a rigid pendulum is the Gravity effect.
//
// The scenes here use dynamic storage (each fixed size instantiates its own Eigen kernels:
// compile time); the storage case names both limits explicitly.
#include <cmath>

#include <doctest/doctest.h>

#include <flexstress/dynamics/energy_audit.hpp>
#include <flexstress/dynamics/explicit_integrator.hpp>
#include <flexstress/dynamics/implicit_integrator.hpp>

#include "fixtures.hpp"

namespace test_effects {

using namespace flexstress;

namespace {

// The hinged beam of test_flexible_scenes: 2 m steel RHS 40 x 20 x 2, revolute about z at x = 0.
testing::BeamBody hinged_beam(int fixed_modes) {
  return testing::make_beam_body(2.0, fe::rectangular_hollow_section(0.04, 0.02, 0.002), 24, {0.0},
                                 fixed_modes);
}

template <int N, class Eff, class Forces = ForceElements<>>
using Hinged = Scene<double, Bodies<FFRFBody<N>>, Joints<Revolute<ground, 0>>, Eff, Forces,
                     FixedGround<double>, 0>;

template <class SceneT>
SceneT make_hinged(const testing::BeamBody& beam) {
  SceneT scene;
  using Body = typename SceneT::template BodyType<0>;
  auto body = Body::from_modal_data(beam.data);
  REQUIRE(body.ok());
  scene.template body<0>() = *body;
  scene.template joint<0>().marker_i = fixed_marker<double>(Vector3d::Zero());
  scene.template joint<0>().marker_j =
      make_marker(scene.template body<0>(), beam.interface_nodes[0], Vector3d::Zero());
  return scene;
}

// Runs `steps` implicit steps from the given initial spin about the hinge and returns the
// coordinates and velocities stacked, for comparison.
template <class SceneT>
Eigen::VectorXd run_implicit(const SceneT& scene, double spin, int steps) {
  ImplicitIntegrator<SceneT> integ(scene);
  typename SceneT::State s;
  s.v(5) = spin;  // body-frame w_z: the frame starts aligned with the ground
  REQUIRE(integ.initialize(s).ok());
  for (int i = 0; i < steps; ++i) REQUIRE(integ.step(s) == StepStatus::ok);
  const auto& q = s.template coordinates<0>();
  Eigen::VectorXd out(3 + 4 + q.p.size() + s.v.size());
  out << q.position, q.theta, q.p, s.v;
  return out;
}

double relative_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).lpNorm<Eigen::Infinity>() / std::max(1e-30, b.lpNorm<Eigen::Infinity>());
}

constexpr int kModes = 2;
constexpr int kSteps = 300;  // 0.3 s at h = 1 ms: the beam swings and flexes visibly

}  // namespace

TEST_CASE("fixed-size and dynamic storage give the same motion") {
  using Base = Hinged<4, Effects<Gravity, QuadraticVelocity, ModalDamping>>;
  using Fixed = Base::with_storage_limit<64>;
  using Dynamic = Base::with_storage_limit<0>;
  static_assert(Fixed::fixed_storage && !Dynamic::fixed_storage);
  static_assert(Fixed::VecV::RowsAtCompileTime == 10 && Dynamic::VecV::RowsAtCompileTime == -1);
  const auto beam = hinged_beam(4);
  const auto a = run_implicit(make_hinged<Fixed>(beam), 1.0, kSteps);
  const auto b = run_implicit(make_hinged<Dynamic>(beam), 1.0, kSteps);
  MESSAGE("implicit, fixed vs dynamic storage: " << relative_difference(a, b));
  CHECK(relative_difference(a, b) < 1e-12);
  // RK4 as well (its own storage paths), from the same initial spin.
  auto rk4 = [&](auto tag) {
    using S = typename decltype(tag)::type;
    const S scene = make_hinged<S>(beam);
    typename ExplicitIntegrator<S>::Settings es;
    es.step = 0.5 / scene.max_modal_frequency();
    ExplicitIntegrator<S> integ(scene, es);
    typename S::State s;
    s.v(5) = 1.0;
    for (int i = 0; i < 200; ++i) REQUIRE(integ.step(s) == StepStatus::ok);
    return Eigen::VectorXd(s.v);
  };
  const Eigen::VectorXd ra = rk4(std::common_type<Fixed>{}), rb = rk4(std::common_type<Dynamic>{});
  MESSAGE("RK4, fixed vs dynamic storage: " << relative_difference(ra, rb));
  CHECK(relative_difference(ra, rb) < 1e-12);
}

TEST_CASE("a scene without an effect moves exactly like one with that effect switched to zero") {
  const auto beam = hinged_beam(kModes);
  SUBCASE("Gravity: left out vs g = 0") {
    using Without = Hinged<kModes, Effects<QuadraticVelocity, ModalDamping>>;
    using With = Hinged<kModes, Effects<Gravity, QuadraticVelocity, ModalDamping>>;
    auto with = make_hinged<With>(beam);
    with.gravity.setZero();
    const double d = relative_difference(run_implicit(make_hinged<Without>(beam), 3.0, kSteps),
                                         run_implicit(with, 3.0, kSteps));
    MESSAGE("relative difference " << d);
    CHECK(d < 1e-13);
  }
  SUBCASE("ModalDamping: left out vs zeta = 0") {
    using Without = Hinged<kModes, Effects<Gravity, QuadraticVelocity>>;
    using With = Hinged<kModes, Effects<Gravity, QuadraticVelocity, ModalDamping>>;
    auto with = make_hinged<With>(beam);
    with.body<0>().set_damping_ratio(0.0);
    const auto a = run_implicit(make_hinged<Without>(beam), 0.0, kSteps);
    const double d = relative_difference(a, run_implicit(with, 0.0, kSteps));
    MESSAGE("relative difference " << d);
    CHECK(d < 1e-13);
    // The comparison can fail: with 2 % damping the motion differs.
    with.body<0>().set_damping_ratio(0.02);
    CHECK(relative_difference(a, run_implicit(with, 0.0, kSteps)) > 1e-9);
  }
  SUBCASE("SpringDampers: left out vs a spring-damper with k = c = preload = 0") {
    using Without = Hinged<kModes, Effects<Gravity, QuadraticVelocity, ModalDamping>>;
    using With = Hinged<kModes, Effects<Gravity, QuadraticVelocity, ModalDamping, SpringDampers>,
                        ForceElements<SpringDamper<ground, 0>>>;
    auto with = make_hinged<With>(beam);
    with.force<0>().marker_i = fixed_marker<double>(Vector3d(2.0, 1.0, 0.0));
    with.force<0>().marker_j =
        make_marker(with.body<0>(), beam.line.node_at(2.0), Vector3d::Zero());
    const auto zero = run_implicit(with, 0.0, kSteps);
    const double d =
        relative_difference(run_implicit(make_hinged<Without>(beam), 0.0, kSteps), zero);
    MESSAGE("relative difference " << d);
    CHECK(d < 1e-13);
    with.force<0>().params.stiffness = 50.0;  // a real spring changes the motion
    CHECK(relative_difference(run_implicit(with, 0.0, kSteps), zero) > 1e-6);
  }
  SUBCASE("ExternalForces: left out vs no callback vs a callback that adds nothing") {
    using Without = Hinged<kModes, Effects<Gravity, QuadraticVelocity, ModalDamping>>;
    using With = Hinged<kModes, Effects<Gravity, QuadraticVelocity, ModalDamping, ExternalForces>>;
    auto with = make_hinged<With>(beam);
    const auto a = run_implicit(make_hinged<Without>(beam), 0.0, kSteps);
    CHECK(relative_difference(a, run_implicit(with, 0.0, kSteps)) < 1e-13);
    with.external_forces = [](const With&, double, With::Workspace&, void*) {};
    CHECK(relative_difference(a, run_implicit(with, 0.0, kSteps)) < 1e-13);
  }
}

namespace {

// A rigid pendulum (1 kg, 1 m, released horizontal) with gravity as an effect, and with gravity
// applied by the external-force callback as a point force m g at the centre of mass.
using GravityPendulum = Scene<double, Bodies<RigidBody>, Joints<Revolute<ground, 0>>,
                              Effects<Gravity>>::with_storage_limit<0>;
using CallbackPendulum = Scene<double, Bodies<RigidBody>, Joints<Revolute<ground, 0>>,
                               Effects<ExternalForces>>::with_storage_limit<0>;

template <class SceneT>
SceneT make_pendulum() {
  SceneT scene;
  scene.template body<0>() = RigidBody::rigid(1.0, Vector3d::Zero(), Matrix3d::Identity() * 1e-3);
  scene.template joint<0>().marker_i = fixed_marker<double>(Vector3d::Zero());
  scene.template joint<0>().marker_j =
      make_marker(scene.template body<0>(), -1, Vector3d(-1, 0, 0));
  return scene;
}

struct PointGravity {
  Marker<double, 0> center;
  Vector3d weight;
};

template <class SceneT>
Eigen::VectorXd swing(const SceneT& scene) {
  ImplicitIntegrator<SceneT> integ(scene);
  typename SceneT::State s;
  s.template coordinates<0>().position = Vector3d(1, 0, 0);
  REQUIRE(integ.initialize(s).ok());
  for (int i = 0; i < 500; ++i) REQUIRE(integ.step(s) == StepStatus::ok);
  Eigen::VectorXd out(13);
  out << s.template coordinates<0>().position, s.template coordinates<0>().theta, s.v;
  return out;
}

}  // namespace

TEST_CASE("an external-force callback applying m g at the centre of mass reproduces Gravity") {
  const auto reference = swing(make_pendulum<GravityPendulum>());
  auto scene = make_pendulum<CallbackPendulum>();
  PointGravity g{make_marker(scene.body<0>(), -1, Vector3d::Zero()), Vector3d(0, -9.81, 0)};
  scene.external_forces = [](const CallbackPendulum& sc, double, CallbackPendulum::Workspace& w,
                             void* user) {
    const auto& pg = *static_cast<const PointGravity*>(user);
    sc.add_point_force<0>(w, pg.center, pg.weight);
  };
  scene.external_forces_user = &g;
  const auto result = swing(scene);
  const double d = relative_difference(result, reference);
  MESSAGE("callback vs Gravity effect after 0.5 s: " << d);
  CHECK(d < 1e-12);
  CHECK(result(1) < -0.5);  // it did swing down (released horizontal, 0.5 s)
}

namespace {

// The hinged beam spun up by a revolute driver (constant angular acceleration from rest, so the
// sudden inertial load sets the beam vibrating) in the vertical plane, with gravity, the
// quadratic velocity terms and 5 % modal damping.
using DrivenBeam = Scene<double, Bodies<FFRFBody<kModes>>,
                         Joints<Revolute<ground, 0>, RevoluteDriver<ground, 0, PolynomialLaw>>,
                         Effects<Gravity, QuadraticVelocity, ModalDamping>, ForceElements<>,
                         FixedGround<double>, 0>;

struct Audit {
  double residual, change, work, dissipated;
};

Audit audit_spin_up(double h) {
  const auto beam = hinged_beam(kModes);
  DrivenBeam scene;
  auto body = FFRFBody<kModes>::from_modal_data(beam.data);
  REQUIRE(body.ok());
  scene.body<0>() = *body;
  scene.body<0>().set_damping_ratio(0.05);
  for (auto* m : {&scene.joint<0>().marker_i, &scene.joint<1>().marker_i})
    *m = fixed_marker<double>(Vector3d::Zero());
  for (auto* m : {&scene.joint<0>().marker_j, &scene.joint<1>().marker_j})
    *m = make_marker(scene.body<0>(), beam.interface_nodes[0], Vector3d::Zero());
  scene.joint<1>().params.law.a = 40.0;  // rad/s^2: 8 rad/s after 0.2 s
  ImplicitIntegrator<DrivenBeam>::Settings settings;
  settings.step = h;
  ImplicitIntegrator<DrivenBeam> integ(scene, settings);
  DrivenBeam::State s;
  REQUIRE(integ.initialize(s).ok());
  EnergyAudit<DrivenBeam> audit(scene);
  audit.start(s);
  const int steps = static_cast<int>(std::lround(0.2 / h));
  for (int i = 0; i < steps; ++i) {
    REQUIRE(integ.step(s) == StepStatus::ok);
    audit.record(s);
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
