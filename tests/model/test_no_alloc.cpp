// The real-time path allocates nothing: an implicit and an explicit step of a flexible model
// (with the body kernels of a compiled mode count and the bounded ones, with geometric
// stiffening, a point load and the energy balance recording each step), the outputs and their
// damage meters, the per-step stress recovery (fused rows, the influence form, a principal
// stress, the whole field from modal stress modes), read-outs, and joints switched and anchored
// at runtime. Counted by a replaced operator new; Eigen's own guard (EIGEN_RUNTIME_NO_MALLOC)
// aborts on any Eigen heap allocation in builds with assertions (the sanitizer build in CI).
#include <cmath>
#include <vector>

#include <doctest/doctest.h>

#include <flexstress/fatigue/sn_curve.hpp>
#include <flexstress/fe/rhs_attachment_mesh.hpp>
#include <flexstress/model/all.hpp>
#include <flexstress/reduction/modal_geometric_stiffness.hpp>
#include <flexstress/stress/deformed_shape.hpp>
#include <flexstress/stress/fused_stress.hpp>
#include <flexstress/stress/host_point.hpp>
#include <flexstress/stress/modal_stress_modes.hpp>
#include <flexstress/stress/stress_outputs.hpp>
#include <flexstress/stress/sub_model.hpp>

#include "support/beam_fixtures.hpp"
#include "support/counting_new.hpp"

