// IFToMM benchmark A01, simple pendulum (Gonzalez, Dopico, Lugris, Cuadrado, Multibody Syst.
// Dyn. 16 (2006) 179-190): point mass 1 kg on a massless 1 m link, g = 9.81, released from
// rest horizontal. Period 4 sqrt(L/g) K(1/sqrt 2) = 2.367842 s.
#include <cmath>
#include <vector>

#include <doctest/doctest.h>

#include <flexstress/core/batch.hpp>
#include <flexstress/dynamics/checkpoint.hpp>
#include <flexstress/dynamics/implicit_integrator.hpp>

namespace test_pendulum {

using namespace flexstress;

namespace {

using Pendulum = Scene<double, Bodies<RigidBody>, Joints<Revolute<ground, 0>>,
                       Effects<Gravity, QuadraticVelocity>>;

Pendulum make_pendulum() {
  Pendulum scene;
  // A point mass: 1 kg with a negligible inertia (a 1.6 mm steel ball's; its effect on the
  // period is I / (2 m L^2) = 5e-7 relative).
  scene.body<0>() = RigidBody::rigid(1.0, Vector3d::Zero(), Matrix3d::Identity() * 1e-6);
  scene.joint<0>().marker_i = fixed_marker<double>(Vector3d::Zero());
  scene.joint<0>().marker_j = make_marker(scene.body<0>(), -1, Vector3d(-1, 0, 0));
  return scene;
}

}  // namespace

TEST_CASE("A01 pendulum: period 2.367842 s and energy over 2000 s") {
  const Pendulum scene = make_pendulum();
  ImplicitIntegrator<Pendulum>::Settings settings;
  settings.step = 5e-3;
  settings.spectral_radius = 0.9;  // slight dissipation of the highest frequencies only
  ImplicitIntegrator<Pendulum> integrator(scene, settings);
  Pendulum::State s;
  s.coordinates<0>().position = Vector3d(1, 0, 0);
  REQUIRE(integrator.initialize(s).ok());
  auto& ws = integrator.workspace();
  scene.update_kinematics(s, ws);
  const double e0 = scene.energy(ws).total();
  double max_drift = 0, last_crossing = -1, first_crossing = -1;
  int crossings = 0;
  double y_prev = s.coordinates<0>().position.x();
  const int steps = 400000;  // 2000 s
  for (int i = 0; i < steps; ++i) {
    const StepStatus st = integrator.step(s);
    REQUIRE(st == StepStatus::ok);
    scene.update_kinematics(s, ws);
    max_drift = std::max(max_drift, std::abs(scene.energy(ws).total() - e0));
    // Upward crossings of x = 0 (the mass swings through the bottom), interpolated.
    const double x = s.coordinates<0>().position.x();
    if (y_prev < 0 && x >= 0) {
      const double tc = s.t - settings.step * x / (x - y_prev);
      if (first_crossing < 0) first_crossing = tc;
      last_crossing = tc;
      ++crossings;
    }
    y_prev = x;
  }
  const double period = (last_crossing - first_crossing) / (crossings - 1);
  MESSAGE("period " << period << " s over " << crossings << " periods, energy drift " << max_drift
                    << " J of " << 9.81 << " J swing, iterations/step "
                    << double(integrator.statistics().iterations) / steps << ", factorizations "
                    << integrator.statistics().factorizations);
  CHECK(period == doctest::Approx(2.367842).epsilon(1e-4));
  CHECK(max_drift < 1e-3 * 9.81);
}

TEST_CASE("a Newton budget keeps the step's last iterate instead of failing") {
  // Real-time use: at most max_iterations corrections per step. Without the budget flag a step
  // that needs more is undone and reported; with it the step is kept and counted, and with a
  // sufficient budget the motion stays close to the converged one (the pendulum's swing, 1 s
  // from horizontal). The pendulum converges in two iterations (its iteration matrix turns
  // exactly with the body, Settings::corotate_factorization), so a budget of one binds at every
  // step; the state stays finite (a budget must never abort or leave NaN behind).
  const Pendulum scene = make_pendulum();
  auto run = [&](int max_iterations, bool budget, long* over_budget, StepStatus* failure) {
    ImplicitIntegrator<Pendulum>::Settings settings;
    settings.step = 1e-3;
    settings.max_iterations = max_iterations;
    settings.accept_at_iteration_limit = budget;
    ImplicitIntegrator<Pendulum> integrator(scene, settings);
    Pendulum::State s;
    s.coordinates<0>().position = Vector3d(1, 0, 0);
    REQUIRE(integrator.initialize(s).ok());
    for (int i = 0; i < 1000; ++i) {
      const double t_before = s.t;
      const StepStatus st = integrator.step(s);
      if (st != StepStatus::ok && st != StepStatus::constraint_violation) {
        if (failure) *failure = st;
        CHECK(s.t == t_before);  // the failed step was undone
        break;
      }
    }
    if (over_budget) *over_budget = integrator.statistics().over_budget;
    return s;
  };
  const auto converged = run(30, false, nullptr, nullptr);
  REQUIRE(converged.t == doctest::Approx(1.0));
  StepStatus failure = StepStatus::ok;
  const auto refused = run(1, false, nullptr, &failure);
  CHECK(refused.t < 0.5);
  CHECK(failure == StepStatus::newton_not_converged);
  long over = 0;
  const auto kept = run(1, true, &over, nullptr);
  CHECK(kept.t == doctest::Approx(1.0));
  CHECK(over > 0);
  const double dx = (kept.coordinates<0>().position - converged.coordinates<0>().position).norm();
  MESSAGE("1-iteration budget: " << over << " steps at the limit, position off by " << dx
                                 << " m after 1 s");
  CHECK(dx < 0.01);  // 1 % of the link length
  CHECK(kept.coordinates<0>().theta.allFinite());
  CHECK(kept.v.allFinite());
}

TEST_CASE("bad scene input: a non-finite state and a bad motion table get errors naming them") {
  const Pendulum scene = make_pendulum();
  ImplicitIntegrator<Pendulum> integrator(scene);
  Pendulum::State s;
  s.coordinates<0>().position = Vector3d(1, std::nan(""), 0);
  const Status st = integrator.initialize(s);
  REQUIRE_FALSE(st.ok());
  MESSAGE(st.error().what());
  CHECK(st.error().code == ErrorCode::invalid_argument);
  CHECK(st.error().what().find("body 0 has a coordinate or velocity that is not finite") !=
        std::string::npos);
  CHECK(max_abs(Vector3d(1, std::nan(""), 0)) != max_abs(Vector3d(1, std::nan(""), 0)));  // NaN
  // A step from a state that was never assembled reports it instead of producing NaN.
  Pendulum::State nan_velocity;
  nan_velocity.coordinates<0>().position = Vector3d(1, 0, 0);
  REQUIRE(integrator.initialize(nan_velocity).ok());
  nan_velocity.v(1) = std::nan("");
  CHECK(integrator.step(nan_velocity) == StepStatus::non_finite_state);
  CHECK(nan_velocity.t == 0.0);  // the step was undone
  auto one_row = TableLaw<double>::create({0.0}, {0.0});
  REQUIRE_FALSE(one_row.ok());
  CHECK(one_row.error().message == "table law: needs at least two rows, got 1");
  auto backwards = TableLaw<double>::create({0.0, 1.0, 0.5}, {0.0, 0.1, 0.2});
  REQUIRE_FALSE(backwards.ok());
  CHECK(backwards.error().message.find("time at row 3 (0.5) does not increase") !=
        std::string::npos);
}

TEST_CASE("checkpoint: a restored run continues bit-identically; damaged ones are refused") {
  // Reference: the run that never stopped. The modified Newton reuses its factorization across
  // steps, so the restored integrator must carry it over exactly, not just the state.
  const Pendulum scene = make_pendulum();
  ImplicitIntegrator<Pendulum>::Settings settings;
  settings.step = 5e-3;
  auto start = [&] {
    Pendulum::State s;
    s.coordinates<0>().position = Vector3d(1, 0, 0);
    return s;
  };
  ImplicitIntegrator<Pendulum> straight(scene, settings);
  Pendulum::State a = start();
  REQUIRE(straight.initialize(a).ok());
  std::vector<unsigned char> bytes;
  for (int i = 0; i < 400; ++i) {
    if (i == 150) {
      auto saved = save_checkpoint(a, straight);
      REQUIRE(saved.ok());
      bytes = *saved;
    }
    REQUIRE(straight.step(a) == StepStatus::ok);
  }
  ImplicitIntegrator<Pendulum> resumed(scene, settings);
  Pendulum::State b;  // a fresh state: everything comes from the checkpoint
  REQUIRE(restore_checkpoint(bytes.data(), bytes.size(), b, resumed).ok());
  for (int i = 150; i < 400; ++i) REQUIRE(resumed.step(b) == StepStatus::ok);
  CHECK(b.t == a.t);
  CHECK(b.coordinates<0>().position == a.coordinates<0>().position);
  CHECK(b.coordinates<0>().theta == a.coordinates<0>().theta);
  CHECK(b.v == a.v);
  CHECK(b.v_dot == a.v_dot);
  CHECK(b.lambda == a.lambda);
  CHECK(resumed.statistics().iterations == straight.statistics().iterations);
  CHECK(resumed.statistics().factorizations == straight.statistics().factorizations);

  auto error_of = [&](std::vector<unsigned char> damaged, ImplicitIntegrator<Pendulum>& integ) {
    Pendulum::State s = start();
    const Pendulum::State before = s;
    const Status st = restore_checkpoint(damaged.data(), damaged.size(), s, integ, "run.ckpt");
    REQUIRE_FALSE(st.ok());
    CHECK(st.error().code == ErrorCode::bad_file_format);
    CHECK(s.coordinates<0>().position == before.coordinates<0>().position);  // untouched
    return st.error().what();
  };
  ImplicitIntegrator<Pendulum> other(scene, settings);
  std::vector<unsigned char> flipped = bytes;
  flipped[flipped.size() / 2] ^= 0x04;
  CHECK(error_of(flipped, other).find("'run.ckpt': checksum mismatch") != std::string::npos);
  std::vector<unsigned char> foreign = bytes;
  foreign[16] ^= 0x01;  // the scene signature
  CHECK(error_of(foreign, other).find("of another scene") != std::string::npos);
  std::vector<unsigned char> cut(bytes.begin(), bytes.end() - 8);
  CHECK(error_of(cut, other).find("truncated or padded") != std::string::npos);
  const std::string text = "t,stroke\n0,0\n";
  CHECK(error_of({text.begin(), text.end()}, other).find("not a flexstress checkpoint") !=
        std::string::npos);
  settings.step = 1e-3;
  ImplicitIntegrator<Pendulum> finer(scene, settings);
  CHECK(error_of(bytes, finer).find("taken with the step h = 0.005") != std::string::npos);
}

TEST_CASE("a batch of pendulums sharing one scene equals the serial runs bit for bit") {
  // One immutable scene; each job its own state and integrator, released from its own angle.
  const Pendulum scene = make_pendulum();
  ImplicitIntegrator<Pendulum>::Settings settings;
  settings.step = 5e-3;
  struct Outcome {
    Vector3d position = Vector3d::Zero();
    double t = 0.0;
    bool ok = false;
  };
  auto run = [&](std::size_t i) {
    const double angle = 0.1 + 0.15 * static_cast<double>(i);
    Pendulum::State s;
    s.coordinates<0>().position = Vector3d(std::cos(angle), -std::sin(angle), 0);
    s.coordinates<0>().theta = Vec4<double>(std::cos(angle / 2), 0, 0, -std::sin(angle / 2));
    ImplicitIntegrator<Pendulum> integrator(scene, settings);
    Outcome out;
    out.ok = integrator.initialize(s).ok();
    for (int k = 0; out.ok && k < 400; ++k) out.ok = integrator.step(s) == StepStatus::ok;
    out.position = s.coordinates<0>().position;
    out.t = s.t;
    return out;
  };
  const std::size_t jobs = 8;
  std::vector<Outcome> serial(jobs), parallel(jobs);
  for (std::size_t i = 0; i < jobs; ++i) serial[i] = run(i);
  run_batch(jobs, 3, [&](std::size_t i) { parallel[i] = run(i); });
  for (std::size_t i = 0; i < jobs; ++i) {
    CAPTURE(i);
    REQUIRE(serial[i].ok);
    CHECK(parallel[i].ok);
    CHECK(parallel[i].t == serial[i].t);
    CHECK(parallel[i].position == serial[i].position);
  }
  // Different angles, different swings: the jobs did not all compute the same thing.
  CHECK(serial[0].position != serial[7].position);
}

}  // namespace test_pendulum
