// IFToMM benchmark A01, simple pendulum (Gonzalez, Dopico, Lugris, Cuadrado, Multibody Syst.
// Dyn. 16 (2006) 179-190): point mass 1 kg on a massless 1 m link, g = 9.81, released from
// rest horizontal. Period 4 sqrt(L/g) K(1/sqrt 2) = 2.367842 s.
#include <cmath>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include <flexstress/core/batch.hpp>
#include <flexstress/model/all.hpp>

namespace test_pendulum {

using namespace flexstress;

namespace {

struct Pendulum {
  Model<double> model;
  BodyId bob;
  JointId brake;  ///< holds the bob at a release angle (with_brake only)
};

/// The pendulum released from `start` (the bob's centre, link along its body x); with a brake,
/// a revolute driver from the ground to the bob that holds it until switched off.
Pendulum make_pendulum(const Vector3d& start = Vector3d(1, 0, 0), bool with_brake = false) {
  ModelBuilder<double> b;
  // A point mass: 1 kg with a negligible inertia (a 1.6 mm steel ball's; its effect on the
  // period is I / (2 m L^2) = 5e-7 relative).
  const BodyId bob = b.add_rigid_body("bob", 1.0, Vector3d::Zero(), Matrix3d::Identity() * 1e-6);
  b.set_initial_pose(bob, start);
  const MarkerId pivot = b.add_marker("pivot", b.ground(), -1, Vector3d::Zero());
  const MarkerId link_end = b.add_marker("link end", bob, -1, Vector3d(-1, 0, 0));
  b.add_joint("hinge", JointKind::revolute, pivot, link_end);
  JointId brake;
  if (with_brake)
    brake = b.add_driver("brake", JointKind::revolute_driver, pivot, link_end,
                         MotionLaw<double>::constant_acceleration(0.0));
  b.set_gravity(Vector3d(0, -9.81, 0));
  auto m = b.finalize();
  if (!m.ok()) FAIL(m.error().what());  // (error() of a success is not to be read)
  return {std::move(*m), bob, brake};
}

}  // namespace

TEST_CASE("A01 pendulum: period 2.367842 s and energy over 2000 s" * doctest::test_suite("long")) {
  const Pendulum p = make_pendulum();
  Data<double> d(p.model);
  d.settings.step = 5e-3;
  d.settings.spectral_radius = 0.9;  // slight dissipation of the highest frequencies only
  REQUIRE(initialize(p.model, d).ok());
  const double e0 = energy(p.model, d).total();
  double max_drift = 0, last_crossing = -1, first_crossing = -1;
  int crossings = 0;
  double y_prev = body_position(p.model, d, p.bob).x();
  const int steps = 400000;  // 2000 s
  for (int i = 0; i < steps; ++i) {
    const StepStatus st = step(p.model, d);
    REQUIRE(st == StepStatus::ok);
    max_drift = std::max(max_drift, std::abs(energy(p.model, d).total() - e0));
    // Upward crossings of x = 0 (the mass swings through the bottom), interpolated.
    const double x = body_position(p.model, d, p.bob).x();
    if (y_prev < 0 && x >= 0) {
      const double tc = d.t - d.settings.step * x / (x - y_prev);
      if (first_crossing < 0) first_crossing = tc;
      last_crossing = tc;
      ++crossings;
    }
    y_prev = x;
  }
  const double period = (last_crossing - first_crossing) / (crossings - 1);
  MESSAGE("period " << period << " s over " << crossings << " periods, energy drift " << max_drift
                    << " J of " << 9.81 << " J swing, iterations/step "
                    << double(d.statistics.iterations) / steps << ", factorizations "
                    << d.statistics.factorizations);
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
  const Pendulum p = make_pendulum();
  auto run = [&](int max_iterations, bool budget, long* over_budget, StepStatus* failure,
                 long* budget_statuses = nullptr) {
    Data<double> d(p.model);
    d.settings.step = 1e-3;
    d.settings.max_iterations = max_iterations;
    d.settings.accept_at_iteration_limit = budget;
    REQUIRE(initialize(p.model, d).ok());
    for (int i = 0; i < 1000; ++i) {
      const double t_before = d.t;
      const StepStatus st = step(p.model, d);
      if (st == StepStatus::budget_reached) {
        // Kept, and says how far from converged: the last correction above its tolerance.
        CHECK(d.statistics.last_correction > 1.0);
        if (budget_statuses) ++*budget_statuses;
        continue;
      }
      if (st != StepStatus::ok && st != StepStatus::constraint_violation) {
        if (failure) *failure = st;
        CHECK(d.t == t_before);  // the failed step was undone
        break;
      }
    }
    if (over_budget) *over_budget = d.statistics.over_budget;
    return d;
  };
  const auto converged = run(30, false, nullptr, nullptr);
  REQUIRE(converged.t == doctest::Approx(1.0));
  StepStatus failure = StepStatus::ok;
  const auto refused = run(1, false, nullptr, &failure);
  CHECK(refused.t < 0.5);
  CHECK(failure == StepStatus::newton_not_converged);
  long over = 0, budget_statuses = 0;
  const auto kept = run(1, true, &over, nullptr, &budget_statuses);
  CHECK(kept.t == doctest::Approx(1.0));
  CHECK(over > 0);
  CHECK(budget_statuses == over);  // every step kept at the budget said so
  const double dx =
      (body_position(p.model, kept, p.bob) - body_position(p.model, converged, p.bob)).norm();
  MESSAGE("1-iteration budget: " << over << " steps at the limit, position off by " << dx
                                 << " m after 1 s");
  CHECK(dx < 0.01);  // 1 % of the link length
  CHECK(body_orientation(p.model, kept, p.bob).allFinite());
  CHECK(kept.v.allFinite());
}

TEST_CASE("bad model input: a non-finite state and a bad motion table get errors naming them") {
  const Pendulum nan_start = make_pendulum(Vector3d(1, std::nan(""), 0));
  Data<double> s(nan_start.model);
  const Status st = initialize(nan_start.model, s);
  REQUIRE_FALSE(st.ok());
  MESSAGE(st.error().what());
  CHECK(st.error().code == ErrorCode::invalid_argument);
  // The runtime model names the body ("body 0" on the compile-time scene).
  CHECK(st.error().what().find("body 'bob' has a coordinate or velocity that is not finite") !=
        std::string::npos);
  CHECK(max_abs(Vector3d(1, std::nan(""), 0)) != max_abs(Vector3d(1, std::nan(""), 0)));  // NaN
  // A step from a state that was never assembled reports it instead of producing NaN.
  const Pendulum p = make_pendulum();
  Data<double> nan_velocity(p.model);
  REQUIRE(initialize(p.model, nan_velocity).ok());
  nan_velocity.v.fill(std::nan(""));  // (no setter writes one velocity: spoil them all)
  CHECK(step(p.model, nan_velocity) == StepStatus::non_finite_state);
  CHECK(nan_velocity.t == 0.0);  // the step was undone
  // Velocities off the joints are read out: the bob moving radially at 1 m/s.
  Data<double> radial(p.model);
  REQUIRE(initialize(p.model, radial).ok());
  CHECK(velocity_violation(p.model, radial) < 1e-12);
  set_body_velocity(p.model, radial, p.bob, Vector3d(1, 0, 0), Vector3d::Zero());
  CHECK(velocity_violation(p.model, radial) == doctest::Approx(1.0));
  auto one_row = TableLaw<double>::create({0.0}, {0.0});
  REQUIRE_FALSE(one_row.ok());
  CHECK(one_row.error().message == "table law: needs at least two rows, got 1");
  auto backwards = TableLaw<double>::create({0.0, 1.0, 0.5}, {0.0, 0.1, 0.2});
  REQUIRE_FALSE(backwards.ok());
  CHECK(backwards.error().message.find("time at row 3 (0.5) does not increase") !=
        std::string::npos);
}

TEST_CASE("a motion table that no step can follow is refused at setup, naming its rows") {
  // A 0.05 rad jump of the brake's angle within a nanosecond: the spline's rate there is 5e7
  // rad/s, so one step of 1 ms would move the law 1e6 times its whole range.
  const auto jump = TableLaw<double>::create({0.0, 1.0, 1.0 + 1e-9, 2.0}, {0.0, 0.0, 0.05, 0.05});
  REQUIRE(jump.ok());
  CHECK(jump->row_too_fast(1e-3) == 2);
  const std::string why = MotionLaw<double>::from_table(*jump).check_step(1e-3);
  MESSAGE(why);
  CHECK(why.find("between rows 2 and 3") != std::string::npos);
  // A sine of period 0.1 s sampled every millisecond: 63 steps of 1 ms per radian of phase
  // follow it; at 50 ms per step (w h = 3.1 > sqrt 2) they cannot.
  std::vector<double> t, s;
  for (int i = 0; i <= 1000; ++i) {
    t.push_back(i * 1e-3);
    s.push_back(0.1 * std::sin(2 * M_PI * t.back() / 0.1));
  }
  const auto sine = TableLaw<double>::create(t, s);
  REQUIRE(sine.ok());
  CHECK(sine->row_too_fast(1e-3) == 0);
  CHECK(sine->row_too_fast(5e-2) > 0);
  // In a model: finalize names the driver.
  ModelBuilder<double> b;
  const BodyId bob = b.add_rigid_body("bob", 1.0, Vector3d::Zero(), Matrix3d::Identity() * 1e-6);
  b.set_initial_pose(bob, Vector3d(1, 0, 0));
  const MarkerId pivot = b.add_marker("pivot", b.ground(), -1, Vector3d::Zero());
  const MarkerId link_end = b.add_marker("link end", bob, -1, Vector3d(-1, 0, 0));
  b.add_joint("hinge", JointKind::revolute, pivot, link_end);
  b.add_driver("brake", JointKind::revolute_driver, pivot, link_end,
               MotionLaw<double>::from_table(*jump));
  const auto m = b.finalize();
  REQUIRE_FALSE(m.ok());
  MESSAGE(m.error().what());
  CHECK(m.error().what().find("joint 'brake': its table changes by 0.05 between rows 2 and 3") !=
        std::string::npos);
  // Swapping it in at run time is refused the same way.
  const Pendulum p = make_pendulum(Vector3d(1, 0, 0), /*with_brake=*/true);
  Data<double> d(p.model);
  const Status swapped = set_law(p.model, d, p.brake, MotionLaw<double>::from_table(*jump));
  REQUIRE_FALSE(swapped.ok());
  CHECK(swapped.error().what().find("rows 2 and 3") != std::string::npos);
}

TEST_CASE("a table of two rows is the cubic smooth step, at rest at both ends") {
  // The clamped spline through (t0, s0), (t1, s1) with zero end slopes is the Hermite cubic
  // s0 + (s1 - s0) (3 u^2 - 2 u^3), u = (t - t0) / T: the smooth step a driver's ramp needs
  // (the closed form is the reference).
  const double t0 = 0.5, t1 = 2.0, s0 = -0.1, s1 = 0.3, period = t1 - t0, rise = s1 - s0;
  const auto law = TableLaw<double>::create({t0, t1}, {s0, s1});
  REQUIRE(law.ok());
  for (int k = 0; k <= 30; ++k) {
    const double t = t0 + period * k / 30.0, u = (t - t0) / period;
    const MotionValue<double> m = (*law)(t);
    CHECK(m.value == doctest::Approx(s0 + rise * (3 * u * u - 2 * u * u * u)).epsilon(1e-12));
    CHECK(m.rate == doctest::Approx(rise * (6 * u - 6 * u * u) / period).epsilon(1e-12));
    // The acceleration jumps at the ends (6 rise / T^2): the rows themselves read as held.
    if (k > 0 && k < 30)
      CHECK(m.acceleration ==
            doctest::Approx(rise * (6 - 12 * u) / (period * period)).epsilon(1e-12));
  }
  // Held outside the table: the end values, at rest.
  for (const double t : {0.0, 3.0}) {
    const MotionValue<double> m = (*law)(t);
    CHECK(m.value == (t < t0 ? s0 : s1));
    CHECK(m.rate == 0.0);
    CHECK(m.acceleration == 0.0);
  }
}

TEST_CASE("a step too large for the motion says so before any state turns non-finite") {
  // The pendulum spun at 100 rad/s: steps of 0.1 and 0.03 s turn it by 10 and 3 rad. Not
  // split (max_step_halvings = 0), each such run ends in step_too_large with the state of the
  // last good step, finite, and a message naming the body and its turn per step; steps of
  // 0.01 s (1 rad, its drifting velocities projected) and 1 ms (0.1 rad) run.
  for (const double h : {0.1, 0.03, 0.01, 1e-3}) {
    CAPTURE(h);
    const Pendulum p = make_pendulum();
    Data<double> d(p.model);
    d.settings.step = h;
    d.settings.max_step_halvings = 0;
    set_body_velocity(p.model, d, p.bob, Vector3d(0, 100, 0), Vector3d(0, 0, 100));
    REQUIRE(initialize(p.model, d).ok());
    StepStatus st = StepStatus::ok;
    const long steps = std::lround(0.2 / h);
    for (long i = 0; i < steps && st == StepStatus::ok; ++i) st = step(p.model, d);
    CHECK(d.q.allFinite());
    CHECK(d.v.allFinite());
    if (h < 0.02) {
      MESSAGE(d.statistics.drift_projections << " drift projections");
      CHECK(st == StepStatus::ok);
      continue;
    }
    const std::string why = d.message.data();
    MESSAGE(why);
    CHECK(st == StepStatus::step_too_large);
    CHECK(why.find("too large for the motion") != std::string::npos);
    CHECK(why.find("body 'bob' turns by") != std::string::npos);
  }
}

namespace {
// A stiff restoring force from outside (a point load the iteration matrix does not see):
// F = -k x along x, k = 1e11 N/m on 1 kg, which no step down to a sixteenth of 1 ms resolves
// (k h^2 is 6e3 there).
void stiff_return(double /*t*/, const double* position, const double* /*velocity*/, double* force,
                  double* /*moment*/, void* /*user*/) {
  force[0] = -1e11 * position[0];
}
}  // namespace

TEST_CASE("a step that diverges where nothing turns says the rotation is not the reason") {
  ModelBuilder<double> b;
  const BodyId block = b.add_rigid_body("block", 1.0, Vector3d::Zero(), Matrix3d::Identity());
  b.add_point_load("stiff return", b.add_marker("centre", block, -1), &stiff_return);
  b.set_gravity(Vector3d::Zero());
  const auto m = b.finalize();
  REQUIRE_MESSAGE(m.ok(), m.error().what());
  Data<double> d(*m);
  set_body_velocity(*m, d, block, Vector3d(0.01, 0, 0), Vector3d::Zero());
  REQUIRE(initialize(*m, d).ok());
  StepStatus st = StepStatus::ok;
  for (int i = 0; i < 10 && st == StepStatus::ok; ++i) st = step(*m, d);
  const std::string why = d.message.data();
  MESSAGE(why);
  CHECK(st == StepStatus::step_too_large);
  CHECK(d.q.allFinite());
  CHECK(why.find("no body turns by more than 0 rad per step (body 'block')") != std::string::npos);
  CHECK(why.find("a stiff force or mode rather than the rotation") != std::string::npos);
}

TEST_CASE("a step too large for the motion is taken in pieces and ends where it should") {
  // The same spinning pendulum on the default max_step_halvings: the steps of 0.1 and 0.03 s
  // that fail whole are taken in halves (down to 1/16), and the runs reach 0.2 s. The bob
  // stays on its circle. Its speed would stay at 100 m/s within 0.2 % (gravity: v^2 = v0^2 -+
  // 2 g 2 m); steps of about a radian lose some of it to the integrator's numerical damping
  // (spectral radius 0.8), less at the smaller step.
  double loss_at_coarser = 1;
  for (const double h : {0.1, 0.03}) {
    CAPTURE(h);
    const Pendulum p = make_pendulum();
    Data<double> d(p.model);
    d.settings.step = h;
    set_body_velocity(p.model, d, p.bob, Vector3d(0, 100, 0), Vector3d(0, 0, 100));
    REQUIRE(initialize(p.model, d).ok());
    const long steps = std::lround(0.2 / h);
    for (long i = 0; i < steps; ++i) REQUIRE(step(p.model, d) == StepStatus::ok);
    MESSAGE(d.statistics.split_steps << " of " << steps << " steps split, into "
                                     << d.statistics.substeps << " pieces");
    CHECK(d.t == doctest::Approx(double(steps) * h).epsilon(1e-12));
    CHECK(d.statistics.steps == steps);
    CHECK(d.statistics.split_steps > 0);
    CHECK(d.message[0] == '\0');  // no failure to report: every step passed
    CHECK(std::abs(d.q.head<3>().norm() - 1.0) < 1e-6);
    const double speed = d.v.head<3>().norm();
    MESSAGE("speed " << speed << " m/s");
    const double loss = 1 - speed / 100;
    CHECK(loss < 0.1);
    CHECK(loss < loss_at_coarser / 2);
    loss_at_coarser = loss;
  }
}

TEST_CASE("a run that takes its steps in pieces remembers them, also through a checkpoint") {
  // The spinning pendulum of the test above at h = 0.03 s: every step is split, and the next
  // step starts with the pieces that passed instead of failing whole first (fewer iterations
  // than a run that forgets them); a checkpoint taken between two split steps carries the piece
  // size, so the restored run continues bit for bit.
  const Pendulum p = make_pendulum();
  Data<double> a(p.model);
  a.settings.step = 0.03;
  set_body_velocity(p.model, a, p.bob, Vector3d(0, 100, 0), Vector3d(0, 0, 100));
  REQUIRE(initialize(p.model, a).ok());
  std::vector<unsigned char> bytes;
  for (int i = 0; i < 7; ++i) {
    if (i == 3) {
      REQUIRE(a.integrator.piece_level > 0);  // in the middle of the split phase
      auto saved = save_checkpoint(p.model, a);
      REQUIRE(saved.ok());
      bytes = *saved;
    }
    REQUIRE(step(p.model, a) == StepStatus::ok);
  }
  CHECK(a.statistics.split_steps == 7);
  Data<double> b(p.model);
  REQUIRE(restore_checkpoint(p.model, b, bytes.data(), bytes.size()).ok());
  CHECK(b.integrator.piece_level > 0);
  for (int i = 3; i < 7; ++i) REQUIRE(step(p.model, b) == StepStatus::ok);
  CHECK(b.t == a.t);
  CHECK(b.q == a.q);
  CHECK(b.v == a.v);
  CHECK(b.statistics.iterations == a.statistics.iterations);
  CHECK(b.statistics.substeps == a.statistics.substeps);
  // Forgetting the pieces (each step tried whole, as a fresh Data restored from the state alone
  // would) costs the failed whole steps' iterations again.
  Data<double> c(p.model);
  c.settings.step = 0.03;
  set_body_velocity(p.model, c, p.bob, Vector3d(0, 100, 0), Vector3d(0, 0, 100));
  REQUIRE(initialize(p.model, c).ok());
  for (int i = 0; i < 7; ++i) {
    c.integrator.piece_level = 0;
    REQUIRE(step(p.model, c) == StepStatus::ok);
  }
  MESSAGE("iterations: " << a.statistics.iterations << " remembering the pieces, "
                         << c.statistics.iterations << " trying each step whole first");
  CHECK(a.statistics.iterations < c.statistics.iterations);
}

TEST_CASE("checkpoint: a restored run continues bit-identically; damaged ones are refused") {
  // Reference: the run that never stopped. The modified Newton reuses its factorization across
  // steps, so the restored Data must carry it over exactly, not just the state.
  const Pendulum p = make_pendulum();
  Data<double> a(p.model);
  a.settings.step = 5e-3;
  REQUIRE(initialize(p.model, a).ok());
  std::vector<unsigned char> bytes;
  for (int i = 0; i < 400; ++i) {
    if (i == 150) {
      auto saved = save_checkpoint(p.model, a);
      REQUIRE(saved.ok());
      bytes = *saved;
    }
    REQUIRE(step(p.model, a) == StepStatus::ok);
  }
  Data<double> b(p.model);  // a fresh Data: everything comes from the checkpoint
  REQUIRE(restore_checkpoint(p.model, b, bytes.data(), bytes.size()).ok());
  for (int i = 150; i < 400; ++i) REQUIRE(step(p.model, b) == StepStatus::ok);
  CHECK(b.t == a.t);
  CHECK(body_position(p.model, b, p.bob) == body_position(p.model, a, p.bob));
  CHECK(body_orientation(p.model, b, p.bob) == body_orientation(p.model, a, p.bob));
  CHECK(b.v == a.v);
  CHECK(b.v_dot == a.v_dot);
  CHECK(b.lambda == a.lambda);
  CHECK(b.statistics.iterations == a.statistics.iterations);
  CHECK(b.statistics.factorizations == a.statistics.factorizations);

  auto error_of = [&](const Model<double>& model, std::vector<unsigned char> damaged) {
    Data<double> s(model);
    s.settings.step = 5e-3;
    const Eigen::VectorXd before = s.q;
    const Status st = restore_checkpoint(model, s, damaged.data(), damaged.size(), "run.ckpt");
    REQUIRE_FALSE(st.ok());
    CHECK(st.error().code == ErrorCode::bad_file_format);
    CHECK(s.q == before);  // untouched
    CHECK(s.settings.step == 5e-3);
    return st.error().what();
  };
  std::vector<unsigned char> flipped = bytes;
  flipped[flipped.size() / 2] ^= 0x04;
  CHECK(error_of(p.model, flipped).find("'run.ckpt': checksum mismatch") != std::string::npos);
  // The header's signature: the compile-time scene's checkpoint put the scene type's there ("of
  // another scene"); the model checkpoint writes 0 and describes the model in the data instead
  // (checked below). A damaged signature must still be refused, saying why.
  std::vector<unsigned char> foreign = bytes;
  foreign[16] ^= 0x01;
  const std::string signature_error = error_of(p.model, foreign);
  MESSAGE(signature_error);
  const std::string after_name = "'run.ckpt': ";
  REQUIRE(signature_error.find(after_name) != std::string::npos);
  CHECK(signature_error.size() > signature_error.find(after_name) + after_name.size());
  std::vector<unsigned char> cut(bytes.begin(), bytes.end() - 8);
  CHECK(error_of(p.model, cut).find("truncated or padded") != std::string::npos);
  const std::string text = "t,stroke\n0,0\n";
  CHECK(error_of(p.model, {text.begin(), text.end()}).find("not a flexstress model checkpoint") !=
        std::string::npos);
  // Another model: the first part that differs is named. A model with one more part (the
  // brake), and one whose body has another mass.
  const Pendulum braked = make_pendulum(Vector3d(1, 0, 0), /*with_brake=*/true);
  const std::string extra = error_of(braked.model, bytes);
  MESSAGE(extra);
  CHECK(extra.find("the checkpoint is of another model: this model also has joint 1 ('brake'") !=
        std::string::npos);
  ModelBuilder<double> heavier;
  const BodyId bob =
      heavier.add_rigid_body("bob", 2.0, Vector3d::Zero(), Matrix3d::Identity() * 1e-6);
  heavier.set_initial_pose(bob, Vector3d(1, 0, 0));
  heavier.add_joint("hinge", JointKind::revolute,
                    heavier.add_marker("pivot", heavier.ground(), -1, Vector3d::Zero()),
                    heavier.add_marker("link end", bob, -1, Vector3d(-1, 0, 0)));
  heavier.set_gravity(Vector3d(0, -9.81, 0));
  const auto heavy = heavier.finalize();
  REQUIRE(heavy.ok());
  const std::string other_mass = error_of(*heavy, bytes);
  MESSAGE(other_mass);
  CHECK(other_mass.find("body 0 ('bob'") != std::string::npos);
  CHECK(other_mass.find("has other parameters") != std::string::npos);
  // The compile-time scene's checkpoint refused an integrator set to another step ("taken with
  // the step h = 0.005"). The model checkpoint is of the whole Data, integrator settings
  // included (and so also integrator-agnostic: the implicit history and the explicit stages
  // live in the same Data): a Data set to a finer step takes the checkpoint's back and continues
  // the run bit for bit.
  Data<double> finer(p.model);
  finer.settings.step = 1e-3;
  REQUIRE(restore_checkpoint(p.model, finer, bytes.data(), bytes.size(), "run.ckpt").ok());
  CHECK(finer.settings.step == 5e-3);
  for (int i = 150; i < 400; ++i) REQUIRE(step(p.model, finer) == StepStatus::ok);
  CHECK(body_position(p.model, finer, p.bob) == body_position(p.model, a, p.bob));
}

TEST_CASE("a batch of pendulums sharing one scene equals the serial runs bit for bit") {
  // One immutable model; each job its own Data, held by the brake at its own angle and released
  // (the model has no per-Data initial pose: the brake's law sets it).
  const Pendulum p = make_pendulum(Vector3d(1, 0, 0), /*with_brake=*/true);
  struct Outcome {
    Vector3d position = Vector3d::Zero();
    double t = 0.0;
    bool ok = false;
  };
  auto run = [&](std::size_t i) {
    const double angle = 0.1 + 0.15 * static_cast<double>(i);
    Data<double> d(p.model);
    d.settings.step = 5e-3;
    Outcome out;
    // Held below the horizontal at `angle` (a turn of -angle about z), then released.
    out.ok = set_law(p.model, d, p.brake, MotionLaw<double>::constant_acceleration(-angle)).ok() &&
             initialize(p.model, d).ok();
    set_joint_active(p.model, d, p.brake, false);
    out.ok = out.ok && initialize(p.model, d).ok();
    for (int k = 0; out.ok && k < 400; ++k) out.ok = step(p.model, d) == StepStatus::ok;
    out.position = body_position(p.model, d, p.bob);
    out.t = d.t;
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
