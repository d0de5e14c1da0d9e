// Model::warnings: what finalize finds legal but likely wrong. A flexible body that keeps fewer
// modes than its Craig-Bampton basis holds can lose the static flexibility at a joint's node
// (docs/reduction.md, "Keeping fewer modes than the basis"); the warning is checked against
// what it warns of, the static deflection of the FE model the body was reduced from.
#include <cmath>
#include <string>

#include <doctest/doctest.h>

#include <flexstress/model/all.hpp>
#include <flexstress/reduction/mode_truncation.hpp>

#include "support/beam_fixtures.hpp"

namespace test_model_warnings {

using namespace flexstress;

namespace {

// A 2 m steel RHS 40 x 20 x 2 mm arm, 24 elements, joints at both ends.
const fe::BeamSection kSection = fe::rectangular_hollow_section(0.04, 0.02, 0.002);
constexpr double kLength = 2.0;

struct Deflection {
  double tip = 0;  ///< the tip's deflection along y under the arm's weight, m
  std::vector<std::string> warnings;
};

/// The arm clamped at x = 0 (a fixed joint at the root's interface node), under its own weight
/// along -y, in static equilibrium, keeping `modes` of the data's modes.
Deflection clamped_arm(const testing::BeamBody& arm, int modes) {
  ModelBuilder<double> b;
  const BodyId body = b.add_flexible_body("arm", arm.data, modes);
  b.add_joint("clamp", JointKind::fixed, b.add_marker("wall", b.ground(), -1),
              b.add_marker("root", body, arm.interface_nodes[0]));
  const MarkerId tip = b.add_marker("tip", body, arm.interface_nodes[1]);
  b.set_gravity(Vector3d(0, -9.81, 0));
  auto m = b.finalize();
  REQUIRE(m.ok());
  Data<double> d(*m);
  const Status eq = solve_static_equilibrium(*m, d);
  REQUIRE_MESSAGE(eq.ok(), (eq.ok() ? std::string() : eq.error().what()));
  return {marker_frame(*m, d, tip).origin.y(), m->warnings()};
}

}  // namespace

TEST_CASE("a body keeping too few of its basis's modes is a warning naming it, and it is off") {
  // Interface nodes at both ends and 4 fixed-interface modes: orthonormalized, the static
  // constraint modes of the far end are among the highest. Reference: the FE model clamped at
  // x = 0, its weight as consistent nodal loads M g.
  const auto arm = testing::make_beam_body(kLength, kSection, 24, {0.0, kLength}, 4);
  const double tip_fe =
      testing::fe_deflection_under_weight(arm, arm.interface_nodes[0], arm.interface_nodes[1]);

  const int all = static_cast<int>(arm.data.num_modes);
  const Deflection whole = clamped_arm(arm, all);
  MESSAGE("tip deflection: all " << all << " modes " << whole.tip << " m, FE " << tip_fe << " m");
  CHECK(whole.warnings.empty());
  CHECK(whole.tip == doctest::Approx(tip_fe).epsilon(1e-3));

  const int kept = all - 4;
  const Deflection fewer = clamped_arm(arm, kept);
  const auto least = reduction::least_kept_interface_flexibility(arm.data, kept);
  REQUIRE(least.has_value());
  MESSAGE("tip deflection: " << kept << " modes " << fewer.tip << " m; least share "
                             << least->fraction << " at node " << least->node << " DOF "
                             << least->dof);
  REQUIRE(fewer.warnings.size() == 1);
  const std::string& w = fewer.warnings[0];
  MESSAGE(w);
  CHECK(w.find("body 'arm'") != std::string::npos);
  CHECK(w.find("interface node " + std::to_string(least->node) + ", " +
               reduction::dof_name(least->dof)) != std::string::npos);
  CHECK(w.find("lowest " + std::to_string(kept) + " of the data's " + std::to_string(all)) !=
        std::string::npos);
  // What it warns of: the weight's static deflection, which the whole basis gets within 1e-3,
  // is more than 1 % off.
  CHECK(std::abs(fewer.tip / tip_fe - 1) > 0.01);
}

TEST_CASE("a flexible body keeping its whole basis, or no modes, is no warning") {
  const auto arm = testing::make_beam_body(kLength, kSection, 12, {0.0, kLength}, 2);
  for (const int modes : {static_cast<int>(arm.data.num_modes), 0}) {
    CAPTURE(modes);
    ModelBuilder<double> b;
    b.add_flexible_body("arm", arm.data, modes);
    auto m = b.finalize();
    REQUIRE(m.ok());
    CHECK(m->warnings().empty());
  }
}

}  // namespace test_model_warnings
