// The real-time path allocates nothing: an implicit and an explicit step of a flexible scene
// (also with geometric stiffening, and with the energy audit recording each step), and the
// per-step stress recovery (fused rows, the influence form, a principal stress, the whole field
// from modal stress modes), and joints switched at runtime. Counted
// by a replaced operator new; Eigen's own guard (EIGEN_RUNTIME_NO_MALLOC) aborts on any Eigen
// heap allocation in builds with assertions (the sanitizer build in CI).
#include <cmath>
#include <vector>

#include <doctest/doctest.h>

#include <flexstress/dynamics/energy_audit.hpp>
#include <flexstress/dynamics/explicit_integrator.hpp>
#include <flexstress/dynamics/implicit_integrator.hpp>
#include <flexstress/fe/rhs_attachment_mesh.hpp>
#include <flexstress/reduction/modal_geometric_stiffness.hpp>
#include <flexstress/stress/deformed_shape.hpp>
#include <flexstress/stress/fused_stress.hpp>
#include <flexstress/stress/host_point.hpp>
#include <flexstress/stress/modal_stress_modes.hpp>
#include <flexstress/stress/stress_outputs.hpp>
#include <flexstress/stress/sub_model.hpp>

#include "dynamics/fixtures.hpp"
#include "support/counting_new.hpp"

namespace test_no_alloc {

using namespace flexstress;

namespace {

constexpr int N = 4;
using Hinged = Scene<double, Bodies<FFRFBody<N>>, Joints<Revolute<ground, 0>>,
                     Effects<Gravity, QuadraticVelocity, ModalDamping>>;

// Counts operator new and forbids Eigen heap allocations while alive.
class NoAllocationScope {
 public:
  NoAllocationScope() : before_(testing::allocations()) {
    Eigen::internal::set_is_malloc_allowed(false);
  }
  ~NoAllocationScope() { Eigen::internal::set_is_malloc_allowed(true); }
  long long count() const { return testing::allocations() - before_; }

