// Flexible bodies in scenes. References: the full FE model (pinned-free beam frequencies and the
// static deflection under self-weight, solved by the FE kernel without reduction), convergence
// as modes are added, and the stability theory of the integrators (A-stable implicit, RK4
// bounded by h w <= 2.78).
#include <cmath>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include <flexstress/dynamics/checkpoint.hpp>
#include <flexstress/dynamics/explicit_integrator.hpp>
#include <flexstress/dynamics/implicit_integrator.hpp>
#include <flexstress/dynamics/linearize.hpp>
#include <flexstress/dynamics/static_equilibrium.hpp>
#include <flexstress/fe/eigen_solver.hpp>
#include <flexstress/fe/static_solver.hpp>

#include "fixtures.hpp"

namespace test_flexible_scenes {

using namespace flexstress;

namespace {

// A 2 m steel RHS 40 x 20 x 2 mm beam hinged at x = 0 (revolute about z): slender enough that
// gravity bends it visibly, stiff enough to have kHz modes.
const fe::BeamSection kSection = fe::rectangular_hollow_section(0.04, 0.02, 0.002);
constexpr double kLength = 2.0;

testing::BeamBody hinged_beam(int fixed_modes) {
  return testing::make_beam_body(kLength, kSection, 24, {0.0}, fixed_modes);
}

// Dynamic storage: every fixed size would instantiate its own Eigen kernels (twice the compile
// time of this file); test_effects.cpp shows both storages give the same motion.
constexpr int kStorage = 0;

template <int N, class Scalar = double, class Eff = Effects<Gravity, QuadraticVelocity>>
using Hinged = typename Scene<Scalar, Bodies<FFRFBody<N, Scalar>>, Joints<Revolute<ground, 0>>,
                              Eff>::template with_storage_limit<kStorage>;

template <class SceneT>
SceneT make_hinged(const reduction::ModalBodyData& data, Index hinge_node) {
  SceneT scene;
  using Body = typename SceneT::template BodyType<0>;
  auto body = Body::from_modal_data(data);
  REQUIRE(body.ok());
  scene.template body<0>() = *body;
  using S = typename SceneT::scalar_type;
  scene.template joint<0>().marker_i = fixed_marker<S>(Vec3<S>::Zero());
  scene.template joint<0>().marker_j =
      make_marker(scene.template body<0>(), hinge_node, Vec3<S>::Zero());
  return scene;
}

}  // namespace

// The mode counts below (2, 4, 8, 16 and float 4) are shared between the cases on purpose: each
// count instantiates the whole scene and integrators once more (compile time).

TEST_CASE("hinged flexible beam: linearized scene frequencies equal the pinned-free FE model's") {
  constexpr int N = 16;
  auto beam = hinged_beam(N);
  auto scene = make_hinged<Hinged<N>>(beam.data, beam.interface_nodes[0]);
  scene.gravity.setZero();
  Hinged<N>::State s;
  auto lin = linearize(scene, s);
  REQUIRE(lin.ok());
  // Reference: the full FE beam with a hinge (translations and rx, ry fixed at x = 0).
  fe::BoundaryConditions bc;
  const Index root = beam.interface_nodes[0];
  bc.pin(root).fix(root, 3).fix(root, 4);
  auto full = fe::assemble(beam.mesh, bc);
  REQUIRE(full.ok());
  fe::EigenOptions eo;
  eo.num_modes = 6;
  auto ref = fe::solve_eigen(full->stiffness, full->mass, eo);
  REQUIRE(ref.ok());
  // The scene has one zero-frequency motion (the free rotation); compare the next ones.
  CHECK(std::abs(lin->frequencies_hz(0)) < 1e-3);
  const VectorXd fe_hz = ref->frequencies_hz();
  for (int i = 1; i < 6; ++i) {
    CAPTURE(i);
    const double f = lin->frequencies_hz(i), fr = fe_hz(i);
    MESSAGE("mode " << i << ": scene " << f << " Hz, FE " << fr << " Hz");
    CHECK(f >= fr * (1 - 1e-6));                    // Rayleigh-Ritz: never below the full model
    CHECK(f == doctest::Approx(fr).epsilon(1e-3));  // within the reduction's own error
  }
}

namespace {

template <int N>
Vector3d flexible_pendulum_tip(double t_end) {
  auto beam = hinged_beam(N);
  auto scene = make_hinged<Hinged<N>>(beam.data, beam.interface_nodes[0]);
  typename Hinged<N>::State s;
  ImplicitIntegrator<Hinged<N>> integ(scene);
  REQUIRE(integ.initialize(s).ok());
  const int steps = static_cast<int>(std::lround(t_end / integ.settings().step));
  for (int i = 0; i < steps; ++i) REQUIRE(integ.step(s) == StepStatus::ok);
  const Index tip = beam.line.nodes.back();
  const auto& q = s.template coordinates<0>();
  const Vector3d local = scene.template body<0>().point(tip).local([&] {
    BodyKinematics<double, N> k;
    k.p = q.p;
    return k;
  }());
  return q.position + rotation_matrix(q.theta) * local;
}

}  // namespace

TEST_CASE("flexible pendulum under gravity converges as modes are added") {
  const Vector3d t2 = flexible_pendulum_tip<2>(0.5), t4 = flexible_pendulum_tip<4>(0.5),
                 t8 = flexible_pendulum_tip<8>(0.5), t16 = flexible_pendulum_tip<16>(0.5);
  const double e2 = (t2 - t16).norm(), e4 = (t4 - t16).norm(), e8 = (t8 - t16).norm();
  MESSAGE("tip at 0.5 s, distance to the 16-mode result: 2 modes " << e2 << " m, 4 modes " << e4
                                                                   << " m, 8 modes " << e8 << " m");
  CHECK(e4 < e2);
  CHECK(e8 < e4);
  CHECK(e8 < 1e-3 * kLength);
  // It really swung (released horizontal, the tip falls about a metre in 0.5 s).
  CHECK(t16.y() < -0.5);
}

// Two runs of the flexible beam released horizontal (Hinged<8>, 0.5 s), the second with one
// setting changed by `change`: a setting of the modified Newton changes where Newton starts or
// which matrix it uses, not the equations it converges to, so the motions differ by the
// solver's tolerance, acceleration errors of tol = 1e-5 m/s^2 moving the tip by at most tol t^2
// in t. Returns the statistics of both runs.
struct SwingPair {
  ImplicitIntegrator<Hinged<8>>::Statistics with_default, changed;
};
template <class Change>
SwingPair same_swing(const std::string& what, Change change) {
  auto beam = hinged_beam(8);
  auto scene = make_hinged<Hinged<8>>(beam.data, beam.interface_nodes[0]);
  ImplicitIntegrator<Hinged<8>>::Settings set;
  ImplicitIntegrator<Hinged<8>> by_default(scene, set);
  change(set);
  ImplicitIntegrator<Hinged<8>> other(scene, set);
  Hinged<8>::State a, b;
  REQUIRE(by_default.initialize(a).ok());
  REQUIRE(other.initialize(b).ok());
  const Index tip = beam.line.nodes.back();
  const auto tip_of = [&](const Hinged<8>::State& s) {
    const auto& q = s.coordinates<0>();
    BodyKinematics<double, 8> k;
    k.p = q.p;
    return Vector3d(q.position + rotation_matrix(q.theta) * scene.body<0>().point(tip).local(k));
  };
  const double t_end = 0.5;
  double diff = 0;
  for (int i = 0; i < 500; ++i) {
    REQUIRE(by_default.step(a) == StepStatus::ok);
    REQUIRE(other.step(b) == StepStatus::ok);
    diff = std::max(diff, (tip_of(a) - tip_of(b)).norm());
  }
  const auto& sa = by_default.statistics();
  const auto& sb = other.statistics();
  MESSAGE("iterations/step " << double(sa.iterations) / sa.steps << " (" << what << ": "
                             << double(sb.iterations) / sb.steps << "), factorizations/step "
                             << double(sa.factorizations) / sa.steps << " ("
                             << double(sb.factorizations) / sb.steps << "), largest tip difference "
                             << diff << " m");
  CHECK(tip_of(a).y() < -0.5);  // it swung
  CHECK(diff < set.acceleration_tolerance * t_end * t_end);
  return {sa, sb};
}

TEST_CASE("extrapolated multipliers: the same swing of a flexible beam") {
  // What the predictor's multipliers save in iterations is the crane's (docs/performance.md);
  // on this swing the guess saves nothing, so only the motion is checked.
  same_swing("held", [](auto& set) { set.extrapolate_multipliers = false; });
}

TEST_CASE("a reused factorization turned with the bodies: the same swing, fewer factorizations") {
  // Settings::corotate_factorization: the beam swings through 90 degrees in 0.5 s, and a matrix
  // kept from an earlier angle is stale in its own rotation blocks unless turned with it.
  const SwingPair runs =
      same_swing("not turned", [](auto& set) { set.corotate_factorization = false; });
  CHECK(2 * runs.with_default.factorizations < runs.changed.factorizations);
  CHECK(runs.with_default.iterations < runs.changed.iterations);
}

TEST_CASE("stiff modes: kHz modes stay stable at h = 1 ms (implicit); RK4 refuses that step") {
  constexpr int N = 16;
  auto beam = hinged_beam(N);
  auto scene = make_hinged<Hinged<N>>(beam.data, beam.interface_nodes[0]);
  const double f_max = scene.max_modal_frequency() / (2 * 3.14159265358979323846);
  MESSAGE("highest modal frequency " << f_max << " Hz");
  REQUIRE(f_max > 2000.0);  // h w > 12 at h = 1 ms: far outside RK4's bound 2.78
  Hinged<N>::State s;
  // Excite every mode: the implicit integrator must damp or keep them, never amplify.
  for (int k = 0; k < N; ++k) s.coordinates<0>().p(k) = 1e-4;
  ImplicitIntegrator<Hinged<N>> integ(scene);  // h = 1 ms, rho = 0.8
  const Status init = integ.initialize(s);
  if (!init) MESSAGE(init.error().what());
  REQUIRE(init.ok());
  auto& w = integ.workspace();
  scene.update_kinematics(s, w);
  const double e0 = scene.energy(w).total();
  double e_max = e0;
  for (int i = 0; i < 2000; ++i) {
    REQUIRE(integ.step(s) == StepStatus::ok);
    scene.update_kinematics(s, w);
    e_max = std::max(e_max, scene.energy(w).total());
  }
  CHECK(s.v.allFinite());
  CHECK(e_max <= e0 + 1e-9 * std::abs(e0));
  // The explicit integrator reports the stability violation instead of blowing up.
  ExplicitIntegrator<Hinged<N>>::Settings es;
  es.step = 1e-3;
  ExplicitIntegrator<Hinged<N>> rk4(scene, es);
  Hinged<N>::State s2;
  CHECK(rk4.stability_number() > 2.78);
  CHECK(rk4.step(s2) == StepStatus::step_above_stability_limit);
  CHECK(s2.t == 0.0);  // nothing was done
}

TEST_CASE("explicit RK4 agrees with the implicit integrator on a non-stiff flexible pendulum") {
  constexpr int N = 2;
  auto beam = hinged_beam(N);
  auto scene = make_hinged<Hinged<N>>(beam.data, beam.interface_nodes[0]);
  ExplicitIntegrator<Hinged<N>>::Settings es;
  es.step = 0.5 / scene.max_modal_frequency();  // h w = 0.5
  ExplicitIntegrator<Hinged<N>> rk4(scene, es);
  Hinged<N>::State a;
  for (double t = 0; t < 0.3 - 1e-12; t += es.step) REQUIRE(rk4.step(a) == StepStatus::ok);
  ImplicitIntegrator<Hinged<N>>::Settings is;
  is.step = es.step / 4;
  ImplicitIntegrator<Hinged<N>> gen(scene, is);
  Hinged<N>::State b;
  REQUIRE(gen.initialize(b).ok());
  while (b.t < a.t - 1e-12) REQUIRE(gen.step(b) == StepStatus::ok);
  const double diff = (a.coordinates<0>().position - b.coordinates<0>().position).norm() +
                      (a.coordinates<0>().theta - b.coordinates<0>().theta).norm();
  MESSAGE("RK4 vs generalized-alpha after " << a.t << " s: " << diff);
  CHECK(diff < 1e-4);
}

TEST_CASE("an explicit (RK4) run restored from its checkpoint continues bit-identically") {
  // Reference: the run that never stopped. RK4 starts each step from the State alone, so the
  // state (modal coordinates included) is all a checkpoint needs.
  constexpr int N = 2;
  auto beam = hinged_beam(N);
  auto scene = make_hinged<Hinged<N>>(beam.data, beam.interface_nodes[0]);
  ExplicitIntegrator<Hinged<N>>::Settings es;
  es.step = 0.5 / scene.max_modal_frequency();
  ExplicitIntegrator<Hinged<N>> rk4(scene, es);
  Hinged<N>::State a;
  std::vector<unsigned char> bytes;
  for (int i = 0; i < 200; ++i) {
    if (i == 80) {
      auto saved = save_checkpoint(a, rk4);
      REQUIRE(saved.ok());
      bytes = *saved;
    }
    REQUIRE(rk4.step(a) == StepStatus::ok);
  }
  ExplicitIntegrator<Hinged<N>> resumed(scene, es);
  Hinged<N>::State b;  // a fresh state: everything comes from the checkpoint
  REQUIRE(restore_checkpoint(bytes.data(), bytes.size(), b, resumed).ok());
  for (int i = 80; i < 200; ++i) REQUIRE(resumed.step(b) == StepStatus::ok);
  CHECK(b.t == a.t);
  CHECK(b.coordinates<0>().position == a.coordinates<0>().position);
  CHECK(b.coordinates<0>().theta == a.coordinates<0>().theta);
  CHECK(b.coordinates<0>().p == a.coordinates<0>().p);
  CHECK(b.coordinates<0>().p.norm() > 0.0);  // the beam did deform
  CHECK(b.v == a.v);

  // Each integrator refuses the other's checkpoint, saying whose it is; another step size is
  // refused too.
  ImplicitIntegrator<Hinged<N>>::Settings is;
  is.step = es.step;
  ImplicitIntegrator<Hinged<N>> gen(scene, is);
  Hinged<N>::State c;
  REQUIRE(gen.initialize(c).ok());
  auto implicit_bytes = save_checkpoint(c, gen);
  REQUIRE(implicit_bytes.ok());
  Hinged<N>::State d;
  const Status into_explicit =
      restore_checkpoint(implicit_bytes->data(), implicit_bytes->size(), d, resumed, "gen.ckpt");
  REQUIRE_FALSE(into_explicit.ok());
  CHECK(into_explicit.error().message ==
        "'gen.ckpt': an implicit-integrator checkpoint: restore it into an ImplicitIntegrator");
  const Status into_implicit = restore_checkpoint(bytes.data(), bytes.size(), d, gen, "rk4.ckpt");
  REQUIRE_FALSE(into_implicit.ok());
  CHECK(into_implicit.error().message ==
        "'rk4.ckpt': an explicit-integrator checkpoint: restore it into an ExplicitIntegrator");
  es.step /= 2;
  ExplicitIntegrator<Hinged<N>> finer(scene, es);
  const Status other_step = restore_checkpoint(bytes.data(), bytes.size(), d, finer, "rk4.ckpt");
  REQUIRE_FALSE(other_step.ok());
  CHECK(other_step.error().message.find("'rk4.ckpt': taken with the step h = ") == 0);
  CHECK(d.t == 0.0);  // untouched
}

TEST_CASE("static equilibrium of a clamped flexible cantilever matches the FE static solution") {
  constexpr int N = 16;
  auto beam = testing::make_beam_body(kLength, kSection, 24, {0.0}, N);
  using Clamped = Scene<double, Bodies<FFRFBody<N>>, Joints<Fixed<ground, 0>>,
                        Effects<Gravity>>::with_storage_limit<kStorage>;
  Clamped scene;
  auto body = FFRFBody<N>::from_modal_data(beam.data);
  REQUIRE(body.ok());
  scene.body<0>() = *body;
  scene.joint<0>().marker_i = fixed_marker<double>(Vector3d::Zero());
  scene.joint<0>().marker_j =
      make_marker(scene.body<0>(), beam.interface_nodes[0], Vector3d::Zero());
  Clamped::State s;
  const Status eq = solve_static_equilibrium(scene, s);
  if (!eq) MESSAGE(eq.error().what());
  REQUIRE(eq.ok());
  const Index tip = beam.line.nodes.back();
  BodyKinematics<double, N> k;
  k.p = s.coordinates<0>().p;
  const double tip_sim = (s.coordinates<0>().position + rotation_matrix(s.coordinates<0>().theta) *
                                                            scene.body<0>().point(tip).local(k))
                             .y();
  // FE: clamped at x = 0, self-weight as consistent nodal loads M g.
  fe::BoundaryConditions bc;
  bc.clamp(beam.interface_nodes[0]);
  auto full = fe::assemble(beam.mesh, bc);
  REQUIRE(full.ok());
  auto solver = fe::StaticSolver::factorize(beam.mesh, *full);
  REQUIRE(solver.ok());
  VectorXd g = VectorXd::Zero(full->dofs.size());
  for (Index n = 0; n < beam.mesh.num_nodes(); ++n) g(full->dofs.dof(n, 1)) = -9.81;
  const VectorXd u = solver->solve(full->mass_all * g);
  const double tip_fe = u(full->dofs.dof(tip, 1));
  // Beam theory for the same load: q L^4 / (8 E I).
  const double q = 7850 * kSection.area * 9.81;
  const double tip_theory = -q * std::pow(kLength, 4) / (8 * 210e9 * kSection.iz);
  MESSAGE("tip deflection: scene " << tip_sim << " m, FE " << tip_fe << " m, beam theory "
                                   << tip_theory);
  CHECK(tip_sim == doctest::Approx(tip_fe).epsilon(1e-3));
  CHECK(tip_fe == doctest::Approx(tip_theory).epsilon(5e-3));  // rotary inertia / shear: none here
}

TEST_CASE("a float scene runs: Euler parameters stay unit to float precision") {
  constexpr int N = 4;
  auto beam = hinged_beam(N);
  auto scene = make_hinged<Hinged<N, float>>(beam.data, beam.interface_nodes[0]);
  Hinged<N, float>::State s;
  ImplicitIntegrator<Hinged<N, float>> integ(scene);
  REQUIRE(integ.initialize(s).ok());
  for (int i = 0; i < 500; ++i) REQUIRE(integ.step(s) == StepStatus::ok);
  CHECK(std::abs(s.coordinates<0>().theta.norm() - 1.0f) < 1e-6f);
  // Same motion as double to float accuracy.
  auto scene_d = make_hinged<Hinged<N>>(beam.data, beam.interface_nodes[0]);
  Hinged<N>::State sd;
  ImplicitIntegrator<Hinged<N>> integ_d(scene_d);
  REQUIRE(integ_d.initialize(sd).ok());
  for (int i = 0; i < 500; ++i) REQUIRE(integ_d.step(sd) == StepStatus::ok);
  const double diff =
      (s.coordinates<0>().position.cast<double>() - sd.coordinates<0>().position).norm();
  MESSAGE("float vs double frame position after 0.5 s: " << diff << " m");
  CHECK(diff < 1e-3);
}

}  // namespace test_flexible_scenes
