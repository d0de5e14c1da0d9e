// Per-step cost of the dynamics (Google Benchmark; build Release). Each benchmark times every one
// of its steps and reports the median and the worst (counters median_us, worst_us), plus the
// Newton iterations per step; the benchmark's own time is the whole run.
//   hinged_implicit<N, L>   a 2 m steel beam (RHS 40x20x2, 24 elements) with N Craig-Bampton
//                           modes on a revolute joint, swinging under gravity from horizontal,
//                           1e5 steps at h = 1 ms; L = 64: fixed-size storage, 0: dynamic
//   hinged_effects<E>       the same with N = 10 and only the effects E (spinning at 2 rad/s so
//                           every variant moves): the cost of each effect
//   hinged_rk4<N>           explicit RK4 at its stable step (h w_max = 2), 1e5 steps
//   crane_cycle<L, E>       the crane (examples/crane: 10 boom modes, 5 joints, 18 equations)
//                           over its 11 s synthetic work cycle, h = 1 ms, Newton tolerance
//                           10^-E m/s^2 (E = 5 by default); also reports factorizations/step
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

#include "../examples/crane/crane_model.hpp"

using namespace flexstress;

namespace {

using Clock = std::chrono::steady_clock;
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

// Times `steps` calls of step(s) one by one; reports median, worst and mean (us).
template <class Integrator, class StateT>
void time_steps(benchmark::State& bench, Integrator& integ, StateT& s, int steps) {
  std::vector<double> us;
  us.reserve(static_cast<std::size_t>(steps));
  for (auto _ : bench) {
    for (int i = 0; i < steps; ++i) {
      const auto a = Clock::now();
      const StepStatus st = integ.step(s);
      const auto b = Clock::now();
      if (st != StepStatus::ok) {
        bench.SkipWithError(to_string(st));
        return;
      }
      us.push_back(std::chrono::duration<double, std::micro>(b - a).count());
    }
  }
  double mean = 0;
  for (double u : us) mean += u;
  mean /= static_cast<double>(us.size());
  const auto mid = us.begin() + static_cast<std::ptrdiff_t>(us.size() / 2);
  std::nth_element(us.begin(), mid, us.end());
  bench.counters["median_us"] = *mid;
  bench.counters["worst_us"] = *std::max_element(us.begin(), us.end());
  bench.counters["mean_us"] = mean;
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
  time_steps(bench, integ, s, kSteps);
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
  time_steps(bench, integ, s, kSteps);
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
  time_steps(bench, integ, s, kSteps);
  bench.counters["h_us"] = es.step * 1e6;
}

// ToleranceExponent E: Newton tolerance 10^-E m/s^2 (5: the default; 3: the accuracy study's
// pick, which gives the same stress history, docs/accuracy-vs-time.md).
template <int L, int ToleranceExponent = 5>
void crane_cycle(benchmark::State& bench) {
  std::vector<double> t, ds;
  crane::synthetic_cycle(t, ds);
  auto made = crane::make_crane<10, L>(crane::CraneSpec{}, t, ds);
  if (!made) return bench.SkipWithError(made.error().what().c_str());
  using S = crane::CraneScene<10, L>;
  typename ImplicitIntegrator<S>::Settings settings;
  settings.acceleration_tolerance = std::pow(10.0, -ToleranceExponent);
  ImplicitIntegrator<S> integ(made->scene, settings);
  auto s = made->initial;
  if (!integ.initialize(s)) return bench.SkipWithError("initialize failed");
  time_steps(bench, integ, s, 11000);
  const auto steps = static_cast<double>(integ.statistics().steps);
  bench.counters["newton_its"] = static_cast<double>(integ.statistics().iterations) / steps;
  bench.counters["factorizations"] = static_cast<double>(integ.statistics().factorizations) / steps;
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
FLEXSTRESS_ONCE(BENCHMARK_TEMPLATE(crane_cycle, 64));
FLEXSTRESS_ONCE(BENCHMARK_TEMPLATE(crane_cycle, 0));
FLEXSTRESS_ONCE(BENCHMARK_TEMPLATE(crane_cycle, 64, 3));

BENCHMARK_MAIN();
