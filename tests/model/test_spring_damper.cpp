// A spring-damper whose damping dominates its bodies' inertia over a step: the iteration matrix
// carries the element's axial stiffness and damping (model/pipeline.hpp,
// add_force_element_tangent), so Newton converges as for any other stiff term. Without them a
// 1 kg block on a 1e4 N/m spring took 30 iterations per 1 ms step at c = 3e3 N s/m and 213 at
// c = 1e4, and failed its first step at c = 1e5. The reference is the exact motion of the
// damped oscillator m x'' + c x' + k x = 0 released from x0 at rest (overdamped: the roots
// s1,2 = (-c +- sqrt(c^2 - 4 k m)) / 2m, x = x0 (s2 e^(s1 t) - s1 e^(s2 t)) / (s2 - s1)).
#include <cmath>

#include <doctest/doctest.h>

#include <flexstress/model/all.hpp>

namespace test_spring_damper {

using namespace flexstress;

namespace {

struct Block {
  Model<double> model;
  BodyId block;
};

constexpr double kMass = 1.0, kStiffness = 1e4, kRest = 0.5, kStretch = 0.01;

/// A block on a prismatic joint along z under the ground, hung by a spring-damper from the
/// ground's origin, released with the spring stretched by kStretch (no gravity).
Block make_block(double damping) {
  ModelBuilder<double> b;
  const BodyId block =
      b.add_rigid_body("block", kMass, Vector3d::Zero(), Vector3d(0.01, 0.01, 0.01).asDiagonal());
  b.set_initial_pose(block, Vector3d(0, 0, -(kRest + kStretch)),
                     EulerParameters<double>(1, 0, 0, 0));
  const MarkerId slot = b.add_marker("slot", b.ground(), -1);
  b.add_joint("slide", JointKind::prismatic, slot, b.add_marker("block axis", block, -1));
  b.add_spring_damper("spring", slot, b.add_marker("block top", block, -1),
                      SpringDamperParams<double>{kStiffness, damping, kRest, 0.0});
  auto m = b.finalize();
  REQUIRE_MESSAGE(m.ok(), m.error().what());
  return {std::move(*m), block};
}

double exact_stretch(double damping, double t) {
  const double root = std::sqrt(damping * damping - 4 * kStiffness * kMass);
  const double s1 = (-damping + root) / (2 * kMass), s2 = (-damping - root) / (2 * kMass);
  return kStretch * (s2 * std::exp(s1 * t) - s1 * std::exp(s2 * t)) / (s2 - s1);
}

}  // namespace

TEST_CASE(
    "a heavily damped spring-damper: Newton converges and the block follows the exact motion") {
  for (const double c : {3e3, 1e4, 1e5}) {
    CAPTURE(c);
    Block s = make_block(c);
    Data<double> d(s.model);
    REQUIRE(initialize(s.model, d).ok());
    double largest_error = 0;
    for (int i = 0; i < 1000; ++i) {
      const StepStatus st = step(s.model, d);
      REQUIRE_MESSAGE(st == StepStatus::ok, to_string(st) << ": " << d.message.data());
      const double stretch = -body_position(s.model, d, s.block).z() - kRest;
      largest_error = std::max(largest_error, std::abs(stretch - exact_stretch(c, d.t)));
    }
    const double iterations = double(d.statistics.iterations) / double(d.statistics.steps);
    MESSAGE("c = " << c << ": " << iterations << " Newton iterations per step, "
                   << d.statistics.split_steps << " steps split, largest error "
                   << largest_error / kStretch << " of the initial stretch");
    CHECK(d.statistics.split_steps == 0);
    CHECK(iterations <= 3.0);
    // Within 0.1 % of the initial stretch (measured: 3.3e-4, 1.2e-4 and 5.2e-5 of it): the
    // largest error is in the first steps, where the fast root (-3e3 to -1e5 1/s) is not
    // resolved by 1 ms steps, which damp it.
    CHECK(largest_error <= 1e-3 * kStretch);
  }
}

}  // namespace test_spring_damper
