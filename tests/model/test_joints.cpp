// Joint and driver equations: analytic constraint Jacobians B and convective terms checked
// against finite differences of the constraint functions along a motion q(t) = q0 o exp(t v)
// (constant velocities, so d2 Phi / dt2 = conv exactly), on a flexible and a rigid body; and an
// evaluation without rates (what Newton iterations use) gives the same Phi and B. A joint
// evaluates only the marker parts it declares (parts_i, parts_j) and the others are NaN, so a
// part read but not declared fails here too. The rows are the runtime model's
// (model/joint_rows.hpp), read per joint with joint_equations.
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <doctest/doctest.h>

#include <flexstress/model/all.hpp>

#include "support/beam_fixtures.hpp"

namespace test_joints {

using namespace flexstress;

namespace {

using Law = MotionLaw<double>;

Vector3d draw3(std::mt19937& rng, std::normal_distribution<double>& n) {
  const double x = n(rng), y = n(rng), z = n(rng);
  return Vector3d(x, y, z);
}
Vec4<double> draw4(std::mt19937& rng, std::normal_distribution<double>& n) {
  const double a = n(rng), b = n(rng), c = n(rng), d = n(rng);
  return Vec4<double>(a, b, c, d);
}

Mat3<double> random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n;
  return rotation_matrix<double>(normalized<double>(draw4(rng, n)));
}

// Marker i on the flexible body at `node` (with a rigid offset), marker j on the rigid body;
// each joint its own markers, so that each marker evaluates only the parts its joint declares.
std::pair<MarkerId, MarkerId> random_markers(ModelBuilder<double>& b, const std::string& joint,
                                             BodyId flex, BodyId rigid, std::mt19937& rng,
                                             Index node) {
  std::normal_distribution<double> n;
  const Vector3d off = 0.1 * draw3(rng, n);
  const Matrix3d axes_i = random_rotation(rng);
  const MarkerId i = b.add_marker(joint + " i", flex, node, off, axes_i);
  const Vector3d at = draw3(rng, n);
  const Matrix3d axes_j = random_rotation(rng);
  const MarkerId j = b.add_marker(joint + " j", rigid, -1, at, axes_j);
  return {i, j};
}

// finalize(), failing with its message.
Model<double> finalized(const ModelBuilder<double>& b) {
  auto m = b.finalize();
  if (!m.ok()) FAIL(m.error().what());
  return std::move(*m);
}

// A body's coordinates and velocities, read by handle.
struct BodyState {
  Vector3d position, velocity, omega;
  EulerParameters<double> theta;
  VectorXd p, p_dot;
};
BodyState read_body(const Model<double>& m, const Data<double>& d, BodyId b) {
  return {body_position(m, d, b),    body_velocity(m, d, b),     body_angular_velocity(m, d, b),
          body_orientation(m, d, b), modal_coordinates(m, d, b), modal_velocities(m, d, b)};
}

// Moves the bodies along q(t) = q0 o exp(t v) with their velocities v held: R = R0 + t R_dot,
// theta = theta0 o exp(t w), p = p0 + t p_dot.
void move_along(const Model<double>& m, Data<double>& d, const std::vector<BodyId>& bodies,
                const std::vector<BodyState>& start, double t0, double dt) {
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    const BodyState& s = start[k];
    const EulerParameters<double> theta =
        normalized<double>(compose<double>(s.theta, exp_rotation<double>(Vector3d(dt * s.omega))));
    REQUIRE(set_body_pose(m, d, bodies[k], Vector3d(s.position + dt * s.velocity), theta).ok());
    set_body_velocity(m, d, bodies[k], s.velocity, s.omega);
    if (s.p.size() > 0)
      REQUIRE(set_modal_state(m, d, bodies[k], VectorXd(s.p + dt * s.p_dot), s.p_dot).ok());
  }
  d.t = t0 + dt;
}

