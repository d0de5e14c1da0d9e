// Per-step stress recovery from a sub-model (Google Benchmark; build Release). The host is the
// crane boom's section as a 12-element beam reduced by Craig-Bampton to 10 modes; the sub-model
// is the RHS detail with its welded rib (density 1.0: 1792 bricks) tied at 0.5 and 0.8 m.
//   fused_row/k         one hot spot: a dot product of length NModes
//   fused_all           every output (hot spots along the toe, tensors, gauges) as F p
//   influence_all       the paper's route: u_b = Phi_b p, then H u_b
//   principal           a fused tensor, then the principal stress near the toe normal
//   modal_field         the whole nodal stress field from modal stress modes, S p
//   modal_field_max_von_mises  the largest von Mises stress over the field (a scan)
//   full_resolve        what the influence matrix replaces: a solve with the factorization and
//                       the stress recovery at the read-out points
//   precompute          SubModel::build (assembly, factorization, 12 unit solves) + rows
//
// Run: ./build/bench/bench_stress --benchmark_format=console
#include <cmath>
#include <optional>
#include <string>

#include <benchmark/benchmark.h>

#include <flexstress/fe/beam_line.hpp>
#include <flexstress/fe/rhs_attachment_mesh.hpp>
#include <flexstress/reduction/modal_body_data.hpp>
#include <flexstress/stress/fused_stress.hpp>
#include <flexstress/stress/host_point.hpp>
#include <flexstress/stress/modal_stress_modes.hpp>
#include <flexstress/stress/stress_outputs.hpp>
#include <flexstress/stress/sub_model.hpp>

using namespace flexstress;
using namespace flexstress::stress;

namespace {

constexpr int kModes = 10;

struct Setup {
  reduction::ModalBodyData host;
  std::vector<HostPoint> hosts;
  fe::RhsAttachmentMesh rhs;
  std::vector<SubModelAttachment> attachments;
  StressOutputs outputs;
  Index first_tensor = 0;
  bool ok = false;