 private:
  long long before_;
};

// The host: a 1.2 m RHS 150x100x4 beam hinged at x = 0, N modes, 2 % damping.
testing::BeamBody hinged_host() {
  auto host = testing::make_beam_body(1.2, fe::rectangular_hollow_section(0.150, 0.100, 0.004), 12,
                                      {0.0}, N);
  host.data.damping_ratios.setConstant(0.02);
  return host;
}

template <class SceneT>
SceneT make_hinged(const testing::BeamBody& host) {
  SceneT scene;
  auto body = FFRFBody<N>::from_modal_data(host.data);
  REQUIRE(body.ok());
  scene.template body<0>() = *body;
  scene.template joint<0>().marker_i = fixed_marker<double>(Vector3d::Zero());
  scene.template joint<0>().marker_j =
      make_marker(scene.template body<0>(), host.interface_nodes[0], Vector3d::Zero());
  return scene;
}

// Allocations counted over 200 RK4 steps at a stable step size (after one warm-up step).
template <class SceneT>
long long explicit_steps_allocate(const SceneT& scene) {
  typename ExplicitIntegrator<SceneT>::Settings es;
  es.step = 0.5 / scene.max_modal_frequency();
  ExplicitIntegrator<SceneT> rk4(scene, es);
  typename SceneT::State e;
  REQUIRE(rk4.step(e) == StepStatus::ok);
  long long counted = 0;
  {
    NoAllocationScope scope;
    for (int i = 0; i < 200; ++i)
      if (rk4.step(e) != StepStatus::ok) break;
    counted = scope.count();
  }
  CHECK(e.t > 200 * es.step);
  return counted;
}

}  // namespace

TEST_CASE("the counting operator new sees allocations") {
  const long long before = testing::allocations();
  auto* v = new std::vector<int>(10);
  CHECK(testing::allocations() - before >= 2);
  delete v;
}

TEST_CASE("a flexible scene's steps and the stress recovery allocate nothing") {
  const auto host = hinged_host();
  const auto scene = make_hinged<Hinged>(host);
  // Sub-model at 0.5 to 0.8 m with a hot spot, a tensor and a gauge.
  fe::RhsAttachmentSpec rs;
  rs.density = 0.6;
  auto detail = fe::make_rhs_attachment_mesh(rs);
  REQUIRE(detail.ok());
  auto sub = stress::SubModel::build(detail->mesh, {{Vector3d(0.5, 0, 0), detail->end_section_x0},
                                                    {Vector3d(0.8, 0, 0), detail->end_section_x1}});
  REQUIRE(sub.ok());
  stress::StressOutputs out;
  stress::HotSpotLocation hs;
  hs.toe = Vector3d(detail->weld_toe_x, 0.075, 0);
  hs.thickness = 0.004;
  REQUIRE(out.add_hot_spot(hs).ok());
  const Index tensor = out.add_tensor(Vector3d(0.56, 0.075, 0));
  REQUIRE(out.add_strain_gauge(Vector3d(0.56, 0.075, 0), Vector3d::UnitX(), 0.003).ok());
  auto rows = out.rows(*sub);
  REQUIRE(rows.ok());
  auto phi =
      stress::boundary_modes(host.data, {stress::HostPoint::at_node(host.line.node_at(0.5)),
                                         stress::HostPoint::at_node(host.line.node_at(0.8))});
  REQUIRE(phi.ok());
  auto fused = stress::FusedStress<N>::build(*rows, *phi);
  REQUIRE(fused.ok());
  auto field_modes = stress::ModalStressModes<N>::build(*sub, *phi);
  REQUIRE(field_modes.ok());
  VectorXd field(6 * field_modes->num_nodes());

  Hinged::State s;
  ImplicitIntegrator<Hinged> implicit(scene);
  REQUIRE(implicit.initialize(s).ok());
  REQUIRE(implicit.step(s) == StepStatus::ok);  // warm-up outside the scope
  VectorXd y(fused->num_outputs()), y2(fused->num_outputs());
  double checksum = 0;
  long long counted = 0;
  {
    NoAllocationScope scope;
    for (int i = 0; i < 200; ++i) {
      if (implicit.step(s) != StepStatus::ok) break;
      fused->evaluate(s.coordinates<0>().p, y);
      fused->evaluate_by_influence(s.coordinates<0>().p, y2);
      checksum += y(0) + y2(0) + fused->evaluate(0, s.coordinates<0>().p);
      field_modes->evaluate(s.coordinates<0>().p, field);
      checksum += field(0) + field_modes->max_von_mises(s.coordinates<0>().p);
      checksum += stress::principal_near_direction<double>(
          fused->tensor(tensor, s.coordinates<0>().p), Vector3d::UnitX(), 1.0471975511965976);
    }
    counted = scope.count();
  }
  CHECK(counted == 0);
  CHECK(s.t == doctest::Approx(0.201).epsilon(1e-9));  // all 200 steps ran
  CHECK(std::isfinite(checksum));
  CHECK(explicit_steps_allocate(scene) == 0);
}

TEST_CASE("the deformed shape at render vertices allocates nothing per frame") {
  const auto host = hinged_host();
  std::vector<Vector3d> vertices;
  for (int i = 0; i <= 48; ++i) vertices.emplace_back(0.025 * i, 0.075, 0.0);  // top flange
  auto shape = stress::DeformedShape<N>::along_beam(host.data, host.line.nodes, vertices);
  REQUIRE(shape.ok());
  Eigen::Matrix3Xd out(3, shape->size());
  const Vec<double, N> p = Vec<double, N>::LinSpaced(1e-3, 4e-3);
  const Vec4<double> theta(std::cos(0.1), 0, 0, std::sin(0.1));
  NoAllocationScope scope;
  for (int frame = 0; frame < 100; ++frame) shape->evaluate(Vector3d(1, 2, 3), theta, p, out);
  CHECK(scope.count() == 0);
  CHECK(out.allFinite());
}

TEST_CASE("with dynamic storage (allocated once at setup) the steps allocate nothing either") {
  using Dynamic = Hinged::with_storage_limit<0>;
  static_assert(!Dynamic::fixed_storage);
  const auto scene = make_hinged<Dynamic>(hinged_host());
  Dynamic::State s;
  s.v(5) = 2.0;  // spinning about the hinge: every term of the step is exercised
  ImplicitIntegrator<Dynamic> implicit(scene);
  REQUIRE(implicit.initialize(s).ok());
  REQUIRE(implicit.step(s) == StepStatus::ok);
  long long counted = 0;
  {
    NoAllocationScope scope;
    for (int i = 0; i < 200; ++i)
      if (implicit.step(s) != StepStatus::ok) break;
    counted = scope.count();
  }
  CHECK(counted == 0);
  CHECK(s.t == doctest::Approx(0.201).epsilon(1e-9));
  CHECK(explicit_steps_allocate(scene) == 0);

  // Runtime changes: the hinge freed, then anchored where the body has flown and switched on
  // again (a capture); the steps that follow restart the integrator, without allocating either.
  Dynamic changing = scene;
  ImplicitIntegrator<Dynamic> restarting(changing);
  REQUIRE(restarting.initialize(s).ok());
  bool all_ok = true;
  {
    NoAllocationScope scope;
    changing.set_joint_active<0>(false);
    for (int i = 0; i < 20; ++i) all_ok = all_ok && restarting.step(s) == StepStatus::ok;
    changing.anchor_joint_at<0>(s, restarting.workspace());
    changing.set_joint_active<0>(true);
    for (int i = 0; i < 20; ++i) all_ok = all_ok && restarting.step(s) == StepStatus::ok;
    counted = scope.count();
  }
  CHECK(all_ok);
  CHECK(counted == 0);
}

TEST_CASE("geometric stiffening and the energy audit allocate nothing per step either") {
  using Stiffened = Scene<double, Bodies<FFRFBody<N>>, Joints<Revolute<ground, 0>>,
                          Effects<Gravity, QuadraticVelocity, ModalDamping, GeometricStiffening>>;
  const auto host = hinged_host();
  auto scene = make_hinged<Stiffened>(host);
  auto g = reduction::modal_geometric_stiffness(host.mesh, host.data,
                                                reduction::clamp_interface_nodes(host.data));
  REQUIRE(g.ok());
  REQUIRE(scene.body<0>().set_geometric_stiffness(*g).ok());
  Stiffened::State s;
  s.v(5) = 2.0;  // spinning: the centrifugal load cases contribute
  ImplicitIntegrator<Stiffened> implicit(scene);
  REQUIRE(implicit.initialize(s).ok());
  EnergyAudit<Stiffened> audit(scene);
  audit.start(s);
  REQUIRE(implicit.step(s) == StepStatus::ok);
  audit.record(s);
  long long counted = 0;
  {
    NoAllocationScope scope;
    for (int i = 0; i < 200; ++i) {
      if (implicit.step(s) != StepStatus::ok) break;
      audit.record(s);
    }
    counted = scope.count();
  }
  CHECK(counted == 0);
  CHECK(s.t == doctest::Approx(0.201).epsilon(1e-9));
  CHECK(std::isfinite(audit.residual()));
  CHECK(explicit_steps_allocate(scene) == 0);
}

}  // namespace test_no_alloc
