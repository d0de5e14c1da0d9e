// The compile-time scene's storage: fixed-size and dynamic storage run the same arithmetic and
// must agree to round-off (the runtime model's fixed and bounded kernels are compared in
// tests/model/test_model_flexible.cpp).
#include <cmath>

#include <doctest/doctest.h>

#include <flexstress/dynamics/explicit_integrator.hpp>
#include <flexstress/dynamics/implicit_integrator.hpp>

#include "fixtures.hpp"

namespace test_effects_storage {

using namespace flexstress;

namespace {

// The hinged beam of test_flexible_scenes: 2 m steel RHS 40 x 20 x 2, revolute about z at x = 0.
testing::BeamBody hinged_beam(int fixed_modes) {
  return testing::make_beam_body(2.0, fe::rectangular_hollow_section(0.04, 0.02, 0.002), 24, {0.0},
                                 fixed_modes);
}

template <int N, class Eff, class Forces = ForceElements<>>
using Hinged = Scene<double, Bodies<FFRFBody<N>>, Joints<Revolute<ground, 0>>, Eff, Forces,
                     FixedGround<double>, 0>;

template <class SceneT>
SceneT make_hinged(const testing::BeamBody& beam) {
  SceneT scene;
  using Body = typename SceneT::template BodyType<0>;
  auto body = Body::from_modal_data(beam.data);
  REQUIRE(body.ok());
  scene.template body<0>() = *body;
  scene.template joint<0>().marker_i = fixed_marker<double>(Vector3d::Zero());
  scene.template joint<0>().marker_j =
      make_marker(scene.template body<0>(), beam.interface_nodes[0], Vector3d::Zero());
  return scene;
}

// Runs `steps` implicit steps from the given initial spin about the hinge and returns the
// coordinates and velocities stacked, for comparison.
template <class SceneT>
Eigen::VectorXd run_implicit(const SceneT& scene, double spin, int steps) {
  ImplicitIntegrator<SceneT> integ(scene);
  typename SceneT::State s;
  s.v(5) = spin;  // body-frame w_z: the frame starts aligned with the ground
  REQUIRE(integ.initialize(s).ok());
  for (int i = 0; i < steps; ++i) REQUIRE(integ.step(s) == StepStatus::ok);
  const auto& q = s.template coordinates<0>();
  Eigen::VectorXd out(3 + 4 + q.p.size() + s.v.size());
  out << q.position, q.theta, q.p, s.v;
  return out;
}

double relative_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).lpNorm<Eigen::Infinity>() / std::max(1e-30, b.lpNorm<Eigen::Infinity>());
}

constexpr int kSteps = 300;  // 0.3 s at h = 1 ms: the beam swings and flexes visibly

}  // namespace

TEST_CASE("fixed-size and dynamic storage give the same motion") {
  using Base = Hinged<4, Effects<Gravity, QuadraticVelocity, ModalDamping>>;
  using Fixed = Base::with_storage_limit<64>;
  using Dynamic = Base::with_storage_limit<0>;
  static_assert(Fixed::fixed_storage && !Dynamic::fixed_storage);
  static_assert(Fixed::VecV::RowsAtCompileTime == 10 && Dynamic::VecV::RowsAtCompileTime == -1);
  const auto beam = hinged_beam(4);
  const auto a = run_implicit(make_hinged<Fixed>(beam), 1.0, kSteps);
  const auto b = run_implicit(make_hinged<Dynamic>(beam), 1.0, kSteps);
  MESSAGE("implicit, fixed vs dynamic storage: " << relative_difference(a, b));
  CHECK(relative_difference(a, b) < 1e-12);
  // RK4 as well (its own storage paths), from the same initial spin.
  auto rk4 = [&](auto tag) {
    using S = typename decltype(tag)::type;
    const S scene = make_hinged<S>(beam);
    typename ExplicitIntegrator<S>::Settings es;
    es.step = 0.5 / scene.max_modal_frequency();
    ExplicitIntegrator<S> integ(scene, es);
    typename S::State s;
    s.v(5) = 1.0;
    for (int i = 0; i < 200; ++i) REQUIRE(integ.step(s) == StepStatus::ok);
    return Eigen::VectorXd(s.v);
  };
  const Eigen::VectorXd ra = rk4(std::common_type<Fixed>{}), rb = rk4(std::common_type<Dynamic>{});
  MESSAGE("RK4, fixed vs dynamic storage: " << relative_difference(ra, rb));
  CHECK(relative_difference(ra, rb) < 1e-12);
}

}  // namespace test_effects_storage
