// The runtime model on rigid mechanisms. References: IFToMM benchmark A01, the simple pendulum
// (Gonzalez, Dopico, Lugris, Cuadrado, Multibody Syst. Dyn. 16 (2006) 179-190: point mass 1 kg
// on a massless 1 m link, g = 9.81, released from rest horizontal; period
// 4 sqrt(L/g) K(1/sqrt 2) = 2.367842 s), the statics of a hanging mass, and conservation.
#include <algorithm>
#include <cmath>
#include <vector>

#include <doctest/doctest.h>

#include <flexstress/model/all.hpp>

namespace test_model_pendulum {

using namespace flexstress;

namespace {

struct Pendulum {
  Model<double> model;
  BodyId bob;
  JointId hinge;
};

Pendulum make_pendulum(double step, double rho) {
  ModelBuilder<double> b;
  // A point mass: 1 kg with a negligible inertia (a 1.6 mm steel ball's; its effect on the
  // period is I / (2 m L^2) = 5e-7 relative), its frame at the mass, 1 m along x from the hinge.
  const BodyId bob = b.add_rigid_body("bob", 1.0, Vector3d::Zero(), Matrix3d::Identity() * 1e-6);
  b.set_initial_pose(bob, Vector3d(1, 0, 0));
  const MarkerId pivot = b.add_marker("pivot", b.ground(), -1, Vector3d::Zero());
  const MarkerId on_bob = b.add_marker("link end", bob, -1, Vector3d(-1, 0, 0));
  const JointId hinge = b.add_joint("hinge", JointKind::revolute, pivot, on_bob);
  b.set_gravity(Vector3d(0, -9.81, 0));
  b.settings().step = step;
  b.settings().spectral_radius = rho;
  auto m = b.finalize();
  REQUIRE_MESSAGE(m.ok(), m.error().what());
  return {std::move(*m), bob, hinge};
}

}  // namespace

TEST_CASE("runtime model, A01 pendulum: period 2.367842 s and energy over 2000 s" *
          doctest::test_suite("long")) {
  const double h = 5e-3;
  const Pendulum p = make_pendulum(h, 0.9);
  Data<double> d(p.model);
  REQUIRE(initialize(p.model, d).ok());
  const double e0 = energy(p.model, d).total();
  double max_drift = 0, first_crossing = -1, last_crossing = -1, x_prev = 1;
  int crossings = 0;
  const int steps = 400000;
  for (int i = 0; i < steps; ++i) {
    REQUIRE(step(p.model, d) == StepStatus::ok);
    max_drift = std::max(max_drift, std::abs(energy(p.model, d).total() - e0));
    const double x = body_position(p.model, d, p.bob).x();
    if (x_prev < 0 && x >= 0) {  // upward crossing of x = 0, interpolated
      const double tc = d.t - h * x / (x - x_prev);
      if (first_crossing < 0) first_crossing = tc;
      last_crossing = tc;
      ++crossings;
    }
    x_prev = x;
  }
  const double period = (last_crossing - first_crossing) / (crossings - 1);
  MESSAGE("period " << period << " s over " << crossings << " periods, energy drift " << max_drift
                    << " J, iterations/step " << double(d.statistics.iterations) / steps);
  CHECK(period == doctest::Approx(2.367842).epsilon(1e-4));
  CHECK(max_drift < 1e-3 * 9.81);
}

TEST_CASE("runtime model: a hanging pendulum's reaction carries its weight") {
  // At rest straight down, the hinge holds m g: the reaction on the bob is +9.81 N in y (the
  // joint frame is the ground marker's, aligned with the global axes), no moment.
  ModelBuilder<double> b;
  const BodyId bob = b.add_rigid_body("bob", 2.0, Vector3d::Zero(), Matrix3d::Identity() * 1e-3);
  b.set_initial_pose(bob, Vector3d(0, -0.5, 0));
  const MarkerId pivot = b.add_marker("pivot", b.ground(), -1, Vector3d::Zero());
  const MarkerId top = b.add_marker("top", bob, -1, Vector3d(0, 0.5, 0));
  const JointId hinge = b.add_joint("hinge", JointKind::spherical, pivot, top);
  b.set_gravity(Vector3d(0, -9.81, 0));
  auto m = b.finalize();
  REQUIRE(m.ok());
  Data<double> d(*m);
  REQUIRE(initialize(*m, d).ok());
  for (int i = 0; i < 100; ++i) REQUIRE(step(*m, d) == StepStatus::ok);
  const Reaction<double> r = joint_reaction(*m, d, hinge);
  CHECK(r.force.y() == doctest::Approx(2.0 * 9.81).epsilon(1e-9));
  CHECK(std::abs(r.force.x()) < 1e-9);
  CHECK(r.moment.norm() < 1e-9);
  CHECK(marker_frame(*m, d, top).origin.norm() < 1e-9);  // held at the pivot
}

TEST_CASE("runtime model: a driver's effort is what holds its body, with its sign") {
  // Statics: a 10 kg rod of 1 m along +x from a hinge about z, held by a revolute driver at
  // 0.3 rad above the horizontal under gravity -y, needs +m g L / 2 cos(0.3) about +z; the same
  // rod on a vertical slider along +y, held by a prismatic driver, needs +m g along +y.
  const double mass = 10.0, g = 9.81;
  for (const bool turning : {true, false}) {
    CAPTURE(turning);
    const double held = turning ? 0.3 : 0.25;  // rad, m
    ModelBuilder<double> b;
    const BodyId rod =
        b.add_rigid_body("rod", mass, Vector3d(0.5, 0, 0),
                         Vector3d(1e-3, 1.0 / 12 * mass, 1.0 / 12 * mass).asDiagonal());
    // Slider axes (columns): x along global z, y along global x, z_i along global +y.
    const Matrix3d up = (Matrix3d() << 0, 1, 0, 0, 0, 1, 1, 0, 0).finished();
    const MarkerId pivot = b.add_marker("pivot", b.ground(), -1, Vector3d::Zero(),
                                        turning ? Matrix3d::Identity() : up);
    const MarkerId root =
        b.add_marker("root", rod, -1, Vector3d::Zero(), turning ? Matrix3d::Identity() : up);
    b.add_joint("guide", turning ? JointKind::revolute : JointKind::prismatic, pivot, root);
    const JointId drive =
        b.add_driver("drive", turning ? JointKind::revolute_driver : JointKind::prismatic_driver,
                     pivot, root, MotionLaw<double>::constant_acceleration(held));
    b.set_gravity(Vector3d(0, -g, 0));
    auto m = b.finalize();
    REQUIRE_MESSAGE(m.ok(), m.error().what());
    Data<double> d(*m);
    StaticEquilibriumOptions tight;  // the multipliers converge with the corrections
    tight.tolerance = 1e-13;
    REQUIRE(solve_static_equilibrium(*m, d, tight).ok());
    const double expected = turning ? mass * g * 0.5 * std::cos(held) : mass * g;
    CHECK(driver_effort(*m, d, drive) == doctest::Approx(expected).epsilon(1e-9));
    const JointCoordinate<double> c = joint_coordinate(*m, d, drive);
    CHECK(c.value == doctest::Approx(held).epsilon(1e-12));
    CHECK(std::abs(c.rate) < 1e-9);
  }
}

// A rigid bar on a revolute joint at the origin under gravity, turned by a revolute driver
// with `law`, or with the input 'crank angle' (from_input).
struct Crank {
  Model<double> model;
  BodyId bar;
  JointId pin, crank;
  InputId angle;
};

Crank make_crank(bool from_input, const MotionLaw<double>& law,
                 double local_error_tolerance = ImplicitSettings<double>().local_error_tolerance) {
  ModelBuilder<double> b;
  Crank c;
  c.bar = b.add_rigid_body("bar", 1.0, Vector3d(0.5, 0, 0), Vector3d(1e-3, 0.1, 0.1).asDiagonal());
  const MarkerId g = b.add_marker("ground", b.ground(), -1, Vector3d::Zero());
  const MarkerId e = b.add_marker("bar end", c.bar, -1, Vector3d::Zero());
  c.pin = b.add_joint("pin", JointKind::revolute, g, e);
  c.angle = b.add_input("crank angle");
  c.crank = b.add_driver("crank", JointKind::revolute_driver, g, e,
                         from_input ? MotionLaw<double>::from_input(c.angle) : law);
  b.set_gravity(Vector3d(0, -9.81, 0));
  b.settings().local_error_tolerance = local_error_tolerance;
  auto m = b.finalize();
  REQUIRE(m.ok());
  c.model = std::move(*m);
  return c;
}

TEST_CASE("runtime model: a driven crank follows its law; an input law reads set_input") {
  // A rigid bar on a revolute joint driven at 2 rad/s: after 1 s its x axis points at 2 rad.
  // The same drive as an input set before each step gives the same motion.
  const auto run = [](bool from_input) {
    const Crank c = make_crank(from_input, MotionLaw<double>::constant_acceleration(0.0, 2.0));
    const Model<double>* m = &c.model;
    const BodyId bar = c.bar;
    const JointId pin = c.pin, crank = c.crank;
    const InputId angle = c.angle;
    Data<double> d(*m);
    if (from_input) {
      CHECK_FALSE(initialize(*m, d).ok());  // the input was never set
      CHECK(std::string(d.message.data()).find("crank angle") != std::string::npos);
    }
    const auto feed = [&](double t) {
      if (from_input) REQUIRE(set_input(*m, d, angle, 2.0 * t, 2.0, 0.0) == StepStatus::ok);
    };
    feed(0.0);
    REQUIRE(initialize(*m, d).ok());
    for (int i = 0; i < 1000; ++i) {
      feed(d.t + d.settings.step);
      REQUIRE(step(*m, d) == StepStatus::ok);
    }
    const Vector3d x = rotation_matrix<double>(body_orientation(*m, d, bar)).col(0);
    // The joints' own coordinate: the pin's and the driver's angle, turning at 2 rad/s.
    for (const JointId joint : {pin, crank}) {
      const JointCoordinate<double> c = joint_coordinate(*m, d, joint);
      CHECK(c.defined);
      CHECK(c.value == doctest::Approx(std::atan2(x.y(), x.x())).epsilon(1e-12));
      CHECK(c.rate == doctest::Approx(2.0).epsilon(1e-8));
    }
    return std::atan2(x.y(), x.x());
  };
  const double by_law = run(false), by_input = run(true);
  CHECK(by_law == doctest::Approx(2.0).epsilon(1e-8));
  CHECK(by_input == doctest::Approx(by_law).epsilon(1e-12));
}

// The crank's law s(t) = 0.5 sin(5 t) for the callback law below.
static void swinging_law(double t, double out[3], void*) {
  out[0] = 0.5 * std::sin(5 * t);
  out[1] = 2.5 * std::cos(5 * t);
  out[2] = -12.5 * std::sin(5 * t);
}

TEST_CASE("runtime model: an input law in the pieces of a split step follows its step's span") {
  // set_input gives the input for the end of the step. A step split in pieces evaluates the
  // driver before that end; the input then follows the quintic through its value, rate and
  // acceleration at the step's two ends, as a law evaluated there would. Every step is split
  // here (a local error tolerance of 1e-12, 16 pieces a step), and the input-driven crank's
  // effort must match the same law given as a callback (the quintic is exact to O((5 h)^6)
  // for sin(5 t)). What is left between the two is the multipliers' own noise: in pieces of
  // 62.5 us they are determined to about alpha times the Newton tolerance, 1e-4 of the effort
  // here. Held at the end's value, the input made each first piece jump by the whole step,
  // and the effort was off by 1e4 times its size.
  const auto run = [](bool from_input) {
    const Crank c =
        make_crank(from_input, MotionLaw<double>::from_callback(&swinging_law, nullptr), 1e-12);
    const Model<double>* m = &c.model;
    const JointId crank = c.crank;
    const InputId angle = c.angle;
    Data<double> d(*m);
    const auto feed = [&](double t) {
      double s[3];
      swinging_law(t, s, nullptr);
      if (from_input) REQUIRE(set_input(*m, d, angle, s[0], s[1], s[2]) == StepStatus::ok);
    };
    feed(0.0);
    REQUIRE(initialize(*m, d).ok());
    std::vector<double> effort;
    for (int i = 0; i < 300; ++i) {
      feed(d.t + d.settings.step);
      REQUIRE(step(*m, d) == StepStatus::ok);
      effort.push_back(driver_effort(*m, d, crank));
    }
    CHECK(d.statistics.split_steps == 300);
    return effort;
  };
  const std::vector<double> by_callback = run(false), by_input = run(true);
  double largest = 0, difference = 0;
  for (std::size_t k = 0; k < by_callback.size(); ++k) {
    largest = std::max(largest, std::abs(by_callback[k]));
    difference = std::max(difference, std::abs(by_input[k] - by_callback[k]));
  }
  MESSAGE("driver effort up to " << largest << " N m, input against callback " << difference);
  CHECK(largest > 1.0);
  CHECK(difference <= 1e-3 * largest);
}

TEST_CASE("runtime model: setup errors name the part") {
  const auto finalize_error = [](auto&& build) {
    ModelBuilder<double> b;
    build(b);
    auto m = b.finalize();
    REQUIRE_FALSE(m.ok());
    return m.error().what();
  };
  CHECK(finalize_error([](ModelBuilder<double>&) {}).find("needs a body") != std::string::npos);
  CHECK(finalize_error([](ModelBuilder<double>& b) {
          const BodyId a = b.add_rigid_body("arm", 1.0, Vector3d::Zero(), Matrix3d::Identity());
          const MarkerId m1 = b.add_marker("m1", a, -1);
          const MarkerId m2 = b.add_marker("m2", a, -1, Vector3d(1, 0, 0));
          b.add_joint("self", JointKind::spherical, m1, m2);
        }).find("joint 'self'") != std::string::npos);
  CHECK(finalize_error([](ModelBuilder<double>& b) {
          b.add_rigid_body("lead", -1.0, Vector3d::Zero(), Matrix3d::Identity());
        }).find("body 'lead'") != std::string::npos);
  CHECK(finalize_error([](ModelBuilder<double>& b) {
          const BodyId a = b.add_rigid_body("arm", 1.0, Vector3d::Zero(), Matrix3d::Identity());
          const MarkerId g = b.add_marker("g", b.ground(), -1);
          const MarkerId m = b.add_marker("m", a, -1);
          b.add_driver("drive", JointKind::revolute_driver, g, m,
                       MotionLaw<double>::constant_acceleration(std::nan(""), 1.0));
        }).find("joint 'drive'") != std::string::npos);
  CHECK(finalize_error([](ModelBuilder<double>& b) {
          const BodyId a = b.add_rigid_body("arm", 1.0, Vector3d::Zero(), Matrix3d::Identity());
          b.add_marker("on a node", a, 3);
        }).find("marker 'on a node'") != std::string::npos);
  // A handle from elsewhere (another model's, or a number): which side, which handle.
  CHECK(finalize_error([](ModelBuilder<double>& b) {
          const BodyId a = b.add_rigid_body("arm", 1.0, Vector3d::Zero(), Matrix3d::Identity());
          const MarkerId g = b.add_marker("g", b.ground(), -1);
          b.add_marker("m", a, -1);
          b.add_joint("hinge", JointKind::revolute, g, MarkerId{42});
        }) ==
        "invalid argument: joint 'hinge': its marker j (handle 42) is not one of this "
        "model's 2 markers");
}

}  // namespace test_model_pendulum
