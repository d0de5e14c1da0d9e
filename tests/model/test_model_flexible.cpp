// The runtime model on flexible bodies. References: the compile-time scene
// (dynamics/scene.hpp), whose flexible pendulum is itself checked against the FE model
// (tests/dynamics/test_flexible_scenes.cpp); the runtime model must move the same way with
// every kernel it can pick (a mode count compiled with a fixed size, and the bounded fallback);
// and a step must allocate nothing.
#include <cmath>

#include <doctest/doctest.h>

#include <flexstress/dynamics/implicit_integrator.hpp>
#include <flexstress/model/all.hpp>

#include "dynamics/fixtures.hpp"
#include "support/counting_new.hpp"

namespace test_model_flexible {

using namespace flexstress;

namespace {

// The hinged beam of tests/dynamics/test_flexible_scenes.cpp: a 2 m steel RHS 40 x 20 x 2 mm,
// hinged at x = 0 about z, released horizontal under gravity.
const fe::BeamSection kSection = fe::rectangular_hollow_section(0.04, 0.02, 0.002);
constexpr double kLength = 2.0;

testing::BeamBody hinged_beam(int fixed_modes) {
  return testing::make_beam_body(kLength, kSection, 24, {0.0}, fixed_modes);
}

struct RuntimeBeam {
  Model<double> model;
  BodyId beam;
  MarkerId tip;
};

RuntimeBeam runtime_beam(const testing::BeamBody& beam, int modes) {
  ModelBuilder<double> b;
  const BodyId body = b.add_flexible_body("beam", beam.data, modes);
  const MarkerId pivot = b.add_marker("pivot", b.ground(), -1);
  const MarkerId root = b.add_marker("root", body, beam.interface_nodes[0]);
  const MarkerId tip = b.add_marker("tip", body, beam.line.nodes.back());
  b.add_joint("hinge", JointKind::revolute, pivot, root);
  b.set_gravity(Vector3d(0, -9.81, 0));
  auto m = b.finalize();
  REQUIRE_MESSAGE(m.ok(), m.error().what());
  return {std::move(*m), body, tip};
}

/// Largest distance between the tips of the compile-time scene and the runtime model over
/// 0.5 s of swing (N modes).
template <int N>
double swing_difference(int* kernel_modes) {
  const auto beam = hinged_beam(N);
  using Hinged = Scene<double, Bodies<FFRFBody<N>>, Joints<Revolute<ground, 0>>,
                       Effects<Gravity, QuadraticVelocity>>;
  Hinged scene;
  auto body = FFRFBody<N>::from_modal_data(beam.data);
  REQUIRE(body.ok());
  scene.template body<0>() = *body;
  scene.template joint<0>().marker_i = fixed_marker<double>(Vector3d::Zero());
  scene.template joint<0>().marker_j =
      make_marker(scene.template body<0>(), beam.interface_nodes[0], Vector3d::Zero());
  ImplicitIntegrator<Hinged> integ(scene);
  typename Hinged::State s;
  REQUIRE(integ.initialize(s).ok());
  const auto old_tip = [&] {
    const auto& q = s.template coordinates<0>();
    BodyKinematics<double, N> k;
    k.p = q.p;
    const auto local = scene.template body<0>().point(beam.line.nodes.back()).local(k);
    return Vector3d(q.position + rotation_matrix(q.theta) * local);
  };

  const RuntimeBeam rt = runtime_beam(beam, N);
  *kernel_modes = rt.model.body(rt.beam).kernels->fixed_modes;
  Data<double> d(rt.model);
  REQUIRE(initialize(rt.model, d).ok());
  double diff = 0;
  for (int i = 0; i < 500; ++i) {
    REQUIRE(integ.step(s) == StepStatus::ok);
    REQUIRE(step(rt.model, d) == StepStatus::ok);
    diff = std::max(diff, (marker_frame(rt.model, d, rt.tip).origin - old_tip()).norm());
  }
  CHECK(marker_frame(rt.model, d, rt.tip).origin.y() < -0.5);  // it swung
  MESSAGE(N << " modes (kernel " << *kernel_modes << "): largest tip difference " << diff
            << " m; iterations/step " << double(d.statistics.iterations) / d.statistics.steps
            << " (scene " << double(integ.statistics().iterations) / integ.statistics().steps
            << ")");
  return diff;
}

}  // namespace

TEST_CASE("runtime model: a flexible pendulum swings as the compile-time scene's") {
  // Both solve the same equations to the Newton tolerance: acceleration errors of
  // tol = 1e-5 m/s^2 move the tip by at most tol t^2 in t = 0.5 s.
  const double bound = 1e-5 * 0.5 * 0.5;
  int fixed = 0, bounded = 0;
  CHECK(swing_difference<10>(&fixed) < bound);
  CHECK(fixed == 10);  // a count compiled with a fixed size
  CHECK(swing_difference<7>(&bounded) < bound);
  CHECK(bounded == Eigen::Dynamic);  // any other count: the bounded kernels
}

TEST_CASE("runtime model: a step allocates nothing, whatever kernel a body uses") {
  const auto beam = hinged_beam(10);
  for (int modes : {10, 7}) {
    CAPTURE(modes);
    const RuntimeBeam rt = runtime_beam(beam, modes);
    Data<double> d(rt.model);
    REQUIRE(initialize(rt.model, d).ok());
    REQUIRE(step(rt.model, d) == StepStatus::ok);
    const long long before = testing::allocations();
    Eigen::internal::set_is_malloc_allowed(false);
    StepStatus status = StepStatus::ok;
    for (int i = 0; i < 50 && status == StepStatus::ok; ++i) status = step(rt.model, d);
    Eigen::internal::set_is_malloc_allowed(true);
    CHECK(status == StepStatus::ok);
    CHECK(testing::allocations() == before);
  }
}

TEST_CASE("runtime model: a mode count the data lacks is an error naming the body") {
  const auto beam = hinged_beam(2);
  ModelBuilder<double> b;
  b.add_flexible_body("boom", beam.data, beam.data.num_modes + 1);
  auto m = b.finalize();
  REQUIRE_FALSE(m.ok());
  CHECK(m.error().what().find("body 'boom'") != std::string::npos);
}

}  // namespace test_model_flexible