std::vector<JointEquations<double>> equations_of(const Model<double>& m, const Data<double>& d,
                                                 const std::vector<JointId>& joints) {
  std::vector<JointEquations<double>> e;
  for (const JointId j : joints) e.push_back(joint_equations(m, d, j));
  return e;
}

}  // namespace

TEST_CASE("constraint Jacobians and convective terms of every joint match finite differences") {
  std::mt19937 rng(42);
  std::normal_distribution<double> n;
  auto beam = testing::make_beam_body(1.2, fe::rectangular_hollow_section(0.05, 0.04, 0.003), 8,
                                      {0.0, 1.2}, 2);
  ModelBuilder<double> b;
  const BodyId flex = b.add_flexible_body("beam", beam.data, 4);
  const BodyId rigid =
      b.add_rigid_body("rigid", 2.0, Vector3d(0.1, 0, 0), Matrix3d::Identity() * 0.3);
  const Index node = beam.line.node_at(0.6);
  std::vector<JointId> joints;
  const auto between = [&](const std::string& name, JointKind kind) {
    const auto [i, j] = random_markers(b, name, flex, rigid, rng, node);
    joints.push_back(b.add_joint(name, kind, i, j));
  };
  between("spherical", JointKind::spherical);
  between("revolute", JointKind::revolute);
  between("universal", JointKind::universal);
  between("cylindrical", JointKind::cylindrical);
  between("prismatic", JointKind::prismatic);
  between("fixed", JointKind::fixed);
  {
    const auto [i, j] = random_markers(b, "distance", flex, rigid, rng, node);
    joints.push_back(b.add_distance("distance", i, j, 0.7));
  }
  {
    const auto [i, j] = random_markers(b, "prismatic driver", flex, rigid, rng, node);
    joints.push_back(b.add_driver("prismatic driver", JointKind::prismatic_driver, i, j,
                                  Law::constant_acceleration(0.2, 0.3, -0.8)));
  }
  {
    const auto [i, j] = random_markers(b, "revolute driver", flex, rigid, rng, node);
    joints.push_back(b.add_driver("revolute driver", JointKind::revolute_driver, i, j,
                                  Law::constant_acceleration(0.1, 0.5, 0.7)));
  }
  {  // ground -> flexible body
    const Matrix3d axes_i = random_rotation(rng);
    const MarkerId i =
        b.add_marker("ground revolute i", b.ground(), -1, Vector3d(0.2, 0.1, 0), axes_i);
    const Matrix3d axes_j = random_rotation(rng);
    const MarkerId j = b.add_marker("ground revolute j", flex, beam.line.node_at(0.0),
                                    Vector3d(0, 0, 0.05), axes_j);
    joints.push_back(b.add_joint("ground revolute", JointKind::revolute, i, j));
  }
  {  // rigid body -> ground
    const Matrix3d axes_i = random_rotation(rng);
    const MarkerId i = b.add_marker("ground prismatic i", rigid, -1, Vector3d(0.3, 0, 0), axes_i);
    const Matrix3d axes_j = random_rotation(rng);
    const MarkerId j =
        b.add_marker("ground prismatic j", b.ground(), -1, Vector3d(1, 2, 3), axes_j);
    joints.push_back(b.add_joint("ground prismatic", JointKind::prismatic, i, j));
  }
  {  // ground -> rigid body, driven
    const Matrix3d axes_i = random_rotation(rng);
    const MarkerId i = b.add_marker("ground driver i", b.ground(), -1, Vector3d(0, 0, 1), axes_i);
    const Matrix3d axes_j = random_rotation(rng);
    const MarkerId j = b.add_marker("ground driver j", rigid, -1, Vector3d(0, 0.2, 0), axes_j);
    joints.push_back(b.add_driver("ground driver", JointKind::revolute_driver, i, j,
                                  Law::constant_acceleration(0.3, -0.4, 1.1)));
  }
  const Model<double> m = finalized(b);
  const std::vector<BodyId> bodies = {flex, rigid};
  Data<double> d(m);

  double worst_rate = 0, worst_conv = 0;
  for (int trial = 0; trial < 5; ++trial) {
    const double t0 = 0.37 * trial;
    // The state through the setters: poses, modal coordinates, velocities.
    const Vector3d r0 = draw3(rng, n);
    const EulerParameters<double> theta0 = normalized<double>(draw4(rng, n));
    VectorXd p0(4);
    for (int k = 0; k < 4; ++k) p0(k) = 0.01 * n(rng);
    const Vector3d r1 = draw3(rng, n);
    const EulerParameters<double> theta1 = normalized<double>(draw4(rng, n));
    const Vector3d v0 = draw3(rng, n), w0 = draw3(rng, n);
    VectorXd p0_dot(4);
    for (int k = 0; k < 4; ++k) p0_dot(k) = 0.1 * n(rng);
    const Vector3d v1 = draw3(rng, n), w1 = draw3(rng, n);
    REQUIRE(set_body_pose(m, d, flex, r0, theta0).ok());
    REQUIRE(set_modal_state(m, d, flex, p0, p0_dot).ok());
    set_body_velocity(m, d, flex, v0, w0);
    REQUIRE(set_body_pose(m, d, rigid, r1, theta1).ok());
    set_body_velocity(m, d, rigid, v1, w1);
    d.t = t0;
    const std::vector<BodyState> start = {read_body(m, d, flex), read_body(m, d, rigid)};

    auto phi_at = [&](double dt) {
      move_along(m, d, bodies, start, t0, dt);
      evaluate(m, d, /*rates=*/false);  // as in a Newton iteration
      std::vector<VectorXd> phi;
      for (const auto& e : equations_of(m, d, joints)) phi.push_back(e.phi);
      return phi;
    };
    // The implicit step's Newton iterations evaluate without rates: Phi and B must be the same
    // to the last bit as in the full evaluation.
    evaluate(m, d, /*rates=*/false);
    const auto positions_only = equations_of(m, d, joints);
    evaluate(m, d);
    const auto w = equations_of(m, d, joints);
    const VectorXd v = d.v;  // all velocities, the columns of each joint's rows
    const double e1 = 1e-6, e2 = 1e-4;
    const auto plus1 = phi_at(e1), minus1 = phi_at(-e1);
    const auto plus2 = phi_at(e2), zero = phi_at(0), minus2 = phi_at(-e2);
    for (std::size_t k = 0; k < joints.size(); ++k) {
      const std::string kind =
          m.joint(joints[k]).name + " (" + to_string(m.joint(joints[k]).kind) + ")";
      CAPTURE(kind);
      CHECK(positions_only[k].phi == w[k].phi);
      CHECK(positions_only[k].jacobian == w[k].jacobian);
      const VectorXd rate_fd = (plus1[k] - minus1[k]) / (2 * e1);
      const VectorXd rate = w[k].jacobian * v + w[k].phi_t;
      const VectorXd acc_fd = (plus2[k] - 2 * zero[k] + minus2[k]) / (e2 * e2);
      for (Index r = 0; r < rate.size(); ++r) {
        CAPTURE(r);
        CHECK(rate(r) == doctest::Approx(rate_fd(r)).epsilon(1e-7).scale(1.0));
        CHECK(w[k].conv(r) == doctest::Approx(acc_fd(r)).epsilon(1e-5).scale(1.0));
        worst_rate =
            std::max(worst_rate, std::abs(rate(r) - rate_fd(r)) / (1.0 + std::abs(rate_fd(r))));
        worst_conv =
            std::max(worst_conv, std::abs(w[k].conv(r) - acc_fd(r)) / (1.0 + std::abs(acc_fd(r))));
      }
    }
  }
  MESSAGE("largest differences to finite differences (relative, scale 1): rate "
          << worst_rate << ", conv " << worst_conv);
}

}  // namespace test_joints
