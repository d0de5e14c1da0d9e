// Shared helpers of the fatigue tests: reproducible random histories and cycle comparisons.
//
// Random histories use std::mt19937 (its output sequence is fixed by the standard) and integer
// arithmetic only, so every platform draws the same histories. Integer-valued stresses are
// exact in float and double, which lets conservation and shift properties be checked with
// exact equality, and they produce many ties (equal values, equal ranges) - the hard cases for
// rainflow counters.
#pragma once

#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include <doctest/doctest.h>

#include <flexstress/fatigue/cycle.hpp>

namespace flexstress::fatigue::test {

/// n integer-valued samples uniformly in [lo, hi].
template <class Scalar>
std::vector<Scalar> random_integer_history(std::mt19937& rng, std::size_t n, int lo, int hi) {
  std::vector<Scalar> x(n);
  const std::uint32_t span = static_cast<std::uint32_t>(hi - lo + 1);
  for (std::size_t i = 0; i < n; ++i) x[i] = Scalar(lo + static_cast<int>(rng() % span));
  return x;
}

/// A random walk with mean reversion, integer-valued, clamped to [lo, hi]: a smoother, more
/// stress-like history than white noise (long residues, nested cycles).
template <class Scalar>
std::vector<Scalar> random_walk_history(std::mt19937& rng, std::size_t n, int lo, int hi,
                                        int max_step) {
  std::vector<Scalar> x(n);
  int v = (lo + hi) / 2;
  const std::uint32_t span = static_cast<std::uint32_t>(2 * max_step + 1);
  for (std::size_t i = 0; i < n; ++i) {
    v += static_cast<int>(rng() % span) - max_step;
    v -= (v - (lo + hi) / 2) / 8;  // pull back towards the middle
    v = v < lo ? lo : (v > hi ? hi : v);
    x[i] = Scalar(v);
  }
  return x;
}

/// Sum |r[i+1] - r[i]| of a reversal sequence (open), or of the closed loop r[0..n) -> r[0].
template <class Scalar>
Scalar path_length(const std::vector<Scalar>& r, bool closed) {
  Scalar s(0);
  for (std::size_t i = 0; i + 1 < r.size(); ++i)
    s += r[i + 1] > r[i] ? r[i + 1] - r[i] : r[i] - r[i + 1];
  if (closed && r.size() >= 2)
    s += r.back() > r.front() ? r.back() - r.front() : r.front() - r.back();
  return s;
}

/// Checks that two cycle lists have the same (range, mean, count) rows, exactly.
template <class Scalar>
void check_same_rows(const std::vector<Cycle<Scalar>>& a, const std::vector<Cycle<Scalar>>& b) {
  const auto ra = aggregate_cycles(a);
  const auto rb = aggregate_cycles(b);
  REQUIRE(ra.size() == rb.size());
  for (std::size_t i = 0; i < ra.size(); ++i) {
    CHECK(ra[i].range == rb[i].range);
    CHECK(ra[i].mean == rb[i].mean);
    CHECK(ra[i].count == rb[i].count);
  }
}

/// Tight relative tolerance for sums of the same positive terms added in a different order
/// (compensated sums): a few units in the last place of the Scalar.
template <class Scalar>
constexpr double sum_order_tolerance() {
  return sizeof(Scalar) == sizeof(float) ? 1e-6 : 1e-14;
}

}  // namespace flexstress::fatigue::test
