// Per-step cost of the dynamics (Google Benchmark; build Release). Each benchmark times every one
// of its steps and reports the median and the worst (counters median_us, worst_us), plus the
// Newton iterations per step; the benchmark's own time is the whole run.
//   hinged_implicit<N, L>   a 2 m steel beam (RHS 40x20x2, 24 elements) with N Craig-Bampton
//                           modes on a revolute joint, swinging under gravity from horizontal,
//                           1e5 steps at h = 1 ms; L = 64: fixed-size storage, 0: dynamic
//   hinged_effects<E>       the same with N = 10 and only the effects E (spinning at 2 rad/s so
//                           every variant moves): the cost of each effect
//   hinged_rk4<N>           explicit RK4 at its stable step (h w_max = 2), 1e5 steps
// The crane's rows are in bench_crane.cpp.
//
// Every template argument list instantiates a scene and its integrator (about a minute of
// compile time each), so the sweep is sparse and CI does not build this program
// (FLEXSTRESS_BENCH_DYNAMICS=OFF there). Results: docs/performance.md.
//
// Run: ./build/bench/bench_dynamics --benchmark_counters_tabular=true
#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <vector>

#include <benchmark/benchmark.h>

#include <flexstress/dynamics/explicit_integrator.hpp>
#include <flexstress/dynamics/implicit_integrator.hpp>
#include <flexstress/fe/beam_line.hpp>
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

template <int N, class Eff = Effects<Gravity, QuadraticVelocity, ModalDamping>, int L = 64>
using Hinged = Scene<double, Bodies<FFRFBody<N>>, Joints<Revolute<ground, 0>>, Eff, ForceElements<>,
                     FixedGround<double>, L>;

template <class SceneT>
std::optional<SceneT> make_hinged(const HingedBeam& beam) {
  if (!beam.ok) return std::nullopt;
  auto body = SceneT::template BodyType<0>::from_modal_data(beam.data);
  if (!body) return std::nullopt;
  SceneT scene;
  scene.template body<0>() = *body;
  scene.template joint<0>().marker_i = fixed_marker<double>(Vector3d::Zero());
  scene.template joint<0>().marker_j =
      make_marker(scene.template body<0>(), beam.hinge, Vector3d::Zero());
  return scene;
}

template <int N, int L>
void hinged_implicit(benchmark::State& bench) {
  using S = Hinged<N, Effects<Gravity, QuadraticVelocity, ModalDamping>, L>;
  const HingedBeam beam(N);
  auto scene = make_hinged<S>(beam);
  if (!scene) return bench.SkipWithError("hinged beam setup failed");
  ImplicitIntegrator<S> integ(*scene);
  typename S::State s;
  if (!integ.initialize(s)) return bench.SkipWithError("initialize failed");
  bench_support::time_steps(bench, integ, s, kSteps);
  bench.counters["newton_its"] = static_cast<double>(integ.statistics().iterations) /
                                 static_cast<double>(integ.statistics().steps);
  bench.counters["nv"] = S::nv;
}

template <class Eff>
void hinged_effects(benchmark::State& bench) {
  using S = Hinged<10, Eff>;
  const HingedBeam beam(10);
  auto scene = make_hinged<S>(beam);
  if (!scene) return bench.SkipWithError("hinged beam setup failed");
  ImplicitIntegrator<S> integ(*scene);
  typename S::State s;
  s.v(5) = 2.0;
  if (!integ.initialize(s)) return bench.SkipWithError("initialize failed");
  bench_support::time_steps(bench, integ, s, kSteps);
  bench.counters["newton_its"] = static_cast<double>(integ.statistics().iterations) /
                                 static_cast<double>(integ.statistics().steps);
}

template <int N>
void hinged_rk4(benchmark::State& bench) {
  using S = Hinged<N>;
  const HingedBeam beam(N);
  auto scene = make_hinged<S>(beam);
  if (!scene) return bench.SkipWithError("hinged beam setup failed");
  typename ExplicitIntegrator<S>::Settings es;
  es.step = 2.0 / scene->max_modal_frequency();
  ExplicitIntegrator<S> integ(*scene, es);
  typename S::State s;
  bench_support::time_steps(bench, integ, s, kSteps);
  bench.counters["h_us"] = es.step * 1e6;
}

}  // namespace

#define FLEXSTRESS_ONCE(b) b->Iterations(1)->Unit(benchmark::kMillisecond)
FLEXSTRESS_ONCE(BENCHMARK_TEMPLATE(hinged_implicit, 1, 64));
FLEXSTRESS_ONCE(BENCHMARK_TEMPLATE(hinged_implicit, 2, 64));
FLEXSTRESS_ONCE(BENCHMARK_TEMPLATE(hinged_implicit, 4, 64));
FLEXSTRESS_ONCE(BENCHMARK_TEMPLATE(hinged_implicit, 10, 64));
FLEXSTRESS_ONCE(BENCHMARK_TEMPLATE(hinged_implicit, 16, 64));
FLEXSTRESS_ONCE(BENCHMARK_TEMPLATE(hinged_implicit, 24, 64));
FLEXSTRESS_ONCE(BENCHMARK_TEMPLATE(hinged_implicit, 40, 64));
FLEXSTRESS_ONCE(BENCHMARK_TEMPLATE(hinged_implicit, 10, 0));
FLEXSTRESS_ONCE(BENCHMARK_TEMPLATE(hinged_implicit, 40, 0));
FLEXSTRESS_ONCE(BENCHMARK_TEMPLATE(hinged_effects, Effects<>));
FLEXSTRESS_ONCE(BENCHMARK_TEMPLATE(hinged_effects, Effects<Gravity>));
FLEXSTRESS_ONCE(BENCHMARK_TEMPLATE(hinged_effects, Effects<Gravity, QuadraticVelocity>));
FLEXSTRESS_ONCE(BENCHMARK_TEMPLATE(hinged_effects,
                                   Effects<Gravity, QuadraticVelocity, ModalDamping>));
FLEXSTRESS_ONCE(BENCHMARK_TEMPLATE(hinged_rk4, 4));
FLEXSTRESS_ONCE(BENCHMARK_TEMPLATE(hinged_rk4, 10));

BENCHMARK_MAIN();
