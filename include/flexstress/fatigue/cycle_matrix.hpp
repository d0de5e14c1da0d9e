// Cycle matrices with user bins: range-mean and from-to (ASTM E1049-85 reports counts as range
// tables; load spectra for design are usually range-mean or from-to "Markov" matrices).
//
// Bins are given by their edges e_0 < e_1 < ... < e_n (any spacing): bin i holds
// e_i <= x < e_{i+1}, the last bin also holds e_n. A cycle whose range or mean (from or to) falls
// outside the bins is not dropped silently: its count goes to unbinned(), so
// total() == counts().sum() + unbinned() always equals the sum of the counts added.
//
// The matrices are sized at setup; add() never allocates, so a matrix can be the sink of the
// streaming counter (`counter.push(x, matrix)`).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "flexstress/core/assert.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/fatigue/cycle.hpp"

namespace flexstress::fatigue {

/// Bin edges for one axis of a cycle matrix.
template <class Scalar>
class Bins {
 public:
  /// Bins from explicit edges. Errors: fewer than 2 edges, a non-finite edge, edges not
  /// strictly increasing (the message names the edge).
  static Result<Bins> from_edges(std::vector<Scalar> edges) {
    if (edges.size() < 2)
      return make_error(ErrorCode::invalid_argument, "bins need at least 2 edges, got ",
                        edges.size());
    for (std::size_t i = 0; i < edges.size(); ++i) {
      if (!std::isfinite(edges[i]))
        return make_error(ErrorCode::invalid_argument, "bin edge ", i, " is not finite");
      if (i >= 1 && !(edges[i] > edges[i - 1]))
        return make_error(ErrorCode::invalid_argument, "bin edge ", i, " (", edges[i],
                          ") must be greater than edge ", i - 1, " (", edges[i - 1], ")");
    }
    return Bins(std::move(edges));
  }

  /// `count` bins of equal width over [lower, upper]. Errors: count < 1, bad bounds.
  static Result<Bins> uniform(Scalar lower, Scalar upper, int count) {
    if (count < 1)
      return make_error(ErrorCode::invalid_argument, "number of bins must be >= 1, got ", count);
    if (!std::isfinite(lower) || !std::isfinite(upper) || !(lower < upper))
      return make_error(ErrorCode::invalid_argument, "bins need finite lower < upper, got [", lower,
                        ", ", upper, "]");
    std::vector<Scalar> edges(static_cast<std::size_t>(count) + 1);
    for (int i = 0; i <= count; ++i)
      edges[static_cast<std::size_t>(i)] = lower + (upper - lower) * Scalar(i) / Scalar(count);
    edges.back() = upper;  // exact, whatever the rounding above
    return from_edges(std::move(edges));
  }

  /// Number of bins.
  int size() const noexcept { return static_cast<int>(edges_.size()) - 1; }
  /// Edge i, 0 <= i <= size().
  Scalar edge(int i) const {
    FLEXSTRESS_ASSERT(i >= 0 && i <= size(), "Bins::edge: index out of range");
    return edges_[static_cast<std::size_t>(i)];
  }
  /// Centre of bin i.
  Scalar center(int i) const { return (edge(i) + edge(i + 1)) / Scalar(2); }

  /// Bin holding x, or -1 when x is outside [e_0, e_n] (or NaN). Binary search on the stored
  /// edges, so a value exactly on an edge always lands in the bin that starts there, whatever
  /// rounding produced the edges.
  int find(Scalar x) const {
    // The negated form also sends NaN to "outside".
    if (!(x >= edges_.front() && x <= edges_.back())) return -1;
    if (x == edges_.back()) return size() - 1;  // the last bin is closed on the right
    // First edge greater than x; the bin starts one edge before it.
    const auto it = std::upper_bound(edges_.begin(), edges_.end(), x);
    return static_cast<int>(it - edges_.begin()) - 1;
  }

 private:
  explicit Bins(std::vector<Scalar> edges) : edges_(std::move(edges)) {}
  std::vector<Scalar> edges_;
};

/// Counts per (range bin, mean bin): counts()(i, j) for range bin i and mean bin j.
template <class Scalar>
class RangeMeanMatrix {
 public:
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  static RangeMeanMatrix create(Bins<Scalar> range_bins, Bins<Scalar> mean_bins) {
    return RangeMeanMatrix(std::move(range_bins), std::move(mean_bins));
  }

