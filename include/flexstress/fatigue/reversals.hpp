// Reversal (peak-valley) extraction with an optional hysteresis gate, one sample at a time or
// for a whole history.
//
// A reversal is a point where the history changes direction (the peaks and valleys of ASTM
// E1049-85 section 3, terminology). Rainflow counting works on reversals only, so everything in
// between is dropped, and so are plateaus (repeated equal values collapse to their first
// occurrence).
//
// Hysteresis gate g >= 0 (the "racetrack" or range-threshold filter that removes small,
// non-damaging ranges before counting): a candidate peak is confirmed only once the history has
// fallen more than g below it, a candidate valley once it has risen more than g above it. Every
// range between two consecutive reversals is then larger than g, and wiggles of size <= g (sensor
// noise, solver jitter) disappear without shifting the reversals that remain. With g = 0 this is
// plain peak-valley extraction.
//
// The first reversal is the smaller or larger of the values seen before the history first moved
// by more than g (for g = 0 this is the first sample); the last is the final candidate, emitted
// by `finish()`. A history that never moves by more than g has no reversals.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "flexstress/core/status.hpp"

namespace flexstress::fatigue {

/// Streaming peak-valley filter. T is the sample type: a floating-point Scalar, or an integer
/// class index (the class-bin counter filters quantized samples exactly, in integers).
///
/// push() never allocates and emits at most one reversal per sample, through a callback
/// `emit(T reversal)`. Preconditions (checked by the callers that take user input): samples are
/// finite and the gate is finite and >= 0.
template <class T>
class ReversalFilter {
 public:
  explicit ReversalFilter(T gate = T(0)) : gate_(gate) {}

  /// Feeds one sample; calls emit(reversal) when a reversal is confirmed.
  template <class Emit>
  void push(T x, Emit&& emit) {
    if (!started_) {
      // The first sample opens the undecided phase: no direction yet.
      started_ = true;
      low_ = high_ = x;
      return;
    }
    if (direction_ == 0) {
      // Undecided: track the extremes until they are more than the gate apart. The newest
      // sample is then one of them; the other, older one is the first reversal.
      if (x > high_) {
        high_ = x;
        if (high_ - low_ > gate_) {
          emit(low_);
          direction_ = 1;
          candidate_ = high_;
        }
      } else if (x < low_) {
        low_ = x;
        if (high_ - low_ > gate_) {
          emit(high_);
          direction_ = -1;
          candidate_ = low_;
        }
      }
      return;
    }
    if (direction_ > 0) {
      // Rising towards a candidate peak.
      if (x > candidate_) {
        candidate_ = x;
      } else if (candidate_ - x > gate_) {
        emit(candidate_);  // peak confirmed
        direction_ = -1;
        candidate_ = x;
      }
    } else {
      // Falling towards a candidate valley.
      if (x < candidate_) {
        candidate_ = x;
      } else if (x - candidate_ > gate_) {
        emit(candidate_);  // valley confirmed
        direction_ = 1;
        candidate_ = x;
      }
    }
  }

  /// Ends the history: emits the last (pending) reversal, if any, and resets the filter.
  template <class Emit>
  void finish(Emit&& emit) {
    if (direction_ != 0) emit(candidate_);
    reset();
  }

  /// True when a last reversal is pending (it becomes final when the history ends or reverses).
  bool has_pending() const noexcept { return direction_ != 0; }
  /// The pending reversal; only meaningful when has_pending().
  T pending() const noexcept { return candidate_; }
  /// Direction of travel: +1 rising, -1 falling, 0 not decided yet.
  int direction() const noexcept { return direction_; }
  T gate() const noexcept { return gate_; }

  /// Forgets the history; keeps the gate.
  void reset() noexcept {
    started_ = false;
    direction_ = 0;
    low_ = high_ = candidate_ = T(0);
  }

  /// What the filter remembers of the history (the gate is configuration): for checkpoints.
  struct State {
    T low = T(0), high = T(0), candidate = T(0);
    int direction = 0;
    bool started = false;
  };
  State state() const noexcept { return State{low_, high_, candidate_, direction_, started_}; }
  /// Sets a saved state (checked by the caller that reads it from outside).
  void set_state(const State& s) noexcept {
    low_ = s.low;
    high_ = s.high;
    candidate_ = s.candidate;
    direction_ = s.direction;
    started_ = s.started;
  }

 private:
  T gate_;
  T low_ = T(0);   // undecided phase: smallest sample so far
  T high_ = T(0);  // undecided phase: largest sample so far
  T candidate_ = T(0);
  int direction_ = 0;
  bool started_ = false;
};

namespace detail {

/// "NaN", "+inf" or "-inf" for a non-finite value (for error messages).
template <class Scalar>
const char* non_finite_name(Scalar x) {
  if (std::isnan(x)) return "NaN";
  return x > Scalar(0) ? "+inf" : "-inf";
}

/// Checks a history: not empty, every sample finite. The message names the first bad sample.
template <class Scalar>
Status check_history(const Scalar* samples, std::size_t n, const char* what) {
  if (n == 0) return make_error(ErrorCode::invalid_argument, what, " is empty");
  if (samples == nullptr)
    return make_error(ErrorCode::invalid_argument, what, ": null data pointer for ", n, " samples");
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(samples[i]))
      return make_error(ErrorCode::invalid_argument, what, ": sample ", i, " is ",
                        non_finite_name(samples[i]));
  }
  return Status::success();
}

/// Checks a hysteresis gate: finite and >= 0.
template <class Scalar>
Status check_gate(Scalar gate) {
  if (!std::isfinite(gate) || gate < Scalar(0))
    return make_error(ErrorCode::invalid_argument, "hysteresis gate must be finite and >= 0, got ",
                      gate);
  return Status::success();
}

}  // namespace detail

/// Reversals (peaks and valleys) of a stress history, filtered by a hysteresis gate (stress
/// units, >= 0). Errors: empty history, a NaN or infinite sample (the message names its index),
/// a negative or non-finite gate.
template <class Scalar>
Result<std::vector<Scalar>> extract_reversals(const Scalar* samples, std::size_t n,
                                              Scalar gate = Scalar(0)) {
  if (Status s = detail::check_gate(gate); !s) return s.error();
  if (Status s = detail::check_history(samples, n, "stress history"); !s) return s.error();
  std::vector<Scalar> reversals;
  ReversalFilter<Scalar> filter(gate);
  auto keep = [&reversals](Scalar r) { reversals.push_back(r); };
  for (std::size_t i = 0; i < n; ++i) filter.push(samples[i], keep);
  filter.finish(keep);
  return reversals;
}

/// Overload for a std::vector history.
template <class Scalar>
Result<std::vector<Scalar>> extract_reversals(const std::vector<Scalar>& samples,
                                              Scalar gate = Scalar(0)) {
  return extract_reversals(samples.data(), samples.size(), gate);
}

}  // namespace flexstress::fatigue
