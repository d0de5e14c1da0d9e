// Flexible bodies in models. References: the full FE model (pinned-free beam frequencies and
// the static deflection under self-weight, solved by the FE kernel without reduction),
// convergence as modes are added, and the stability theory of the integrators (A-stable
// implicit, RK4 bounded by h w <= 2.78).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include <flexstress/fe/eigen_solver.hpp>
#include <flexstress/fe/static_solver.hpp>
#include <flexstress/model/all.hpp>

#include "support/beam_fixtures.hpp"

namespace test_flexible_models {

using namespace flexstress;

namespace {

// A 2 m steel RHS 40 x 20 x 2 mm beam hinged at x = 0 (revolute about z): slender enough that
// gravity bends it visibly, stiff enough to have kHz modes.
const fe::BeamSection kSection = fe::rectangular_hollow_section(0.04, 0.02, 0.002);
constexpr double kLength = 2.0;

testing::BeamBody hinged_beam(int modes) {
  return testing::make_beam_body(kLength, kSection, 24, {0.0}, modes);
}

template <class Scalar>
struct Hinged {
  Model<Scalar> model;
  BodyId beam;
  MarkerId tip;
};

// The beam on a revolute joint about z at its root, released horizontal, gravity along -y
// unless left out; `joint` makes it clamped instead (JointKind::fixed).
template <class Scalar = double>
Hinged<Scalar> make_hinged(const testing::BeamBody& beam, int modes, bool gravity = true,
                           JointKind joint = JointKind::revolute,
                           const ImplicitSettings<Scalar>& settings = {}) {
  ModelBuilder<Scalar> b;
  Hinged<Scalar> h;
  h.beam = b.add_flexible_body("beam", beam.data, modes);
  h.tip = b.add_marker("tip", h.beam, beam.line.nodes.back());
  b.add_joint("hinge", joint, b.add_marker("pivot", b.ground(), -1),
              b.add_marker("root", h.beam, beam.interface_nodes[0]));
  if (gravity) b.set_gravity(Vec3<Scalar>(0, Scalar(-9.81), 0));
  b.settings() = settings;
  auto m = b.finalize();
  REQUIRE_MESSAGE(m.ok(), m.error().what());
  h.model = std::move(*m);
  return h;
}

template <class Scalar>
Vec3<Scalar> tip_of(const Hinged<Scalar>& h, const Data<Scalar>& d) {
  return marker_frame(h.model, d, h.tip).origin;
}

double max_frequency(const Model<double>& m) {
  double w = 0;
  for (const auto& body : m.bodies()) w = std::max(w, body.max_frequency);
  return w;
}

}  // namespace

TEST_CASE("hinged flexible beam: linearized model frequencies equal the pinned-free FE model's") {
  constexpr int N = 16;
  auto beam = hinged_beam(N);
  const auto h = make_hinged(beam, N, /*gravity=*/false);
  Data<double> d(h.model);
  auto lin = linearize(h.model, d);
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
  // The model has one zero-frequency motion (the free rotation); compare the next ones.
  CHECK(std::abs(lin->frequencies_hz(0)) < 1e-3);
  const VectorXd fe_hz = ref->frequencies_hz();
  for (int i = 1; i < 6; ++i) {
    CAPTURE(i);
    const double f = lin->frequencies_hz(i), fr = fe_hz(i);
    MESSAGE("mode " << i << ": model " << f << " Hz, FE " << fr << " Hz");
    CHECK(f >= fr * (1 - 1e-6));                    // Rayleigh-Ritz: never below the full model
    CHECK(f == doctest::Approx(fr).epsilon(1e-3));  // within the reduction's own error
  }
}

namespace {

Vector3d flexible_pendulum_tip(int modes, double t_end) {
  auto beam = hinged_beam(modes);
  const auto h = make_hinged(beam, modes);
  Data<double> d(h.model);
  REQUIRE(initialize(h.model, d).ok());
  const int steps = static_cast<int>(std::lround(t_end / d.settings.step));
  for (int i = 0; i < steps; ++i) REQUIRE(step(h.model, d) == StepStatus::ok);
  return tip_of(h, d);
}

}  // namespace

TEST_CASE("flexible pendulum under gravity converges as modes are added") {
  const Vector3d t2 = flexible_pendulum_tip(2, 0.5), t4 = flexible_pendulum_tip(4, 0.5),
                 t8 = flexible_pendulum_tip(8, 0.5), t16 = flexible_pendulum_tip(16, 0.5);
  const double e2 = (t2 - t16).norm(), e4 = (t4 - t16).norm(), e8 = (t8 - t16).norm();
  MESSAGE("tip at 0.5 s, distance to the 16-mode result: 2 modes " << e2 << " m, 4 modes " << e4
                                                                   << " m, 8 modes " << e8 << " m");
  CHECK(e4 < e2);
  CHECK(e8 < e4);
  CHECK(e8 < 1e-3 * kLength);
  // It really swung (released horizontal, the tip falls about a metre in 0.5 s).
  CHECK(t16.y() < -0.5);
}

// Two runs of the flexible beam released horizontal (8 modes, 0.5 s), the second with one
// setting changed by `change`: a setting of the modified Newton changes where Newton starts or
// which matrix it uses, not the equations it converges to, so the motions differ by the
// solver's tolerance, acceleration errors of tol (1e-5 m/s^2, or the relative tolerance times the
// acceleration scale if that is larger) moving the tip by at most tol t^2 in t. Returns the
// statistics of both runs.
struct SwingPair {
  StepStatistics with_default, changed;
};
template <class Change>
SwingPair same_swing(const std::string& what, Change change, int refactor_backoff_limit = 0) {
  auto beam = hinged_beam(8);
  const auto h = make_hinged(beam, 8);
  Data<double> a(h.model), b(h.model);
  ImplicitSettings<double> set = h.model.settings();
  if (refactor_backoff_limit > 0) {  // for both runs
    set.refactor_backoff_limit = refactor_backoff_limit;
    REQUIRE(set_settings(h.model, a, set).ok());
  }
  change(set);
  REQUIRE(set_settings(h.model, b, set).ok());
  REQUIRE(initialize(h.model, a).ok());
  REQUIRE(initialize(h.model, b).ok());
  const double t_end = 0.5;
  double diff = 0;
  for (int i = 0; i < 500; ++i) {
    REQUIRE(step(h.model, a) == StepStatus::ok);
    REQUIRE(step(h.model, b) == StepStatus::ok);
    diff = std::max(diff, (tip_of(h, a) - tip_of(h, b)).norm());
  }
  const auto& sa = a.statistics;
  const auto& sb = b.statistics;
  MESSAGE("iterations/step " << double(sa.iterations) / sa.steps << " (" << what << ": "
                             << double(sb.iterations) / sb.steps << "), factorizations/step "
                             << double(sa.factorizations) / sa.steps << " ("
                             << double(sb.factorizations) / sb.steps << "), largest tip difference "
                             << diff << " m");
  CHECK(tip_of(h, a).y() < -0.5);  // it swung
  const double tol = std::max(set.acceleration_tolerance, set.relative_acceleration_tolerance *
                                                              a.integrator.acceleration_scale);
  CHECK(diff < tol * t_end * t_end);
  return {sa, sb};
}

TEST_CASE("extrapolated multipliers: the same swing of a flexible beam") {
  // What the predictor's multipliers save in iterations is the crane's (docs/performance.md);
  // on this swing the guess saves nothing, so only the motion is checked.
  same_swing("held", [](auto& set) { set.extrapolate_multipliers = false; });
}

TEST_CASE("a reused factorization turned with the bodies: the same swing, fewer factorizations") {
  // ImplicitSettings::corotate_factorization: the beam swings through 90 degrees in 0.5 s, and a
  // matrix kept from an earlier angle is stale in its own rotation blocks unless turned with it.
  const auto not_turned = [](auto& set) { set.corotate_factorization = false; };
  const SwingPair runs = same_swing("not turned", not_turned);
  CHECK(2 * runs.with_default.factorizations < runs.changed.factorizations);
  // Reused as long as it contracts, a matrix not turned costs iterations too. (On the defaults
  // it goes stale in every step that reuses it, and refactor_backoff_limit has the following
  // steps refactorize at their start instead: fewer iterations, a factorization each.)
  const SwingPair reused = same_swing("not turned", not_turned, /*refactor_backoff_limit=*/1);
  CHECK(2 * reused.with_default.factorizations < reused.changed.factorizations);
  CHECK(reused.with_default.iterations < reused.changed.iterations);
}

TEST_CASE("steps refactorizing at their start after stale matrices: checkpointed, restored") {
  // A matrix not turned with the swinging beam goes stale in each step that reuses it, so the
  // steps after such a miss refactorize at their start (refactor_backoff_limit). A checkpoint
  // taken while they do holds that run, and the restored run continues bit for bit.
  auto beam = hinged_beam(8);
  const auto h = make_hinged(beam, 8);
  ImplicitSettings<double> set = h.model.settings();
  set.corotate_factorization = false;
  Data<double> a(h.model);
  set.refactor_backoff_limit = 0;
  const Status refused = set_settings(h.model, a, set);
  REQUIRE_FALSE(refused.ok());
  CHECK(std::string(refused.error().what()).find("refactor_backoff_limit") != std::string::npos);
  set.refactor_backoff_limit = 16;
  REQUIRE(set_settings(h.model, a, set).ok());
  REQUIRE(initialize(h.model, a).ok());
  std::vector<unsigned char> bytes;
  int saved_at = -1;
  for (int i = 0; i < 400; ++i) {
    if (saved_at < 0 && i >= 100 && a.integrator.fresh_starts_left > 1) {
      auto saved = save_checkpoint(h.model, a);
      REQUIRE(saved.ok());
      bytes = *saved;
      saved_at = i;
    }
    REQUIRE(step(h.model, a) == StepStatus::ok);
  }
  REQUIRE(saved_at >= 0);  // the backoff was running when the checkpoint was taken
  Data<double> b(h.model);
  REQUIRE(restore_checkpoint(h.model, b, bytes.data(), bytes.size()).ok());
  const long iterations_at_save = b.statistics.iterations;
  for (int i = saved_at; i < 400; ++i) REQUIRE(step(h.model, b) == StepStatus::ok);
  CHECK(b.statistics.iterations > iterations_at_save);
  CHECK(b.statistics.iterations == a.statistics.iterations);
  CHECK(b.statistics.factorizations == a.statistics.factorizations);
  CHECK(modal_coordinates(h.model, b, h.beam) == modal_coordinates(h.model, a, h.beam));
  CHECK(Eigen::Vector4d(body_orientation(h.model, b, h.beam)) ==
        Eigen::Vector4d(body_orientation(h.model, a, h.beam)));
}

TEST_CASE("stiff modes: kHz modes stay stable at h = 1 ms (implicit); RK4 refuses that step") {
  constexpr int N = 16;
  auto beam = hinged_beam(N);
  const auto h = make_hinged(beam, N);
  const double f_max = max_frequency(h.model) / (2 * 3.14159265358979323846);
  MESSAGE("highest modal frequency " << f_max << " Hz");
  REQUIRE(f_max > 2000.0);  // h w > 12 at h = 1 ms: far outside RK4's bound 2.78
  Data<double> d(h.model);
  // Excite every mode: the implicit integrator must damp or keep them, never amplify.
  REQUIRE(set_modal_state(h.model, d, h.beam, VectorXd::Constant(N, 1e-4), VectorXd::Zero(N)).ok());
  const Status init = initialize(h.model, d);  // h = 1 ms, rho = 0.8
  if (!init) MESSAGE(init.error().what());
  REQUIRE(init.ok());
  const double e0 = energy(h.model, d).total();
  double e_max = e0;
  for (int i = 0; i < 2000; ++i) {
    REQUIRE(step(h.model, d) == StepStatus::ok);
    e_max = std::max(e_max, energy(h.model, d).total());
  }
  CHECK(modal_velocities(h.model, d, h.beam).allFinite());
  CHECK(e_max <= e0 + 1e-9 * std::abs(e0));
  // The explicit integrator reports the stability violation instead of blowing up.
  ExplicitSettings<double> es;
  es.step = 1e-3;
  Data<double> d2(h.model);
  CHECK(stability_number(h.model, es.step) > 2.78);
  CHECK(explicit_step(h.model, d2, es) == StepStatus::step_above_stability_limit);
  CHECK(d2.t == 0.0);  // nothing was done
}

TEST_CASE("explicit RK4 agrees with the implicit integrator on a non-stiff flexible pendulum") {
  constexpr int N = 2;
  auto beam = hinged_beam(N);
  const auto h = make_hinged(beam, N);
  ExplicitSettings<double> es;
  es.step = 0.5 / max_frequency(h.model);  // h w = 0.5
  Data<double> a(h.model);
  for (double t = 0; t < 0.3 - 1e-12; t += es.step)
    REQUIRE(explicit_step(h.model, a, es) == StepStatus::ok);
  Data<double> b(h.model);
  set_step_size(b, es.step / 4);
  REQUIRE(initialize(h.model, b).ok());
  while (b.t < a.t - 1e-12) REQUIRE(step(h.model, b) == StepStatus::ok);
  const double diff =
      (body_position(h.model, a, h.beam) - body_position(h.model, b, h.beam)).norm() +
      (Eigen::Vector4d(body_orientation(h.model, a, h.beam)) -
       Eigen::Vector4d(body_orientation(h.model, b, h.beam)))
          .norm();
  MESSAGE("RK4 vs generalized-alpha after " << a.t << " s: " << diff);
  CHECK(diff < 1e-4);
}

TEST_CASE("an explicit (RK4) run restored from its checkpoint continues bit-identically") {
  // Reference: the run that never stopped. RK4 starts each step from the state alone (and the
  // multipliers as the first guess), all of which a checkpoint of the Data holds.
  constexpr int N = 2;
  auto beam = hinged_beam(N);
  const auto h = make_hinged(beam, N);
  ExplicitSettings<double> es;
  es.step = 0.5 / max_frequency(h.model);
  Data<double> a(h.model);
  std::vector<unsigned char> bytes;
  for (int i = 0; i < 200; ++i) {
    if (i == 80) {
      auto saved = save_checkpoint(h.model, a);
      REQUIRE(saved.ok());
      bytes = *saved;
    }
    REQUIRE(explicit_step(h.model, a, es) == StepStatus::ok);
  }
  Data<double> b(h.model);  // a fresh Data: everything comes from the checkpoint
  REQUIRE(restore_checkpoint(h.model, b, bytes.data(), bytes.size()).ok());
  for (int i = 80; i < 200; ++i) REQUIRE(explicit_step(h.model, b, es) == StepStatus::ok);
  CHECK(b.t == a.t);
  CHECK(body_position(h.model, b, h.beam) == body_position(h.model, a, h.beam));
  CHECK(Eigen::Vector4d(body_orientation(h.model, b, h.beam)) ==
        Eigen::Vector4d(body_orientation(h.model, a, h.beam)));
  CHECK(modal_coordinates(h.model, b, h.beam) == modal_coordinates(h.model, a, h.beam));
  CHECK(modal_coordinates(h.model, b, h.beam).norm() > 0.0);  // the beam did deform
  CHECK(body_velocity(h.model, b, h.beam) == body_velocity(h.model, a, h.beam));
  CHECK(modal_velocities(h.model, b, h.beam) == modal_velocities(h.model, a, h.beam));

  // A checkpoint belongs to its model: the same beam with 4 modes refuses it and says which
  // part differs; a Data left untouched by the failed restore.
  auto beam4 = hinged_beam(4);
  const auto h4 = make_hinged(beam4, 4);
  Data<double> c(h4.model);
  const Status other = restore_checkpoint(h4.model, c, bytes.data(), bytes.size(), "rk4.ckpt");
  REQUIRE_FALSE(other.ok());
  MESSAGE(other.error().message);
  CHECK(other.error().message ==
        "'rk4.ckpt': the checkpoint is of another model: body 0 is 'beam', 2 modes, 2 markers "
        "there and 'beam', 4 modes, 2 markers here");
  CHECK(c.t == 0.0);  // untouched
}

TEST_CASE("static equilibrium of a clamped flexible cantilever matches the FE static solution") {
  constexpr int N = 16;
  auto beam = testing::make_beam_body(kLength, kSection, 24, {0.0}, N);
  const auto h = make_hinged(beam, N, true, JointKind::fixed);
  Data<double> d(h.model);
  const Status eq = solve_static_equilibrium(h.model, d);
  if (!eq) MESSAGE(eq.error().what());
  REQUIRE(eq.ok());
  const Index tip = beam.line.nodes.back();
  const double tip_sim = tip_of(h, d).y();
  // FE: clamped at x = 0, self-weight as consistent nodal loads M g.
  const double tip_fe = testing::fe_deflection_under_weight(beam, beam.interface_nodes[0], tip);
  // Beam theory for the same load: q L^4 / (8 E I).
  const double q = 7850 * kSection.area * 9.81;
  const double tip_theory = -q * std::pow(kLength, 4) / (8 * 210e9 * kSection.iz);
  MESSAGE("tip deflection: model " << tip_sim << " m, FE " << tip_fe << " m, beam theory "
                                   << tip_theory);
  CHECK(tip_sim == doctest::Approx(tip_fe).epsilon(1e-3));
  CHECK(tip_fe == doctest::Approx(tip_theory).epsilon(5e-3));  // rotary inertia / shear: none here
}

TEST_CASE("a float model runs: Euler parameters stay unit to float precision") {
  constexpr int N = 4;
  auto beam = hinged_beam(N);
  const auto hf = make_hinged<float>(beam, N);
  Data<float> s(hf.model);
  REQUIRE(initialize(hf.model, s).ok());
  for (int i = 0; i < 500; ++i) REQUIRE(step(hf.model, s) == StepStatus::ok);
  CHECK(std::abs(body_orientation(hf.model, s, hf.beam).norm() - 1.0f) < 1e-6f);
  // Same motion as double to float accuracy.
  const auto hd = make_hinged(beam, N);
  Data<double> sd(hd.model);
  REQUIRE(initialize(hd.model, sd).ok());
  for (int i = 0; i < 500; ++i) REQUIRE(step(hd.model, sd) == StepStatus::ok);
  const double diff =
      (body_position(hf.model, s, hf.beam).cast<double>() - body_position(hd.model, sd, hd.beam))
          .norm();
  MESSAGE("float vs double frame position after 0.5 s: " << diff << " m");
  CHECK(diff < 1e-3);
}

}  // namespace test_flexible_models