  explicit Setup(double density) {
    fe::Mesh mesh;
    fe::BeamLineSpec spec;
    spec.end = Vector3d(1.2, 0, 0);
    spec.num_elements = 12;
    spec.extra_positions = {0.5, 0.8};
    spec.material = mesh.add_material(fe::steel());
    spec.section = mesh.add_section(fe::rectangular_hollow_section(0.150, 0.100, 0.004));
    const auto line = fe::add_beam_line(mesh, spec);
    reduction::ReductionSpec rs;
    rs.interface = {{line.node_at(0.0)}, {line.node_at(1.2)}};
    rs.dynamic_modes.count = kModes;
    auto data = reduction::reduce(mesh, rs);
    if (!data) return;
    host = std::move(*data);
    hosts = {HostPoint::at_node(line.node_at(0.5)), HostPoint::at_node(line.node_at(0.8))};
    fe::RhsAttachmentSpec rspec;
    rspec.density = density;
    auto r = fe::make_rhs_attachment_mesh(rspec);
    if (!r) return;
    rhs = std::move(*r);
    attachments = {{Vector3d(0.5, 0, 0), rhs.end_section_x0},
                   {Vector3d(0.8, 0, 0), rhs.end_section_x1}};
    // Hot spots along the toe line (type a linear, every toe node across the flange), one
    // tensor next to the toe, one strain gauge.
    for (Index n : rhs.weld_toe_nodes) {
      HotSpotLocation h;
      h.toe = rhs.mesh.node(n);
      h.away = Vector3d::UnitX();
      h.thickness = rspec.wall;
      if (!outputs.add_hot_spot(h)) return;
    }
    first_tensor = outputs.add_tensor(Vector3d(rhs.weld_toe_x + 0.0016, 0.075, 0.0));
    if (!outputs.add_strain_gauge(Vector3d(0.56, 0.075, 0), Vector3d::UnitX(), 0.006)) return;
    ok = true;
  }
};

struct Recovery {
  Setup setup{1.0};
  std::optional<SubModel> sub;
  std::optional<FusedStress<kModes>> fused;
  MatrixXd rows;
  Recovery() {
    if (!setup.ok) return;
    auto s = SubModel::build(setup.rhs.mesh, setup.attachments);
    if (!s) return;
    sub.emplace(std::move(*s));
    auto r = setup.outputs.rows(*sub);
    if (!r) return;
    rows = std::move(*r);
    auto phi = boundary_modes(setup.host, setup.hosts);
    if (!phi) return;
    auto f = FusedStress<kModes>::build(rows, *phi);
    if (!f) return;
    fused.emplace(std::move(*f));
    auto m = ModalStressModes<kModes>::build(*sub, *phi);
    if (!m) return;
    field.emplace(std::move(*m));
  }
  std::optional<ModalStressModes<kModes>> field;
  bool ok() const { return fused.has_value() && field.has_value(); }
};

Recovery& recovery() {
  static Recovery r;
  return r;
}

Eigen::Matrix<double, kModes, 1> modal_state(int i) {
  Eigen::Matrix<double, kModes, 1> p;
  for (int k = 0; k < kModes; ++k) p(k) = 1e-4 * std::sin(0.37 * i + k);
  return p;
}

void fused_row(benchmark::State& state) {
  auto& r = recovery();
  if (!r.ok()) return state.SkipWithError("setup failed");
  const auto p = modal_state(1);
  for (auto _ : state) {
    double s = r.fused->evaluate(0, p);
    benchmark::DoNotOptimize(s);
  }
  state.SetLabel(std::to_string(kModes) + " modes, one hot spot");
}

void fused_all(benchmark::State& state) {
  auto& r = recovery();
  if (!r.ok()) return state.SkipWithError("setup failed");
  const auto p = modal_state(2);
  VectorXd y(r.fused->num_outputs());
  for (auto _ : state) {
    r.fused->evaluate(p, y);
    benchmark::DoNotOptimize(y.data());
  }
  state.SetLabel(std::to_string(r.fused->num_outputs()) + " outputs");
  state.counters["per_output_ns"] = benchmark::Counter(
      static_cast<double>(r.fused->num_outputs()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void influence_all(benchmark::State& state) {
  auto& r = recovery();
  if (!r.ok()) return state.SkipWithError("setup failed");
  const auto p = modal_state(3);
  VectorXd y(r.fused->num_outputs());
  for (auto _ : state) {
    r.fused->evaluate_by_influence(p, y);
    benchmark::DoNotOptimize(y.data());
  }
  state.SetLabel(std::to_string(r.fused->num_outputs()) + " outputs");
}

void principal(benchmark::State& state) {
  auto& r = recovery();
  if (!r.ok()) return state.SkipWithError("setup failed");
  const auto p = modal_state(4);
  const double limit = 60.0 * 3.14159265358979323846 / 180.0;
  for (auto _ : state) {
    const Vec6<double> s = r.fused->tensor(r.setup.first_tensor, p);
    double v = principal_near_direction<double>(s, Vector3d::UnitX(), limit);
    benchmark::DoNotOptimize(v);
  }
}

void modal_field(benchmark::State& state) {
  auto& r = recovery();
  if (!r.ok()) return state.SkipWithError("setup failed");
  const auto p = modal_state(6);
  VectorXd y(6 * r.field->num_nodes());
  for (auto _ : state) {
    r.field->evaluate(p, y);
    benchmark::DoNotOptimize(y.data());
  }
  state.SetLabel(std::to_string(r.field->num_nodes()) + " nodes, 6 components");
}

void modal_field_max_von_mises(benchmark::State& state) {
  auto& r = recovery();
  if (!r.ok()) return state.SkipWithError("setup failed");
  const auto p = modal_state(7);
  for (auto _ : state) {
    Index where = -1;
    double v = r.field->max_von_mises(p, &where);
    benchmark::DoNotOptimize(v);
  }
}

void full_resolve(benchmark::State& state) {
  auto& r = recovery();
  if (!r.ok()) return state.SkipWithError("setup failed");
  auto phi = boundary_modes(r.setup.host, r.setup.hosts);
  const VectorXd ub = *phi * modal_state(5);
  const auto& points = r.setup.outputs.stress_points();
  for (auto _ : state) {
    auto s = r.sub->stresses_by_resolve(points, ub);
    benchmark::DoNotOptimize(s.ok());
  }
  state.SetLabel(std::to_string(r.sub->model().dofs.size()) + " DOFs, " +
                 std::to_string(points.size()) + " read-out points");
}

void precompute(benchmark::State& state) {
  Setup setup(1.0);
  if (!setup.ok) return state.SkipWithError("setup failed");
  for (auto _ : state) {
    auto s = SubModel::build(setup.rhs.mesh, setup.attachments);
    if (!s) return state.SkipWithError("build failed");
    auto rows = setup.outputs.rows(*s);
    benchmark::DoNotOptimize(rows.ok());
  }
  state.SetLabel(std::to_string(setup.rhs.mesh.hexes().size()) + " bricks");
}

}  // namespace

BENCHMARK(fused_row)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(fused_all)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(influence_all)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(principal)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(modal_field)->Unit(benchmark::kMicrosecond)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(modal_field_max_von_mises)
    ->Unit(benchmark::kMicrosecond)
    ->Repetitions(5)
    ->ReportAggregatesOnly(true);
BENCHMARK(full_resolve)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(precompute)->Unit(benchmark::kMillisecond)->Iterations(1)->Repetitions(3);

BENCHMARK_MAIN();
