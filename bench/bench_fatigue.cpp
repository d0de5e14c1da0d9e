// Fatigue layer benchmarks: cost per sample of the streaming rainflow + damage meter (mean and
// per-step latency percentiles, and the worst step the class-bin rule allows), and batch
// counting throughput on a 1e7-sample history.
//
// The history imitates the hot-spot stress of a crane boom sampled at 1 kHz (fixed seed): a
// 20 s lift/lower work cycle (mean 40 MPa, amplitude 80 MPa), the first two flexible modes
// (1.3 Hz and 7.9 Hz) excited by filtered noise, and measurement-like noise. Every run uses the
// same history, so figures are comparable between runs and machines.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include <flexstress/fatigue/damage.hpp>
#include <flexstress/fatigue/rainflow.hpp>
#include <flexstress/fatigue/streaming_damage.hpp>
#include <flexstress/fatigue/streaming_rainflow.hpp>

namespace {

using namespace flexstress;
using namespace flexstress::fatigue;

constexpr std::size_t kBatchSamples = 10'000'000;
constexpr double kWindow = 300.0;  // class window [-300, 300] MPa

/// The crane-like stress history described in the file comment, n samples at 1 kHz.
template <class Scalar>
const std::vector<Scalar>& history(std::size_t n) {
  static std::vector<Scalar> x;
  if (x.size() == n) return x;
  x.resize(n);
  std::mt19937 rng(20240915);
  std::normal_distribution<double> noise(0.0, 1.0);
  const double dt = 1e-3, pi = 3.14159265358979323846;
  // Two lightly damped modes driven by white noise (semi-implicit Euler on x'' + 2 z w x' +
  // w^2 x = f), giving narrow-band random vibration at 1.3 Hz and 7.9 Hz.
  double q1 = 0, v1 = 0, q2 = 0, v2 = 0;
  const double w1 = 2 * pi * 1.3, w2 = 2 * pi * 7.9, z = 0.02;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = double(i) * dt;
    v1 += dt * (-2 * z * w1 * v1 - w1 * w1 * q1 + 900.0 * noise(rng));
    q1 += dt * v1;
    v2 += dt * (-2 * z * w2 * v2 - w2 * w2 * q2 + 2500.0 * noise(rng));
    q2 += dt * v2;
    const double work = 40.0 + 80.0 * std::sin(2 * pi * t / 20.0);
    const double s = work + 4.0 * q1 + 1.5 * q2 + 1.5 * noise(rng);
    x[i] = Scalar(std::clamp(s, -kWindow, kWindow));
  }
  return x;
}

template <class Scalar>
DamageModel<Scalar> model() {
  auto curve = iiw_normal_curve(Scalar(90), IiwBeyondKnee::haibach);
  auto m = DamageModel<Scalar>::create(*curve);
  return *m;
}

template <class Scalar, int N>
StreamingDamage<Scalar, N> meter(int gate_classes = 1) {
  auto grid = ClassGrid<Scalar>::create(Scalar(-kWindow), Scalar(kWindow), N);
  auto m = StreamingDamage<Scalar, N>::create(*grid, gate_classes, model<Scalar>());
  return *m;
}

/// Mean cost per sample of the streaming meter (rainflow + Miner), over a 1e6-sample stretch,
/// with a gate of Gate classes. Reported: ns per sample, and the reversals and closed cycles per
/// 1000 samples (what the cost depends on: the gate sets how much noise becomes reversals).
template <class Scalar, int N, int Gate>
void BM_StreamingDamage(benchmark::State& state) {
  const std::vector<Scalar>& x = history<Scalar>(1'000'000);
  auto m = meter<Scalar, N>(Gate);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(m.push(x[i]));
    if (++i == x.size()) i = 0;
  }
  benchmark::DoNotOptimize(m.closed_damage());
  state.SetItemsProcessed(state.iterations());
  state.counters["ns_per_sample"] = benchmark::Counter(
      double(state.iterations()) * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["cycles_per_1000"] =
      1000.0 * double(m.counter().closed_cycles()) / double(m.counter().samples());
  state.counters["residue"] = double(m.counter().residue_size());
}
BENCHMARK_TEMPLATE(BM_StreamingDamage, float, 64, 1);
BENCHMARK_TEMPLATE(BM_StreamingDamage, double, 64, 1);
BENCHMARK_TEMPLATE(BM_StreamingDamage, float, 256, 1);
BENCHMARK_TEMPLATE(BM_StreamingDamage, double, 256, 1);
BENCHMARK_TEMPLATE(BM_StreamingDamage, double, 256, 4);  // same gate in MPa as <64, 1>

