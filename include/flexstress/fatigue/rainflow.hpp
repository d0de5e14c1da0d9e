// Batch rainflow counting per ASTM E1049-85 (reapproved 2017), "Standard Practices for Cycle
// Counting in Fatigue Analysis":
//   - section 5.4.4, the three-point rainflow algorithm for a finished history: closed cycles
//     plus half cycles (the ranges that contain the starting point, and the residue);
//   - section 5.4.5, the simplified algorithm for a repeating history: the block is rotated to
//     start at its peak or valley of greatest magnitude, so every count is a full cycle.
//
// These are the reference implementations: they keep the whole history (they allocate), and the
// streaming counter (streaming_rainflow.hpp) is tested against them.
//
// Three entry points:
//   rainflow_half_cycles / rainflow_repeating   on a reversal sequence you already have;
//   count_cycles                                on raw samples (reversals + gate + count);
//   count_cycles_classed                        on raw samples quantized to a ClassGrid, the
//                                               batch twin of the streaming class-bin counter.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdlib>  // std::abs(int)
#include <vector>

#include "flexstress/core/assert.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/fatigue/class_grid.hpp"
#include "flexstress/fatigue/cycle.hpp"
#include "flexstress/fatigue/reversals.hpp"

namespace flexstress::fatigue {

namespace detail {

/// |a - b| without overflow concerns for the value types used here (floating point, int class
/// indices).
template <class T>
T abs_diff(T a, T b) {
  return a > b ? a - b : b - a;
}

/// ASTM E1049-85 section 5.4.4, fed one reversal at a time: push() runs steps 1-5 for the new
/// point, finish() runs step 6. emit(from, to, full) receives every count. X is the most recent
/// range, Y the one before it, S the starting point (the first live point of the stack, moved
/// forward by step 5).
template <class T>
class AstmThreePoint {
 public:
  template <class Emit>
  void push(T r, Emit&& emit) {
    s_.push_back(r);  // step 1: read the next peak or valley
    // Step 2: while there are at least three points, form X and Y.
    while (s_.size() - base_ >= 3) {
      const std::size_t e = s_.size();
      const T x = abs_diff(s_[e - 1], s_[e - 2]);
      const T y = abs_diff(s_[e - 2], s_[e - 3]);
      if (x < y) break;  // step 3: X < Y, read on
      if (e - 3 == base_) {
        // Step 5: Y contains S; count Y as one half cycle, discard its first point, move S.
        emit(s_[base_], s_[base_ + 1], false);
        ++base_;
      } else {
        // Step 4: count Y as one cycle and discard its peak and valley.
        emit(s_[e - 3], s_[e - 2], true);
        s_[e - 3] = s_[e - 1];
        s_.resize(e - 2);
      }
    }
    // Drop discarded points from the front once they are the larger part (amortized O(1)).
    if (base_ >= 64 && base_ >= s_.size() / 2) {
      s_.erase(s_.begin(), s_.begin() + static_cast<std::ptrdiff_t>(base_));
      base_ = 0;
    }
  }

  template <class Emit>
  void finish(Emit&& emit) {
    // Step 6: every range not yet counted is one half cycle.
    for (std::size_t k = base_; k + 1 < s_.size(); ++k) emit(s_[k], s_[k + 1], false);
    s_.clear();
    base_ = 0;
  }

