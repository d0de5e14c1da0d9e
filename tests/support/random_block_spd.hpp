// A random symmetric positive definite matrix with a given block pattern (the envelope
// Cholesky's tests and benchmark): dense diagonal blocks, random coupling blocks, every other
// entry exactly zero, made positive definite by a dominant diagonal.
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Core>
#include <flexstress/core/envelope_cholesky.hpp>

namespace flexstress::testing {

/// Diagonal entries exceed their row's absolute sum (Gershgorin: positive definite) by
/// 10^((r mod 7) - 3) with spread, else by 1: spread scales the rows over six decades, as the
/// crane's inertias are (1087 kg m^2 down to 3e-4).
inline Eigen::MatrixXd random_block_spd(const BlockPattern& pattern, unsigned seed,
                                        bool spread = true) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<int> start(pattern.block_sizes.size() + 1, 0);
  for (std::size_t b = 0; b < pattern.block_sizes.size(); ++b)
    start[b + 1] = start[b] + pattern.block_sizes[b];
  const int n = start.back();
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  const auto fill = [&](int bi, int bj) {
    const auto i = static_cast<std::size_t>(bi), j = static_cast<std::size_t>(bj);
    for (int r = start[i]; r < start[i + 1]; ++r)
      for (int c = start[j]; c < start[j + 1]; ++c) a(r, c) = u(rng);
  };
  for (int b = 0; b < static_cast<int>(pattern.block_sizes.size()); ++b) fill(b, b);
  for (const auto& [bi, bj] : pattern.couplings) fill(bi, bj);
  a = (a + a.transpose()).eval();
  for (int r = 0; r < n; ++r)
    a(r, r) = a.row(r).cwiseAbs().sum() + (spread ? std::pow(10.0, r % 7 - 3) : 1.0);
  return a;
}

}  // namespace flexstress::testing
