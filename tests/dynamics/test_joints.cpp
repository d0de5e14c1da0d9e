// Joint and driver equations: analytic constraint Jacobians B and convective terms checked
// against finite differences of the constraint functions along a motion q(t) = q0 o exp(t v)
// (constant velocities, so d2 Phi / dt2 = conv exactly), on a flexible and a rigid body; and an
// evaluation without rates (what Newton iterations use) gives the same Phi and B. A joint
// evaluates only the marker parts it declares (parts_i, parts_j) and the others are NaN, so a
// part read but not declared fails here too.
#include <cmath>
#include <random>
#include <string>

#include <doctest/doctest.h>

#include <flexstress/dynamics/scene.hpp>

#include "fixtures.hpp"

namespace test_joints {

using namespace flexstress;

namespace {

using Law = PolynomialLaw<double>;
template <class S>
using Poly = PolynomialLaw<S>;

using AllJoints = Scene<
    double, Bodies<FFRFBody<4>, RigidBody>,
    Joints<Spherical<0, 1>, Revolute<0, 1>, Universal<0, 1>, Cylindrical<0, 1>, Prismatic<0, 1>,
           Fixed<0, 1>, Distance<0, 1>, PrismaticDriver<0, 1, Poly>, RevoluteDriver<0, 1, Poly>,
           Revolute<ground, 0>, Prismatic<1, ground>, RevoluteDriver<ground, 1, Poly>>>;

Mat3<double> random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n;
  return rotation_matrix<double>(normalized<double>(Vec4<double>(n(rng), n(rng), n(rng), n(rng))));
}

// Marker i on the flexible body at `node` (with a rigid offset), marker j on the rigid body.
template <class Joint>
void set_markers(AllJoints& scene, Joint& j, std::mt19937& rng, Index node) {
  std::normal_distribution<double> n;
  const Vector3d off(n(rng) * 0.1, n(rng) * 0.1, n(rng) * 0.1);
  j.marker_i = make_marker(scene.body<0>(), node, off, random_rotation(rng));
  j.marker_j =
      make_marker(scene.body<1>(), -1, Vector3d(n(rng), n(rng), n(rng)), random_rotation(rng));
}

}  // namespace

TEST_CASE("constraint Jacobians and convective terms of every joint match finite differences") {
  std::mt19937 rng(42);
  std::normal_distribution<double> n;
  auto beam = testing::make_beam_body(1.2, fe::rectangular_hollow_section(0.05, 0.04, 0.003), 8,
                                      {0.0, 1.2}, 2);
  AllJoints scene;
  auto flex = FFRFBody<4>::from_modal_data(beam.data);
  REQUIRE(flex.ok());
  scene.body<0>() = *flex;
  scene.body<1>() = RigidBody::rigid(2.0, Vector3d(0.1, 0, 0), Matrix3d::Identity() * 0.3);
  const Index node = beam.line.node_at(0.6);
  set_markers(scene, scene.joint<0>(), rng, node);
  set_markers(scene, scene.joint<1>(), rng, node);
  set_markers(scene, scene.joint<2>(), rng, node);
  set_markers(scene, scene.joint<3>(), rng, node);
  set_markers(scene, scene.joint<4>(), rng, node);
  set_markers(scene, scene.joint<5>(), rng, node);
  set_markers(scene, scene.joint<6>(), rng, node);
  scene.joint<6>().params.length = 0.7;
  set_markers(scene, scene.joint<7>(), rng, node);
  scene.joint<7>().params.law = Law{0.2, 0.3, -0.8};
  set_markers(scene, scene.joint<8>(), rng, node);
  scene.joint<8>().params.law = Law{0.1, 0.5, 0.7};
  scene.joint<9>().marker_i = fixed_marker<double>(Vector3d(0.2, 0.1, 0), random_rotation(rng));
  scene.joint<9>().marker_j = make_marker(scene.body<0>(), beam.line.node_at(0.0),
                                          Vector3d(0, 0, 0.05), random_rotation(rng));
  scene.joint<10>().marker_i =
      make_marker(scene.body<1>(), -1, Vector3d(0.3, 0, 0), random_rotation(rng));
  scene.joint<10>().marker_j = fixed_marker<double>(Vector3d(1, 2, 3), random_rotation(rng));
  scene.joint<11>().marker_i = fixed_marker<double>(Vector3d(0, 0, 1), random_rotation(rng));
  scene.joint<11>().marker_j =
      make_marker(scene.body<1>(), -1, Vector3d(0, 0.2, 0), random_rotation(rng));
  scene.joint<11>().params.law = Law{0.3, -0.4, 1.1};

  for (int trial = 0; trial < 5; ++trial) {
    AllJoints::State s;
    s.t = 0.37 * trial;
    auto& q0 = s.coordinates<0>();
    q0.position = Vector3d(n(rng), n(rng), n(rng));
    q0.theta = normalized<double>(Vec4<double>(n(rng), n(rng), n(rng), n(rng)));
    for (int k = 0; k < 4; ++k) q0.p(k) = 0.01 * n(rng);
    auto& q1 = s.coordinates<1>();
    q1.position = Vector3d(n(rng), n(rng), n(rng));
    q1.theta = normalized<double>(Vec4<double>(n(rng), n(rng), n(rng), n(rng)));
    for (int i = 0; i < AllJoints::nv; ++i) s.v(i) = n(rng);
    s.v.segment<4>(6) *= 0.1;

    auto phi_at = [&](double dt) {
      AllJoints::State sd = s;
      scene.integrate(sd, AllJoints::VecV(dt * s.v));
      sd.t = s.t + dt;
      AllJoints::Workspace w;
      scene.evaluate(sd, w, /*rates=*/false);  // as in a Newton iteration
      return AllJoints::VecC(w.phi);
    };
    AllJoints::Workspace w;
    scene.evaluate(s, w);
    // The implicit integrator's Newton iterations evaluate without rates: Phi and B must be
    // the same to the last bit as in the full evaluation.
    AllJoints::Workspace positions_only;
    scene.evaluate(s, positions_only, /*rates=*/false);
    CHECK(positions_only.phi == w.phi);
    CHECK(positions_only.jac == w.jac);
    const double e1 = 1e-6, e2 = 1e-4;
    const AllJoints::VecC rate_fd = (phi_at(e1) - phi_at(-e1)) / (2 * e1);
    const AllJoints::VecC rate = w.jac * s.v + w.phi_t;
    const AllJoints::VecC acc_fd = (phi_at(e2) - 2 * phi_at(0) + phi_at(-e2)) / (e2 * e2);
    for (int r = 0; r < AllJoints::nc; ++r) {
      CAPTURE(r);
      const std::string kind = AllJoints::joint_kind_name(AllJoints::joint_of_row(r));
      CAPTURE(kind);
      CHECK(rate(r) == doctest::Approx(rate_fd(r)).epsilon(1e-7).scale(1.0));
      CHECK(w.conv(r) == doctest::Approx(acc_fd(r)).epsilon(1e-5).scale(1.0));
    }
  }
}

}  // namespace test_joints