 private:
  std::vector<T> s_;  // points not yet discarded; s_[base_] is S
  std::size_t base_ = 0;
};

/// ASTM E1049-85 section 5.4.4 on reversals r[0..n).
template <class T, class Emit>
void astm_three_point(const T* r, std::size_t n, Emit&& emit) {
  AstmThreePoint<T> counter;
  for (std::size_t i = 0; i < n; ++i) counter.push(r[i], emit);
  counter.finish(emit);
}

/// ASTM E1049-85 section 5.4.5 on one block r[0..n) of a repeating history: emit(from, to,
/// true) for every cycle. The end of the block joins its start; points that stop being
/// reversals at that junction are dropped.
template <class T, class Emit>
void astm_repeating(const T* r, std::size_t n, Emit&& emit) {
  if (n < 2) return;
  // The closed loop r[0..m): a final point equal to the first is the same point.
  const std::size_t m = r[n - 1] == r[0] ? n - 1 : n;
  if (m < 2) return;
  // Rearrange to start at the peak or valley of greatest magnitude (a global extreme).
  using std::abs;
  std::size_t k = 0;
  for (std::size_t i = 1; i < m; ++i)
    if (abs(r[i]) > abs(r[k])) k = i;
  // Walk the loop from the extreme back to itself, re-extracting reversals (gate 0) so that the
  // old start and end are kept only if they are reversals of the loop.
  std::vector<T> seq;
  seq.reserve(m + 1);
  ReversalFilter<T> filter(T(0));
  auto keep = [&seq](T v) { seq.push_back(v); };
  for (std::size_t j = 0; j < m; ++j) filter.push(r[(k + j) % m], keep);
  filter.push(r[k], keep);
  filter.finish(keep);
  // Steps 1-4 of section 5.4.5: X >= Y counts Y as one cycle (no starting-point rule).
  std::vector<T> s;
  s.reserve(seq.size());
  for (const T v : seq) {
    s.push_back(v);
    while (s.size() >= 3) {
      const std::size_t e = s.size();
      if (abs_diff(s[e - 1], s[e - 2]) < abs_diff(s[e - 2], s[e - 3])) break;
      emit(s[e - 3], s[e - 2], true);
      s[e - 3] = s[e - 1];
      s.resize(e - 2);
    }
  }
  // Starting and ending at a global extreme closes every loop: only that point is left.
  FLEXSTRESS_ASSERT(s.size() <= 1, "astm_repeating: residue left after a closed loop");
}

/// Counts reversals r[0..n) with the given closure into Cycle<Scalar>, mapping each reversal
/// through value(r) (identity for stresses, class centre for class indices).
template <class Scalar, class T, class Value>
std::vector<Cycle<Scalar>> count_reversals(const T* r, std::size_t n, CycleClosure closure,
                                           Value&& value) {
  std::vector<Cycle<Scalar>> cycles;
  auto add = [&](T from, T to, bool full) {
    cycles.push_back({value(from), value(to), full ? Scalar(1) : Scalar(0.5)});
  };
  if (closure == CycleClosure::repeating) {
    astm_repeating(r, n, add);
  } else {
    astm_three_point(r, n, add);
  }
  return cycles;
}

/// Counts a history of n samples, sample(i) giving sample i as T (a stress, or a class index),
/// with reversal gate `gate` and the given closure. For half cycles the reversals go straight
/// into the three-point counter, without being stored; a repeating block needs them all.
template <class Scalar, class T, class Sample, class Value>
std::vector<Cycle<Scalar>> count_history(std::size_t n, Sample&& sample, T gate,
                                         CycleClosure closure, Value&& value) {
  std::vector<Cycle<Scalar>> cycles;
  auto add = [&](T from, T to, bool full) {
    cycles.push_back({value(from), value(to), full ? Scalar(1) : Scalar(0.5)});
  };
  ReversalFilter<T> filter(gate);
  if (closure == CycleClosure::half_cycles) {
    AstmThreePoint<T> counter;
    auto feed = [&](T r) { counter.push(r, add); };
    for (std::size_t i = 0; i < n; ++i) filter.push(sample(i), feed);
    filter.finish(feed);
    counter.finish(add);
  } else {
    std::vector<T> r;
    auto keep = [&r](T v) { r.push_back(v); };
    for (std::size_t i = 0; i < n; ++i) filter.push(sample(i), keep);
    filter.finish(keep);
    astm_repeating(r.data(), r.size(), add);
  }
  return cycles;
}

/// Checks a reversal sequence: finite values that strictly alternate in direction.
template <class Scalar>
Status check_reversals(const std::vector<Scalar>& r) {
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (!std::isfinite(r[i]))
      return make_error(ErrorCode::invalid_argument, "reversal ", i, " is ", non_finite_name(r[i]));
    if (i >= 1 && r[i] == r[i - 1])
      return make_error(ErrorCode::invalid_argument, "reversal ", i, " (", r[i],
                        ") repeats reversal ", i - 1, "; reversals must alternate");
    if (i >= 2 && (r[i] > r[i - 1]) == (r[i - 1] > r[i - 2]))
      return make_error(ErrorCode::invalid_argument, "reversal ", i - 1, " (", r[i - 1],
                        ") is not a peak or valley: the history keeps ",
                        r[i] > r[i - 1] ? "rising" : "falling", " through it");
  }
  return Status::success();
}

}  // namespace detail

