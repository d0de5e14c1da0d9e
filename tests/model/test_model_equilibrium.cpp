// Static equilibrium and linearization of runtime models, against the FE model the bodies were
// reduced from (solved by the FE kernel without reduction) and beam theory.
#include <cmath>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include <flexstress/fe/eigen_solver.hpp>
#include <flexstress/fe/static_solver.hpp>
#include <flexstress/model/all.hpp>

#include "support/beam_fixtures.hpp"

namespace test_model_equilibrium {

using namespace flexstress;

namespace {

// A 2 m steel RHS 40 x 20 x 2 mm beam, reduced with its x = 0 node as interface.
const fe::BeamSection kSection = fe::rectangular_hollow_section(0.04, 0.02, 0.002);
constexpr double kLength = 2.0;

}  // namespace

TEST_CASE("runtime model: a hinged flexible beam's frequencies equal the pinned-free FE model's") {
  // 16 modes (a count compiled with a fixed size) and 13 (the bounded kernels). Clamped-root
  // modes converge slowly to a hinged beam's: 13 of them are still 13 % high at the second
  // bending frequency, so the 13-mode model is checked by Rayleigh-Ritz nesting instead.
  auto beam = testing::make_beam_body(kLength, kSection, 24, {0.0}, 16);
  fe::BoundaryConditions bc;
  const Index root = beam.interface_nodes[0];
  bc.pin(root).fix(root, 3).fix(root, 4);
  auto full = fe::assemble(beam.mesh, bc);
  REQUIRE(full.ok());
  fe::EigenOptions eo;
  eo.num_modes = 6;
  auto ref = fe::solve_eigen(full->stiffness, full->mass, eo);
  REQUIRE(ref.ok());
  const VectorXd fe_hz = ref->frequencies_hz();
  VectorXd with_16;
  for (int modes : {16, 13}) {
    CAPTURE(modes);
    ModelBuilder<double> b;
    const BodyId body = b.add_flexible_body("beam", beam.data, modes);
    b.add_joint("hinge", JointKind::revolute, b.add_marker("pivot", b.ground(), -1),
                b.add_marker("root", body, root));
    std::vector<MarkerId> nodes;  // where the mode shapes are compared
    for (Index k = 0; k < beam.data.num_nodes(); ++k)
      nodes.push_back(b.add_marker("node " + std::to_string(k), body, k));
    auto m = b.finalize();
    REQUIRE(m.ok());
    Data<double> d(*m);
    auto lin = linearize(*m, d);
    REQUIRE(lin.ok());
    // One zero-frequency motion (the free rotation); then the FE model's, from above
    // (Rayleigh-Ritz) and within the reduction's own error.
    CHECK(std::abs(lin->frequencies_hz(0)) < 1e-3);
    for (int i = 1; i < 6; ++i) {
      CAPTURE(i);
      const double f = lin->frequencies_hz(i), fr = fe_hz(i);
      CHECK(f >= fr * (1 - 1e-6));
      if (modes == 16)
        CHECK(f == doctest::Approx(fr).epsilon(1e-3));
      else  // a subspace of the 16 modes: never below their frequencies (Rayleigh-Ritz)
        CHECK(f >= with_16(i) * (1 - 1e-9));
    }
    if (modes == 16) with_16 = lin->frequencies_hz;
    // The mode shapes, read as the nodes' velocities with d.v set to a mode (linear in d.v),
    // against the FE model's eigenvectors at every node: the modal assurance criterion
    // (a.b)^2 / (|a|^2 |b|^2) (Allemang, Sound and Vibration 37 (2003) 14-21) within 1e-3 of
    // 1 for the 16-mode model, whose frequencies are within 1e-3 too. Mass-orthonormal: each
    // mode's kinetic energy is 1/2.
    if (modes != 16) continue;
    REQUIRE(lin->modes.rows() == d.v.size());
    REQUIRE(lin->modes.cols() == lin->frequencies_hz.size());
    const auto n = static_cast<Index>(nodes.size());
    for (int i = 0; i < 6; ++i) {
      CAPTURE(i);
      d.v = lin->modes.col(i);
      const VectorXd fe_all = full->constraints.free_to_all() * ref->vectors.col(i);
      VectorXd model_shape(3 * n), fe_shape(3 * n);
      for (Index k = 0; k < n; ++k)
        for (int c = 0; c < 3; ++c) {
          model_shape(3 * k + c) =
              marker_state(*m, d, nodes[static_cast<std::size_t>(k)]).origin.velocity(c);
          const Index dof = full->dofs.dof(k, c);
          fe_shape(3 * k + c) = dof >= 0 ? fe_all(dof) : 0.0;
        }
      const double dot = model_shape.dot(fe_shape);
      const double mac = dot * dot / (model_shape.squaredNorm() * fe_shape.squaredNorm());
      MESSAGE("mode " << i << ": MAC " << mac);
      CHECK(mac > 1 - 1e-3);
      CHECK(energy(*m, d).kinetic == doctest::Approx(0.5).epsilon(1e-9));
    }
  }
}

// A rigid pendulum on a spherical joint, 1 m from the pivot to its centre of mass, started
// 0.2 rad off the vertical: its static equilibrium is straight under the pivot (statics: the
// weight's moment about the pivot vanishes only there), and linearized there it swings as a
// compound pendulum. The iteration diverged when it kept
// its matrix while the pendulum turned (solve_static_equilibrium reported a NaN correction).
TEST_CASE(
    "runtime model: static equilibrium of a pendulum started off the vertical hangs under the "
    "pivot") {
  ModelBuilder<double> b;
  const BodyId bob =
      b.add_rigid_body("bob", 50.0, Vector3d::Zero(), Vector3d(0.2, 0.2, 0.2).asDiagonal());
  const double a = 0.2;
  b.set_initial_pose(bob, Vector3d(std::sin(a), 0, -std::cos(a)),
                     EulerParameters<double>(std::cos(a / 2), 0, -std::sin(a / 2), 0));
  b.add_joint("hook", JointKind::spherical, b.add_marker("pivot", b.ground(), -1),
              b.add_marker("hook", bob, -1, Vector3d(0, 0, 1.0)));
  b.set_gravity(Vector3d(0, 0, -9.81));
  const auto m = b.finalize();
  REQUIRE_MESSAGE(m.ok(), m.error().what());
  Data<double> d(*m);
  // Linearized where it starts, off the vertical with no joint force yet, the static residual
  // says it is no equilibrium: the weight m g on the bob's frame at its centre of mass.
  const auto off = linearize(*m, d);
  REQUIRE(off.ok());
  CHECK(off->static_residual == doctest::Approx(50.0 * 9.81).epsilon(1e-9));
  const Status st = solve_static_equilibrium(*m, d);
  REQUIRE_MESSAGE(st.ok(), st.error().what());
  const Vector3d p = body_position(*m, d, bob);
  CHECK(std::abs(p.x()) < 1e-8);
  CHECK(std::abs(p.y()) < 1e-8);
  CHECK(p.z() == doctest::Approx(-1.0).epsilon(1e-9));
  // At rest: residual gone, and the two swings at the compound pendulum's frequency,
  // omega^2 = m g l / (I + m l^2) (l = 1 m to the centre of mass, I = 0.2 kg m^2 about it);
  // the spin about the vertical is free (0 Hz).
  const auto lin = linearize(*m, d);
  REQUIRE(lin.ok());
  CHECK(lin->static_residual < 1e-8 * 50.0 * 9.81);
  const double f = std::sqrt(50.0 * 9.81 / (0.2 + 50.0)) / (2 * 3.14159265358979);
  REQUIRE(lin->frequencies_hz.size() == 3);
  CHECK(std::abs(lin->frequencies_hz(0)) < 1e-3);
  CHECK(lin->frequencies_hz(1) == doctest::Approx(f).epsilon(1e-6));
  CHECK(lin->frequencies_hz(2) == doctest::Approx(f).epsilon(1e-6));
}

TEST_CASE("runtime model: static equilibrium of a clamped cantilever matches the FE solution") {
  auto beam = testing::make_beam_body(kLength, kSection, 24, {0.0}, 16);
  ModelBuilder<double> b;
  const BodyId body = b.add_flexible_body("cantilever", beam.data, 16);
  const JointId clamp = b.add_joint("clamp", JointKind::fixed, b.add_marker("wall", b.ground(), -1),
                                    b.add_marker("root", body, beam.interface_nodes[0]));
  const MarkerId tip = b.add_marker("tip", body, beam.line.nodes.back());
  b.set_gravity(Vector3d(0, -9.81, 0));
  auto m = b.finalize();
  REQUIRE(m.ok());
  Data<double> d(*m);
  const Status eq = solve_static_equilibrium(*m, d);
  REQUIRE_MESSAGE(eq.ok(), (eq.ok() ? std::string() : eq.error().what()));
  const double tip_sim = marker_frame(*m, d, tip).origin.y();
  // FE: clamped at x = 0, self-weight as consistent nodal loads M g.
  const double tip_fe =
      testing::fe_deflection_under_weight(beam, beam.interface_nodes[0], beam.line.nodes.back());
  // Beam theory for the same load: q L^4 / (8 E I).
  const double q = 7850 * kSection.area * 9.81;
  const double tip_theory = -q * std::pow(kLength, 4) / (8 * 210e9 * kSection.iz);
  MESSAGE("tip deflection: model " << tip_sim << " m, FE " << tip_fe << " m, beam theory "
                                   << tip_theory);
  CHECK(tip_sim == doctest::Approx(tip_fe).epsilon(1e-3));
  CHECK(tip_fe == doctest::Approx(tip_theory).epsilon(5e-3));
  // The clamp carries the weight: its reaction on the beam is m g upwards.
  const double weight = 7850 * kSection.area * kLength * 9.81;
  CHECK(joint_reaction(*m, d, clamp).force.y() == doctest::Approx(weight).epsilon(1e-6));
}

TEST_CASE("runtime model: static equilibrium of a platform that only its suspension spring holds") {
  // A 500 kg platform on a vertical slide, carried by a 2e5 N/m spring whose rest length is its
  // start height, with a flexible cantilever mast on it; the spring is ten times stiffer than
  // the iteration's regularization c M (1 Hz), which alone made the iteration diverge (NaN).
  // Reference: the spring's sag under the whole weight, (m_platform + m_beam) g / k, and the
  // mast's own tip deflection under its weight, q L^4 / (8 E I) (Euler-Bernoulli).
  auto beam = testing::make_beam_body(kLength, kSection, 24, {0.0}, 16);
  constexpr double platform_mass = 500, stiffness = 2e5, g = 9.81;
  ModelBuilder<double> b;
  const BodyId platform =
      b.add_rigid_body("platform", platform_mass, Vector3d::Zero(), Matrix3d::Identity() * 50.0);
  b.set_initial_pose(platform, Vector3d(0, 0, 1));
  const BodyId mast = b.add_flexible_body("mast", beam.data, 16);
  b.set_initial_pose(mast, Vector3d(0, 0, 1));
  b.add_joint("slide", JointKind::prismatic, b.add_marker("rail", b.ground(), -1),
              b.add_marker("carriage", platform, -1));
  b.add_joint("mast root", JointKind::fixed, b.add_marker("socket", platform, -1),
              b.add_marker("root", mast, beam.interface_nodes[0]));
  SpringDamperParams<double> spring;
  spring.stiffness = stiffness;
  spring.rest_length = 1.0;
  b.add_spring_damper("suspension", b.add_marker("base", b.ground(), -1),
                      b.add_marker("seat", platform, -1), spring);
  const MarkerId root = b.add_marker("mast at root", mast, beam.interface_nodes[0]);
  const MarkerId mast_tip = b.add_marker("mast tip", mast, beam.line.nodes.back());
  b.set_gravity(Vector3d(0, 0, -g));
  auto m = b.finalize();
  REQUIRE_MESSAGE(m.ok(), m.error().what());
  Data<double> d(*m);
  const Status eq = solve_static_equilibrium(*m, d);
  REQUIRE_MESSAGE(eq.ok(), (eq.ok() ? std::string() : eq.error().what()));
  const double beam_mass = 7850 * kSection.area * kLength;
  const double sag = 1.0 - body_position(*m, d, platform).z();
  const double tip =
      marker_frame(*m, d, mast_tip).origin.z() - marker_frame(*m, d, root).origin.z();
  const double q = 7850 * kSection.area * g;
  const double tip_theory = -q * std::pow(kLength, 4) / (8 * 210e9 * kSection.iy);
  MESSAGE("sag " << sag << " m (spring: " << (platform_mass + beam_mass) * g / stiffness
                 << "), mast tip " << tip << " m (beam theory " << tip_theory << ")");
  CHECK(sag == doctest::Approx((platform_mass + beam_mass) * g / stiffness).epsilon(1e-9));
  CHECK(tip == doctest::Approx(tip_theory).epsilon(5e-3));
}

// A body that nothing holds has no static equilibrium: the error says why, the coordinates stay
// where they were, and the next step starts afresh (the iteration overwrote the step's matrix
// and zeroed the velocities): free fall, v = -g h after one step (constant acceleration, which
// the generalized-alpha step integrates exactly).
TEST_CASE(
    "runtime model: a failed static equilibrium names the cause and the next step starts afresh") {
  ModelBuilder<double> b;
  const BodyId box = b.add_rigid_body("box", 2.0, Vector3d::Zero(), Matrix3d::Identity());
  b.set_gravity(Vector3d(0, -9.81, 0));
  auto m = b.finalize();
  REQUIRE(m.ok());
  Data<double> d(*m);
  REQUIRE(initialize(*m, d).ok());
  REQUIRE(step(*m, d) == StepStatus::ok);  // a factorization to be kept or not
  const Vector3d before = body_position(*m, d, box);
  const Status eq = solve_static_equilibrium(*m, d);
  REQUIRE_FALSE(eq.ok());
  CHECK(std::string(eq.error().what()).find("no joints") != std::string::npos);
  CHECK(body_position(*m, d, box) == before);
  CHECK_FALSE(d.integrator.have_factorization);
  CHECK_FALSE(d.integrator.initialized);
  const double h = d.settings.step;
  REQUIRE(step(*m, d) == StepStatus::ok);
  CHECK(body_velocity(*m, d, box).y() == doctest::Approx(-9.81 * h).epsilon(1e-9));
}

}  // namespace test_model_equilibrium