/// The counter alone (no damage), to show what the Miner sum costs.
template <class Scalar, int N>
void BM_StreamingRainflowOnly(benchmark::State& state) {
  const std::vector<Scalar>& x = history<Scalar>(1'000'000);
  auto grid = ClassGrid<Scalar>::create(Scalar(-kWindow), Scalar(kWindow), N);
  auto counter = *StreamingRainflow<Scalar, N>::create(*grid, 1);
  std::size_t i = 0, cycles = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(counter.push(x[i], [&cycles](const Cycle<Scalar>&) { ++cycles; }));
    if (++i == x.size()) i = 0;
  }
  benchmark::DoNotOptimize(cycles);
  state.SetItemsProcessed(state.iterations());
  state.counters["ns_per_sample"] = benchmark::Counter(
      double(state.iterations()) * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK_TEMPLATE(BM_StreamingRainflowOnly, double, 64);

/// Per-step latency of the meter over 1e6 samples: median, 99.9th percentile and maximum of
/// single push() calls (each timed with steady_clock; the clock's own cost, reported as
/// clock_ns, is included in every figure).
template <class Scalar, int N>
void BM_StreamingDamageLatency(benchmark::State& state) {
  using Clock = std::chrono::steady_clock;
  const std::vector<Scalar>& x = history<Scalar>(1'000'000);
  std::vector<double> ns(x.size());
  double clock_ns = 0;
  for (auto _ : state) {
    auto m = meter<Scalar, N>();
    for (std::size_t i = 0; i < x.size(); ++i) {
      const auto t0 = Clock::now();
      benchmark::DoNotOptimize(m.push(x[i]));
      const auto t1 = Clock::now();
      ns[i] = std::chrono::duration<double, std::nano>(t1 - t0).count();
    }
    const auto c0 = Clock::now();
    for (int k = 0; k < 1000; ++k) benchmark::DoNotOptimize(Clock::now());
    clock_ns = std::chrono::duration<double, std::nano>(Clock::now() - c0).count() / 1000;
  }
  std::sort(ns.begin(), ns.end());
  state.counters["p50_ns"] = ns[ns.size() / 2];
  state.counters["p999_ns"] = ns[ns.size() * 999 / 1000];
  state.counters["max_ns"] = ns.back();
  state.counters["clock_ns"] = clock_ns;
}
BENCHMARK_TEMPLATE(BM_StreamingDamageLatency, double, 64)
    ->Iterations(3)
    ->Unit(benchmark::kMillisecond);

/// Worst step the class-bin rule allows: the residue holds 2N - 1 reversals (an oscillation that
/// grows to the full window and decays again), and one sample beyond them closes every loop.
template <class Scalar, int N>
void BM_StreamingDamageWorstStep(benchmark::State& state) {
  using Clock = std::chrono::steady_clock;
  auto prepared = meter<Scalar, N>();
  const Scalar w = Scalar(2 * kWindow / N);
  auto level = [w](int k) { return Scalar(-kWindow) + (Scalar(k) + Scalar(0.5)) * w; };
  // Ranges must exceed the 1-class gate, so the oscillation starts 3 classes wide.
  for (int a = 1; a < N / 2; ++a) {  // growing: classes N/2-1-a and N/2+a
    benchmark::DoNotOptimize(prepared.push(level(N / 2 - 1 - a)));
    benchmark::DoNotOptimize(prepared.push(level(N / 2 + a)));
  }
  for (int a = N / 2 - 2; a >= 1; --a) {  // decaying
    benchmark::DoNotOptimize(prepared.push(level(N / 2 - 1 - a)));
    benchmark::DoNotOptimize(prepared.push(level(N / 2 + a)));
  }
  const int residue = prepared.counter().residue_size();
  // Falling to the bottom class (with the gate of 1 class) closes all nested loops at once.
  const Scalar closing = level(0);
  for (auto _ : state) {
    auto m = prepared;  // copy outside the timed region
    const auto t0 = Clock::now();
    benchmark::DoNotOptimize(m.push(closing));
    benchmark::DoNotOptimize(m.push(level(N - 1)));
    const auto t1 = Clock::now();
    state.SetIterationTime(std::chrono::duration<double>(t1 - t0).count());
    benchmark::DoNotOptimize(m.closed_damage());
  }
  state.counters["residue_before"] = residue;
}
BENCHMARK_TEMPLATE(BM_StreamingDamageWorstStep, double, 64)
    ->UseManualTime()
    ->Unit(benchmark::kNanosecond);
BENCHMARK_TEMPLATE(BM_StreamingDamageWorstStep, double, 256)
    ->UseManualTime()
    ->Unit(benchmark::kNanosecond);

/// Batch ASTM E1049-85 counting (reversals + three-point rainflow) of a 1e7-sample history.
template <class Scalar>
void BM_BatchCount(benchmark::State& state) {
  const std::vector<Scalar>& x = history<Scalar>(kBatchSamples);
  std::size_t cycles = 0;
  for (auto _ : state) {
    auto c = count_cycles(x);
    cycles = c->size();
    benchmark::DoNotOptimize(c->data());
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(x.size()));
  state.counters["cycles"] = double(cycles);
}
BENCHMARK_TEMPLATE(BM_BatchCount, double)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_BatchCount, float)->Unit(benchmark::kMillisecond);

/// Batch class-bin counting (the streaming counter's twin) of the same history.
template <class Scalar>
void BM_BatchCountClassed(benchmark::State& state) {
  const std::vector<Scalar>& x = history<Scalar>(kBatchSamples);
  auto grid = ClassGrid<Scalar>::create(Scalar(-kWindow), Scalar(kWindow), 64);
  for (auto _ : state) {
    auto c = count_cycles_classed(x, *grid, 1);
    benchmark::DoNotOptimize(c->data());
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(x.size()));
}
BENCHMARK_TEMPLATE(BM_BatchCountClassed, double)->Unit(benchmark::kMillisecond);

/// Batch damage per work cycle: repeating-history count + Miner sum of the 1e7 samples.
template <class Scalar>
void BM_BatchDamagePerWorkCycle(benchmark::State& state) {
  const std::vector<Scalar>& x = history<Scalar>(kBatchSamples);
  const auto m = model<Scalar>();
  for (auto _ : state) {
    auto d = damage_per_work_cycle(x, m);
    benchmark::DoNotOptimize(*d);
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(x.size()));
}
BENCHMARK_TEMPLATE(BM_BatchDamagePerWorkCycle, double)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