/// Rainflow cycles of a finished history given as reversals (ASTM E1049-85 section 5.4.4):
/// closed cycles count 1, ranges through the starting point and the residue count 0.5.
/// Errors: a non-finite reversal, or a sequence that does not alternate (the message names the
/// point). An empty or one-point sequence has no cycles.
template <class Scalar>
Result<std::vector<Cycle<Scalar>>> rainflow_half_cycles(const std::vector<Scalar>& reversals) {
  if (Status s = detail::check_reversals(reversals); !s) return s.error();
  return detail::count_reversals<Scalar>(reversals.data(), reversals.size(),
                                         CycleClosure::half_cycles, [](Scalar v) { return v; });
}

/// Rainflow cycles of one block of a repeating history (ASTM E1049-85 section 5.4.5): every
/// count is a full cycle, nothing is left as residue. Same errors as rainflow_half_cycles.
template <class Scalar>
Result<std::vector<Cycle<Scalar>>> rainflow_repeating(const std::vector<Scalar>& reversals) {
  if (Status s = detail::check_reversals(reversals); !s) return s.error();
  return detail::count_reversals<Scalar>(reversals.data(), reversals.size(),
                                         CycleClosure::repeating, [](Scalar v) { return v; });
}

/// Options of count_cycles.
template <class Scalar>
struct CountOptions {
  Scalar gate = Scalar(0);                           ///< Hysteresis gate (stress units, >= 0).
  CycleClosure closure = CycleClosure::half_cycles;  ///< How the residue is closed.
};

/// Rainflow cycles of a stress history: reversals with the hysteresis gate, then ASTM E1049-85
/// section 5.4.4 (half_cycles) or 5.4.5 (repeating). Errors: empty history, a NaN or infinite
/// sample (named by index), a bad gate.
template <class Scalar>
Result<std::vector<Cycle<Scalar>>> count_cycles(const Scalar* samples, std::size_t n,
                                                const CountOptions<Scalar>& options = {}) {
  if (Status s = detail::check_gate(options.gate); !s) return s.error();
  if (Status s = detail::check_history(samples, n, "stress history"); !s) return s.error();
  return detail::count_history<Scalar>(
      n, [samples](std::size_t i) { return samples[i]; }, options.gate, options.closure,
      [](Scalar v) { return v; });
}

/// Overload for a std::vector history.
template <class Scalar>
Result<std::vector<Cycle<Scalar>>> count_cycles(const std::vector<Scalar>& samples,
                                                const CountOptions<Scalar>& options = {}) {
  return count_cycles(samples.data(), samples.size(), options);
}

/// Class-bin rainflow: each sample is replaced by its class of `grid`, reversals are extracted
/// on class indices with a gate of `gate_classes` classes (a reversal needs a move of more than
/// gate_classes classes), counted per ASTM E1049-85, and reported at class centres. This is the
/// batch twin of StreamingRainflow: both give the same (range, mean, count) rows.
/// Errors: empty history, a non-finite sample, a sample outside the class window (each named by
/// index), gate_classes < 0.
template <class Scalar>
Result<std::vector<Cycle<Scalar>>> count_cycles_classed(
    const Scalar* samples, std::size_t n, const ClassGrid<Scalar>& grid, int gate_classes = 0,
    CycleClosure closure = CycleClosure::half_cycles) {
  if (gate_classes < 0)
    return make_error(ErrorCode::invalid_argument, "class gate must be >= 0, got ", gate_classes);
  if (Status s = detail::check_history(samples, n, "stress history"); !s) return s.error();
  if (Status s = detail::check_in_grid(samples, n, grid, "stress history"); !s) return s.error();
  // Reversals on class indices: exact integer comparisons, as in the streaming counter.
  return detail::count_history<Scalar>(
      n, [samples, &grid](std::size_t i) { return grid.index(samples[i]); }, gate_classes, closure,
      [&grid](int i) { return grid.center(i); });
}

/// Overload for a std::vector history.
template <class Scalar>
Result<std::vector<Cycle<Scalar>>> count_cycles_classed(
    const std::vector<Scalar>& samples, const ClassGrid<Scalar>& grid, int gate_classes = 0,
    CycleClosure closure = CycleClosure::half_cycles) {
  return count_cycles_classed(samples.data(), samples.size(), grid, gate_classes, closure);
}

}  // namespace flexstress::fatigue