namespace test_no_alloc {

using namespace flexstress;

namespace {

constexpr int N = 4;  // not a compiled count: the bounded kernels (kFixed: the compiled ones)
constexpr int kFixed = 10;

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

// Takes `steps` steps (up to a failed one) and returns the allocations they made.
long long allocations_in_steps(const Model<double>& model, Data<double>& d, int steps) {
  NoAllocationScope scope;
  for (int i = 0; i < steps; ++i)
    if (step(model, d) != StepStatus::ok) break;
  return scope.count();
}

// The host: a 1.2 m RHS 150x100x4 beam hinged at x = 0, `modes` modes, 2 % damping.
testing::BeamBody hinged_host(int modes = N) {
  auto host = testing::make_beam_body(1.2, fe::rectangular_hollow_section(0.150, 0.100, 0.004), 12,
                                      {0.0}, modes);
  host.data.damping_ratios.setConstant(0.02);
  return host;
}

struct Hinged {
  Model<double> model;
  BodyId body;
  JointId hinge;
  OutputRange outputs;  ///< with fused rows
  MeterId meter;        ///< on the first output
};

// The host on a revolute joint about z under gravity; optionally geometrically stiffened, with
// a point load at its far end and stress outputs (fused rows) with a damage meter on the first.
Hinged make_hinged(const testing::BeamBody& host, int modes, bool stiffened = false,
                   const Eigen::MatrixXd* fused_rows = nullptr) {
  ModelBuilder<double> b;
  Hinged h;
  h.body = b.add_flexible_body("host", host.data, modes);
  h.hinge = b.add_joint("hinge", JointKind::revolute, b.add_marker("pivot", b.ground(), -1),
                        b.add_marker("root", h.body, host.interface_nodes[0]));
  b.set_gravity(Vector3d(0, -9.81, 0));
  if (stiffened) {
    auto g = reduction::modal_geometric_stiffness(host.mesh, host.data,
                                                  reduction::clamp_interface_nodes(host.data));
    REQUIRE(g.ok());
    b.add_geometric_stiffening(h.body, *g);
    b.add_point_load("push", b.add_marker("end", h.body, host.line.nodes.back()),
                     [](double t, const double*, const double*, double* f, double* m, void*) {
                       f[1] = 50.0 * std::sin(20.0 * t);
                       m[2] = 5.0;
                     });
  }
  if (fused_rows != nullptr) {
    h.outputs = b.add_stress_outputs("detail", h.body, *fused_rows);
    // IIW FAT 100 on 128 classes of -400..400 MPa (as the crane's meter).
    auto curve = fatigue::iiw_normal_curve(100.0, fatigue::IiwBeyondKnee::haibach);
    REQUIRE(curve.ok());
    auto damage = fatigue::DamageModel<double>::create(*curve);
    REQUIRE(damage.ok());
    auto grid = fatigue::ClassGrid<double>::create(-400.0, 400.0, 128);
    REQUIRE(grid.ok());
    auto meter = DamageMeter<double>::create(*grid, 0, *damage);
    REQUIRE(meter.ok());
    h.meter = b.add_damage_meter("hot spot", h.outputs[0], *meter, 1e-6);
  }
  auto m = b.finalize();
  REQUIRE_MESSAGE(m.ok(), m.error().what());
  h.model = std::move(*m);
  return h;
}

// Allocations counted over 200 RK4 steps at a stable step size (after one warm-up step).
long long explicit_steps_allocate(const Hinged& h) {
  double w = 0;
  for (const auto& body : h.model.bodies()) w = std::max(w, body.max_frequency);
  ExplicitSettings<double> es;
  es.step = 0.5 / w;
  Data<double> e(h.model);
  REQUIRE(explicit_step(h.model, e, es) == StepStatus::ok);
  long long counted = 0;
  {
    NoAllocationScope scope;
    for (int i = 0; i < 200; ++i)
      if (explicit_step(h.model, e, es) != StepStatus::ok) break;
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

TEST_CASE("a flexible model's steps, outputs and the stress recovery allocate nothing") {
  const auto host = hinged_host();
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

  const Eigen::MatrixXd fused_rows = fused->rows();
  const Hinged h = make_hinged(host, N, false, &fused_rows);
  Data<double> s(h.model);
  REQUIRE(initialize(h.model, s).ok());
  REQUIRE(step(h.model, s) == StepStatus::ok);  // warm-up outside the scope
  VectorXd y(fused->num_outputs()), y2(fused->num_outputs());
  double checksum = 0;
  long long counted = 0;
  {
    NoAllocationScope scope;
    for (int i = 0; i < 200; ++i) {
      if (step(h.model, s) != StepStatus::ok) break;
      if (evaluate_outputs(h.model, s) != StepStatus::ok) break;
      const Vec<double, N> p = modal_coordinates(h.model, s, h.body);
      fused->evaluate(p, y);
      fused->evaluate_by_influence(p, y2);
      checksum += y(0) + y2(0) + fused->evaluate(0, p) + output_value(s, h.outputs[0]);
      field_modes->evaluate(p, field);
      checksum += field(0) + field_modes->max_von_mises(p);
      checksum += stress::principal_near_direction<double>(fused->tensor(tensor, p),
                                                           Vector3d::UnitX(), 1.0471975511965976);
      // Read-outs by handle.
      checksum += joint_reaction(h.model, s, h.hinge).force.norm() +
                  body_position(h.model, s, h.body).norm() + energy(h.model, s).total() +
                  momentum(h.model, s).angular.norm() + meter_damage(s, h.meter);
    }
    counted = scope.count();
  }
  CHECK(counted == 0);
  CHECK(s.t == doctest::Approx(0.201).epsilon(1e-9));  // all 200 steps ran
  CHECK(std::isfinite(checksum));
  CHECK(explicit_steps_allocate(h) == 0);
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

TEST_CASE("with the kernels of a compiled mode count the steps allocate nothing either") {
  const auto host = hinged_host(kFixed);
  const Hinged h = make_hinged(host, kFixed);
  Data<double> s(h.model);
  // Spinning about the hinge: every term of the step is exercised.
  set_body_velocity(h.model, s, h.body, Vector3d::Zero(), Vector3d(0, 0, 2.0));
  REQUIRE(initialize(h.model, s).ok());
  REQUIRE(step(h.model, s) == StepStatus::ok);
  long long counted = allocations_in_steps(h.model, s, 200);
  CHECK(counted == 0);
  CHECK(s.t == doctest::Approx(0.201).epsilon(1e-9));
  CHECK(explicit_steps_allocate(h) == 0);

  // Runtime changes: the hinge freed, then anchored where the body has flown and switched on
  // again (a capture); the steps that follow restart the integrator, without allocating either.
  bool all_ok = true;
  {
    NoAllocationScope scope;
    set_joint_active(h.model, s, h.hinge, false);
    for (int i = 0; i < 20; ++i) all_ok = all_ok && step(h.model, s) == StepStatus::ok;
    all_ok = all_ok && anchor_joint_at(h.model, s, h.hinge).ok();
    set_joint_active(h.model, s, h.hinge, true);
    for (int i = 0; i < 20; ++i) all_ok = all_ok && step(h.model, s) == StepStatus::ok;
    counted = scope.count();
  }
  CHECK(all_ok);
  CHECK(counted == 0);
}

TEST_CASE("geometric stiffening, a point load and the energy balance allocate nothing either") {
  const auto host = hinged_host();
  const Hinged h = make_hinged(host, N, /*stiffened=*/true);
  Data<double> s(h.model);
  set_body_velocity(h.model, s, h.body, Vector3d::Zero(), Vector3d(0, 0, 2.0));
  REQUIRE(initialize(h.model, s).ok());
  EnergyBalance<double> audit;
  audit.start(h.model, s);
  REQUIRE(step(h.model, s) == StepStatus::ok);
  audit.record(h.model, s);
  long long counted = 0;
  {
    NoAllocationScope scope;
    for (int i = 0; i < 200; ++i) {
      if (step(h.model, s) != StepStatus::ok) break;
      audit.record(h.model, s);
    }
    counted = scope.count();
  }
  CHECK(counted == 0);
  CHECK(s.t == doctest::Approx(0.201).epsilon(1e-9));
  CHECK(std::isfinite(audit.residual()));
  CHECK(explicit_steps_allocate(h) == 0);
}

TEST_CASE("a step taken in pieces allocates nothing either") {
  // The stiffened host with its point load (a force element: its state is saved too), spun at
  // 30 rad/s with 50 ms steps: 1.5 rad per step, which the local error control splits.
  const auto host = hinged_host();
  const Hinged h = make_hinged(host, N, /*stiffened=*/true);
  Data<double> s(h.model);
  s.settings.step = 0.05;
  set_body_velocity(h.model, s, h.body, Vector3d::Zero(), Vector3d(0, 0, 30.0));
  REQUIRE(initialize(h.model, s).ok());
  REQUIRE(step(h.model, s) == StepStatus::ok);
  CHECK(allocations_in_steps(h.model, s, 10) == 0);
  CHECK(s.statistics.split_steps > 1);
  CHECK(s.t == doctest::Approx(0.55).epsilon(1e-9));
}

TEST_CASE("velocities projected after they drift allocate nothing either") {
  // A drift limit far below any run's drift projects the velocities after every step, in the
  // mass metric (its own factorization; the next step then factorizes its own matrix).
  const auto host = hinged_host();
  const Hinged h = make_hinged(host, N);
  Data<double> s(h.model);
  s.settings.velocity_drift_limit = 1e-15;
  set_body_velocity(h.model, s, h.body, Vector3d::Zero(), Vector3d(0, 0, 3.0));
  REQUIRE(initialize(h.model, s).ok());
  REQUIRE(step(h.model, s) == StepStatus::ok);
  CHECK(allocations_in_steps(h.model, s, 10) == 0);
  CHECK(s.t == doctest::Approx(0.011).epsilon(1e-9));
  CHECK(s.statistics.drift_projections >= 10);
}

}  // namespace test_no_alloc
