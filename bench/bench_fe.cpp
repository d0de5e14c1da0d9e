// FE kernel benchmarks (Google Benchmark; build Release): assembly, factorization
// (StaticSolver::factorize) and one static solve of the RHS sub-model at three densities
// (about 500, 1800 and 8000 bricks; labels give bricks and DOFs), and the eigen solve of a
// 20-element cantilever beam (4 and 10 modes, dense and subspace iteration). Each benchmark
// repeats 5 times and reports mean, median and max (the worst case matters to real-time users).
//
// Run: ./build/bench/bench_fe --benchmark_format=console
#include <string>

#include <benchmark/benchmark.h>

#include <flexstress/fe/assembly.hpp>
#include <flexstress/fe/beam_line.hpp>
#include <flexstress/fe/eigen_solver.hpp>
#include <flexstress/fe/rhs_attachment_mesh.hpp>
#include <flexstress/fe/static_solver.hpp>

using namespace flexstress;
using namespace flexstress::fe;

namespace {

constexpr double kDensities[3] = {0.6, 1.0, 1.6};

// The sub-model as the paper uses it: end sections tied by rigid links to centre-line masters,
// master 0 clamped, master 1 loaded by a bending moment.
struct RhsCase {
  Mesh mesh;
  BoundaryConditions bc;
  Index loaded = 0;
  std::string label;
  explicit RhsCase(double density) {
    RhsAttachmentSpec spec;
    spec.density = density;
    auto r = make_rhs_attachment_mesh(spec);
    if (!r) return;
    mesh = std::move(r->mesh);
    const Index m0 = mesh.add_node(Vector3d(spec.x0, 0, 0));
    loaded = mesh.add_node(Vector3d(spec.x1, 0, 0));
    mesh.add_rigid_link(m0, r->end_section_x0);
    mesh.add_rigid_link(loaded, r->end_section_x1);
    bc.clamp(m0);
    auto model = assemble(mesh, bc);
    if (model)
      label = "bricks=" + std::to_string(mesh.hexes().size()) +
              " dofs=" + std::to_string(model->dofs.size()) +
              " free=" + std::to_string(model->constraints.num_free());
  }
};

const RhsCase& rhs_case(int i) {
  static const RhsCase cases[3] = {RhsCase(kDensities[0]), RhsCase(kDensities[1]),
                                   RhsCase(kDensities[2])};
  return cases[i];
}

void BM_RhsAssembly(benchmark::State& state) {
  const RhsCase& c = rhs_case(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    auto model = assemble(c.mesh, c.bc);
    if (!model) state.SkipWithError(model.error().message.c_str());
    benchmark::DoNotOptimize(model);
  }
  state.SetLabel(c.label);
}

void BM_RhsFactorize(benchmark::State& state) {
  const RhsCase& c = rhs_case(static_cast<int>(state.range(0)));
  auto model = assemble(c.mesh, c.bc);
  if (!model) {
    state.SkipWithError(model.error().message.c_str());
    return;
  }
  for (auto _ : state) {
    auto solver = StaticSolver::factorize(c.mesh, *model);
    if (!solver) state.SkipWithError(solver.error().message.c_str());
    benchmark::DoNotOptimize(solver);
  }
  state.SetLabel(c.label);
}

void BM_RhsSolve(benchmark::State& state) {
  const RhsCase& c = rhs_case(static_cast<int>(state.range(0)));
  auto model = assemble(c.mesh, c.bc);
  if (!model) {
    state.SkipWithError(model.error().message.c_str());
    return;
  }
  auto solver = StaticSolver::factorize(c.mesh, *model);
  auto f = load_vector(model->dofs, {{c.loaded, 5, 1e4}});
  if (!solver || !f) {
    state.SkipWithError("factorization or load failed");
    return;
  }
  for (auto _ : state) {
    VectorXd u = solver->solve(*f);
    benchmark::DoNotOptimize(u.data());
  }
  state.SetLabel(c.label);
}

// The crane boom as a 20-element Euler-Bernoulli cantilever (paper, Table 2).
void BM_BeamEigen(benchmark::State& state) {
  Mesh mesh;
  BeamLineSpec spec;
  spec.end = Vector3d(4.5, 0, 0);
  spec.num_elements = 20;
  spec.material = mesh.add_material(steel());
  spec.section = mesh.add_section(rectangular_hollow_section(0.15, 0.10, 0.004));
  const BeamLine line = add_beam_line(mesh, spec);
  BoundaryConditions bc;
  bc.clamp(line.nodes.front());
  auto model = assemble(mesh, bc);
  if (!model) {
    state.SkipWithError(model.error().message.c_str());
    return;
  }
  EigenOptions options;
  options.num_modes = static_cast<int>(state.range(0));
  options.method = state.range(1) == 0 ? EigenMethod::dense : EigenMethod::subspace_iteration;
  for (auto _ : state) {
    auto modes = solve_eigen(model->stiffness, model->mass, options);
    if (!modes) state.SkipWithError(modes.error().message.c_str());
    benchmark::DoNotOptimize(modes);
  }
  state.SetLabel(std::string(state.range(1) == 0 ? "dense" : "subspace") +
                 " dofs=" + std::to_string(model->stiffness.rows()));
}

double max_of(const std::vector<double>& v) {
  double m = v.empty() ? 0.0 : v.front();
  for (double x : v) m = x > m ? x : m;
  return m;
}

}  // namespace

BENCHMARK(BM_RhsAssembly)
    ->DenseRange(0, 2)
    ->Unit(benchmark::kMillisecond)
    ->Repetitions(5)
    ->ComputeStatistics("max", max_of);
BENCHMARK(BM_RhsFactorize)
    ->DenseRange(0, 2)
    ->Unit(benchmark::kMillisecond)
    ->Repetitions(5)
    ->ComputeStatistics("max", max_of);
BENCHMARK(BM_RhsSolve)
    ->DenseRange(0, 2)
    ->Unit(benchmark::kMillisecond)
    ->Repetitions(5)
    ->ComputeStatistics("max", max_of);
BENCHMARK(BM_BeamEigen)
    ->ArgsProduct({{4, 10}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->Repetitions(5)
    ->ComputeStatistics("max", max_of);

BENCHMARK_MAIN();
