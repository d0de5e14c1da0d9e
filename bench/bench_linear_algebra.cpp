// The implicit integrator's linear algebra: factorization and solve of its iteration matrix with
// Eigen's dense LLT and with EnvelopeCholesky (core/envelope_cholesky.hpp), on
//   crane   the crane's 28 x 28 pattern (boom 16, cylinder 6, rod 6; the boom and the cylinder
//           joined only through the rod), fixed size
//   chain   40 bodies of 6 velocities in a chain (240 x 240, dynamic size), like IFToMM A02
// The matrices are random, symmetric positive definite, with exactly the pattern's zeros.
// Results: docs/performance.md.
//
// Run: ./build/bench/bench_linear_algebra
#include <benchmark/benchmark.h>
#include <Eigen/Cholesky>

#include <flexstress/core/envelope_cholesky.hpp>

#include "../tests/support/random_block_spd.hpp"

using namespace flexstress;

namespace {

BlockPattern crane_pattern() {
  return {{16, 6, 6}, {{0, 2}, {1, 2}}};
}

BlockPattern chain_pattern() {
  BlockPattern p;
  p.block_sizes.assign(40, 6);
  for (int k = 0; k + 1 < 40; ++k) p.couplings.emplace_back(k, k + 1);
  return p;
}

template <class Matrix>
Matrix random_spd(const BlockPattern& pattern) {
  return testing::random_block_spd(pattern, 42, /*spread=*/false);
}

template <int N>
BlockPattern pattern_of() {
  return N == Eigen::Dynamic ? chain_pattern() : crane_pattern();
}

template <int N>
void eigen_llt_factorize(benchmark::State& state) {
  using Matrix = Eigen::Matrix<double, N, N>;
  const Matrix a = random_spd<Matrix>(pattern_of<N>());
  Eigen::LLT<Matrix> llt(a);
  for (auto _ : state) {
    llt.compute(a);
    benchmark::DoNotOptimize(llt.matrixLLT().data());
  }
}

template <int N>
void eigen_llt_solve(benchmark::State& state) {
  using Matrix = Eigen::Matrix<double, N, N>;
  using Vector = Eigen::Matrix<double, N, 1>;
  const Matrix a = random_spd<Matrix>(pattern_of<N>());
  const Eigen::LLT<Matrix> llt(a);
  const Vector b = Vector::Ones(a.rows());
  Vector x = b;
  for (auto _ : state) {
    x = b;
    llt.solveInPlace(x);
    benchmark::DoNotOptimize(x.data());
  }
}

/// Analyzed: the scene's pattern; else the dense kernels (one block).
template <int N, bool Analyzed>
void envelope_factorize(benchmark::State& state) {
  using Matrix = Eigen::Matrix<double, N, N>;
  const Matrix a = random_spd<Matrix>(pattern_of<N>());
  EnvelopeCholesky<double, N> chol;
  if (Analyzed) chol.analyze(pattern_of<N>());
  chol.compute(a);
  for (auto _ : state) {
    benchmark::DoNotOptimize(chol.compute(a));
    benchmark::ClobberMemory();
  }
  state.counters["multiply_adds"] = chol.factorization_work();
}

template <int N, bool Analyzed>
void envelope_solve(benchmark::State& state) {
  using Matrix = Eigen::Matrix<double, N, N>;
  using Vector = Eigen::Matrix<double, N, 1>;
  const Matrix a = random_spd<Matrix>(pattern_of<N>());
  EnvelopeCholesky<double, N> chol;
  if (Analyzed) chol.analyze(pattern_of<N>());
  chol.compute(a);
  const Vector b = Vector::Ones(a.rows());
  Vector x = b;
  for (auto _ : state) {
    x = b;
    chol.solve_in_place(x);
    benchmark::DoNotOptimize(x.data());
  }
}

}  // namespace

BENCHMARK_TEMPLATE(eigen_llt_factorize, 28);
BENCHMARK_TEMPLATE(envelope_factorize, 28, false);
BENCHMARK_TEMPLATE(envelope_factorize, 28, true);
BENCHMARK_TEMPLATE(eigen_llt_solve, 28);
BENCHMARK_TEMPLATE(envelope_solve, 28, false);
BENCHMARK_TEMPLATE(envelope_solve, 28, true);
BENCHMARK_TEMPLATE(eigen_llt_factorize, Eigen::Dynamic);
BENCHMARK_TEMPLATE(envelope_factorize, Eigen::Dynamic, false);
BENCHMARK_TEMPLATE(envelope_factorize, Eigen::Dynamic, true);
BENCHMARK_TEMPLATE(eigen_llt_solve, Eigen::Dynamic);
BENCHMARK_TEMPLATE(envelope_solve, Eigen::Dynamic, false);
BENCHMARK_TEMPLATE(envelope_solve, Eigen::Dynamic, true);

BENCHMARK_MAIN();