  /// Adds a cycle (its count) to its cell, or to unbinned(). Never allocates.
  void add(const Cycle<Scalar>& c) {
    // Row from the range, column from the mean; half cycles add 0.5.
    const int i = range_bins_.find(c.range());
    const int j = mean_bins_.find(c.mean());
    if (i < 0 || j < 0) {
      unbinned_ += c.count;
    } else {
      counts_(i, j) += c.count;
    }
  }
  /// Sink form of add(), for StreamingRainflow::push.
  void operator()(const Cycle<Scalar>& c) { add(c); }

  const Matrix& counts() const noexcept { return counts_; }
  /// Counts of cycles whose range or mean fell outside the bins.
  Scalar unbinned() const noexcept { return unbinned_; }
  /// All counts added (binned and unbinned).
  Scalar total() const { return counts_.sum() + unbinned_; }
  const Bins<Scalar>& range_bins() const noexcept { return range_bins_; }
  const Bins<Scalar>& mean_bins() const noexcept { return mean_bins_; }

 private:
  // The count matrix is allocated here, once; add() only writes into it.
  RangeMeanMatrix(Bins<Scalar> range_bins, Bins<Scalar> mean_bins)
      : range_bins_(std::move(range_bins)),
        mean_bins_(std::move(mean_bins)),
        counts_(Matrix::Zero(range_bins_.size(), mean_bins_.size())) {}

  Bins<Scalar> range_bins_;
  Bins<Scalar> mean_bins_;
  Matrix counts_;
  Scalar unbinned_ = Scalar(0);
};

/// Counts per (from bin, to bin): counts()(i, j) for cycles going from bin i to bin j. A
/// rising cycle lies above the diagonal (i < j), a falling one below it.
template <class Scalar>
class FromToMatrix {
 public:
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  static FromToMatrix create(Bins<Scalar> bins) { return FromToMatrix(std::move(bins)); }

  /// Adds a cycle (its count) to its cell, or to unbinned(). Never allocates.
  void add(const Cycle<Scalar>& c) {
    // Row from the first reversal, column from the second: the direction is kept.
    const int i = bins_.find(c.from);
    const int j = bins_.find(c.to);
    if (i < 0 || j < 0) {
      unbinned_ += c.count;
    } else {
      counts_(i, j) += c.count;
    }
  }
  /// Sink form of add(), for StreamingRainflow::push.
  void operator()(const Cycle<Scalar>& c) { add(c); }

  const Matrix& counts() const noexcept { return counts_; }
  Scalar unbinned() const noexcept { return unbinned_; }
  Scalar total() const { return counts_.sum() + unbinned_; }
  const Bins<Scalar>& bins() const noexcept { return bins_; }

 private:
  explicit FromToMatrix(Bins<Scalar> bins)
      : bins_(std::move(bins)), counts_(Matrix::Zero(bins_.size(), bins_.size())) {}

  Bins<Scalar> bins_;
  Matrix counts_;
  Scalar unbinned_ = Scalar(0);
};

/// Range-mean matrix of a cycle list.
template <class Scalar>
RangeMeanMatrix<Scalar> range_mean_matrix(const std::vector<Cycle<Scalar>>& cycles,
                                          const Bins<Scalar>& range_bins,
                                          const Bins<Scalar>& mean_bins) {
  RangeMeanMatrix<Scalar> m = RangeMeanMatrix<Scalar>::create(range_bins, mean_bins);
  for (const Cycle<Scalar>& c : cycles) m.add(c);
  return m;
}

/// From-to matrix of a cycle list.
template <class Scalar>
FromToMatrix<Scalar> from_to_matrix(const std::vector<Cycle<Scalar>>& cycles,
                                    const Bins<Scalar>& bins) {
  FromToMatrix<Scalar> m = FromToMatrix<Scalar>::create(bins);
  for (const Cycle<Scalar>& c : cycles) m.add(c);
  return m;
}

}  // namespace flexstress::fatigue
