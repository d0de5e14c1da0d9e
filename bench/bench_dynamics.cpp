// Per-step cost of the dynamics (Google Benchmark; build Release). Each benchmark times every one
// of its steps and reports the median and the worst (counters median_us, worst_us), plus the
// Newton iterations per step; the benchmark's own time is the whole run.
//   hinged_implicit/modes:N  a 2 m steel beam (RHS 40x20x2, 24 elements) with N Craig-Bampton
//                            modes on a revolute joint, swinging under gravity from horizontal,
//                            1e5 steps at h = 1 ms; counter fixed_kernel: 1 where N has
//                            fixed-size body kernels (FLEXSTRESS_MODE_COUNTS), 0 bounded
//   hinged_bounded/modes:N   the same on the bounded kernels (ModelBuilder::use_bounded_kernels)
//                            where N has fixed-size ones: what the fixed sizes save
//   hinged_effects/...       the same with N = 10 and only the effects switched on (spinning at
//                            2 rad/s so every variant moves): the cost of each effect
//   hinged_rk4/modes:N       explicit RK4 at its stable step (h w_max = 2), 1e5 steps
// The crane's rows are in bench_crane.cpp. Results: docs/performance.md.
//
// Run: ./build/bench/bench_dynamics --benchmark_counters_tabular=true
#include <optional>

#include <benchmark/benchmark.h>

#include <flexstress/fe/beam_line.hpp>
#include <flexstress/model/all.hpp>
#include <flexstress/reduction/modal_body_data.hpp>

#include "step_timing.hpp"

using namespace flexstress;

namespace {

constexpr int kSteps = 100000;

// The hinged beam's modal data with n fixed-interface modes (hinge node as the interface).
struct HingedBeam {
  reduction::ModalBodyData data;
  Index hinge = -1;
  bool ok = false;
  explicit HingedBeam(int modes) {
    fe::Mesh mesh;
    fe::BeamLineSpec spec;
    spec.end = Vector3d(2.0, 0, 0);
    spec.num_elements = 24;
    spec.material = mesh.add_material(fe::steel());
    spec.section = mesh.add_section(fe::rectangular_hollow_section(0.04, 0.02, 0.002));
    const auto line = fe::add_beam_line(mesh, spec);
    hinge = line.node_at(0.0);
    reduction::ReductionSpec rs;
    rs.interface = {{hinge}};
    rs.dynamic_modes.count = modes;
    rs.damping_ratio = 0.02;
    auto reduced = reduction::reduce(mesh, rs);
    if (!reduced) return;
    data = std::move(*reduced);
    ok = true;
  }
};

struct HingedEffects {
  bool gravity = true, quadratic_velocity = true, damping = true;
  bool bounded_kernels = false;
};

struct Hinged {
  Model<double> model;
  BodyId beam;
};

std::optional<Hinged> make_hinged(const HingedBeam& beam, int modes, HingedEffects e = {}) {
  if (!beam.ok) return std::nullopt;
  ModelBuilder<double> b;
  Hinged h;
  if (e.bounded_kernels) b.use_bounded_kernels();
  h.beam = b.add_flexible_body("beam", beam.data, modes);
  if (!e.damping) b.set_damping_ratio(h.beam, 0.0);
  b.add_joint("hinge", JointKind::revolute, b.add_marker("pivot", b.ground(), -1),
              b.add_marker("root", h.beam, beam.hinge));
  if (e.gravity) b.set_gravity(Vector3d(0, -9.81, 0));
  if (!e.quadratic_velocity) b.approximate_without_quadratic_velocity();
  auto model = b.finalize();
  if (!model) return std::nullopt;
  h.model = std::move(*model);
  return h;
}

void newton_counters(benchmark::State& bench, const Data<double>& d) {
  bench.counters["newton_its"] =
      static_cast<double>(d.statistics.iterations) / static_cast<double>(d.statistics.steps);
}

void hinged_run(benchmark::State& bench, bool bounded_kernels) {
  const int modes = static_cast<int>(bench.range(0));
  const HingedBeam beam(modes);
  HingedEffects e;
  e.bounded_kernels = bounded_kernels;
  auto h = make_hinged(beam, modes, e);
  if (!h) return bench.SkipWithError("hinged beam setup failed");
  Data<double> d(h->model);
  if (!initialize(h->model, d)) return bench.SkipWithError("initialize failed");
  bench_support::time_steps(
      bench, [&] { return step(h->model, d); }, kSteps);
  newton_counters(bench, d);
  bench.counters["nv"] = h->model.num_velocities();
  bench.counters["fixed_kernel"] = h->model.body(h->beam).kernels->fixed_modes == modes ? 1 : 0;
}

void hinged_implicit(benchmark::State& bench) {
  hinged_run(bench, false);
}
void hinged_bounded(benchmark::State& bench) {
  hinged_run(bench, true);
}

void hinged_effects(benchmark::State& bench) {
  HingedEffects e;
  e.gravity = bench.range(0) != 0;
  e.quadratic_velocity = bench.range(1) != 0;
  e.damping = bench.range(2) != 0;
  const HingedBeam beam(10);
  auto h = make_hinged(beam, 10, e);
  if (!h) return bench.SkipWithError("hinged beam setup failed");
  Data<double> d(h->model);
  set_body_velocity(h->model, d, h->beam, Vector3d::Zero(), Vector3d(0, 0, 2.0));
  if (!initialize(h->model, d)) return bench.SkipWithError("initialize failed");
  bench_support::time_steps(
      bench, [&] { return step(h->model, d); }, kSteps);
  newton_counters(bench, d);
}

void hinged_rk4(benchmark::State& bench) {
  const int modes = static_cast<int>(bench.range(0));
  const HingedBeam beam(modes);
  auto h = make_hinged(beam, modes);
  if (!h) return bench.SkipWithError("hinged beam setup failed");
  ExplicitSettings<double> es;
  es.step = 2.0 / stability_number(h->model, 1.0);  // h w_max = 2
  Data<double> d(h->model);
  bench_support::time_steps(
      bench, [&] { return explicit_step(h->model, d, es); }, kSteps);
  bench.counters["h_us"] = es.step * 1e6;
}

}  // namespace

#define FLEXSTRESS_ONCE(b) b->Iterations(1)->Unit(benchmark::kMillisecond)
FLEXSTRESS_ONCE(BENCHMARK(hinged_implicit)
                    ->ArgName("modes")
                    ->Arg(1)
                    ->Arg(2)
                    ->Arg(4)
                    ->Arg(10)
                    ->Arg(16)
                    ->Arg(24)
                    ->Arg(40));
FLEXSTRESS_ONCE(BENCHMARK(hinged_bounded)->ArgName("modes")->Arg(10)->Arg(16));
// Effects switched on in turn: none, gravity, + quadratic velocity, + modal damping.
FLEXSTRESS_ONCE(BENCHMARK(hinged_effects)
                    ->ArgNames({"gravity", "quadratic_velocity", "damping"})
                    ->Args({0, 0, 0})
                    ->Args({1, 0, 0})
                    ->Args({1, 1, 0})
                    ->Args({1, 1, 1}));
FLEXSTRESS_ONCE(BENCHMARK(hinged_rk4)->ArgName("modes")->Arg(4)->Arg(10));

BENCHMARK_MAIN();
