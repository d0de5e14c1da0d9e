// Streaming rainflow counter: one sample at a time, fixed memory, no allocation, on class bins.
//
// Method: the four-point rainflow rule on a residue stack (equivalent to ASTM E1049-85 section
// 5.4.4 up to how ties are split between one cycle and two half cycles). Whenever the stack
// ends in four reversals A B C D with |C - B| <= |B - A| and |C - B| <= |D - C|, the inner range
// B-C is a closed hysteresis loop: it is counted as one cycle and B, C are removed. What stays
// is the residue. It is closed when asked, without changing the counter, in one of two ways
// (CycleClosure): each residue range as a half cycle (finished history; this reproduces the
// ASTM 5.4.4 counts), or by counting the residue followed by itself (the history is one block of
// a repeating history, ASTM 5.4.5; Amzallag et al., Int. J. Fatigue 16 (1994) 287-293).
//
// CAPACITY RULE (class-bin counting). The residue of an unbounded history grows without limit
// (a slowly decaying oscillation keeps every reversal), so this counter counts on NClasses
// class bins (a ClassGrid over a stress window [lower, upper] chosen at setup):
//   - every sample is replaced by its class index; reversals and ranges are exact integers,
//     reported at class centres;
//   - on N classes the residue never holds more than 2N - 1 reversals: its ranges (integers in
//     1..N-1) rise strictly, then fall strictly, the largest at most twice (an inner range no
//     larger than both neighbours would have closed), so at most 2N - 2 ranges; a residue
//     buffer of 2N (compile time) can never overflow, however long the history;
//   - streaming equals batch within this rule: count_cycles_classed() on the same samples, grid
//     and gate gives the same (range, mean, count) rows and the same damage (tested);
//   - a finite sample outside the window is refused with StepStatus::capacity_exceeded and
//     nothing changes (clamp it yourself if saturation is what you want); a NaN or infinite
//     sample is refused with StepStatus::invalid_input and nothing changes.
//
// Cost per sample: one class lookup and one comparison in the common case; a cycle closure
// touches the top four stack entries. Memory: 2 NClasses ints (the residue); closing the
// residue takes 4 NClasses ints of stack for the call.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

#include "flexstress/core/assert.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/fatigue/class_grid.hpp"
#include "flexstress/fatigue/cycle.hpp"
#include "flexstress/fatigue/reversals.hpp"

namespace flexstress::fatigue {

/// Class-bin four-point rainflow counter with a residue of at most 2 NClasses reversals.
///
/// Sink: any callable `sink(const Cycle<Scalar>&)`; it receives every counted cycle (from, to at
/// class centres). The counter itself stores no cycle list: StreamingDamage passes a Miner sum,
/// a RangeMeanMatrix or FromToMatrix is a sink as it is, or pass your own.
template <class Scalar, int NClasses>
class StreamingRainflow {
  static_assert(NClasses >= 2, "StreamingRainflow needs at least 2 classes");
  static_assert(NClasses <= 4096,
                "StreamingRainflow: more than 4096 classes makes the counter large (2 ints per "
                "class, 4 more on the stack to close it); 4096 classes already resolve 1/4096 of "
                "the stress window");

 public:
  static constexpr int classes = NClasses;
  /// Residue buffer size; the residue never exceeds 2 NClasses - 1 reversals.
  static constexpr int residue_capacity = 2 * NClasses;

  /// Counter over `grid` (which must have NClasses classes) with a hysteresis gate of
  /// `gate_classes` classes (a reversal needs a move of more than gate_classes classes; 0 keeps
  /// every change of class, 1 drops one-class flicker at class edges).
  static Result<StreamingRainflow> create(const ClassGrid<Scalar>& grid, int gate_classes = 0) {
    if (grid.size() != NClasses)
      return make_error(ErrorCode::size_mismatch, "class grid has ", grid.size(),
                        " classes, the streaming counter was compiled for ", NClasses);
    if (gate_classes < 0 || gate_classes >= NClasses)
      return make_error(ErrorCode::invalid_argument, "class gate must be in [0, ", NClasses - 1,
                        "], got ", gate_classes);
    return StreamingRainflow(grid, gate_classes);
  }

  /// Feeds one sample; every cycle it closes goes to sink. Never allocates.
  /// Returns ok; invalid_input for NaN/inf; capacity_exceeded for a sample outside the class
  /// window. On any status but ok the counter is unchanged.
  template <class Sink>
  StepStatus push(Scalar x, Sink&& sink) {
    if (!std::isfinite(x)) return StepStatus::invalid_input;
    if (!grid_.contains(x)) return StepStatus::capacity_exceeded;
    ++samples_;
    filter_.push(grid_.index(x), [this, &sink](int reversal) {
      four_point_push(residue_.data(), size_, reversal, [this, &sink](int a, int b) {
        ++closed_cycles_;
        sink(Cycle<Scalar>{grid_.center(a), grid_.center(b), Scalar(1)});
      });
    });
    FLEXSTRESS_ASSERT(size_ < residue_capacity, "StreamingRainflow: residue bound violated");
    return StepStatus::ok;
  }

  /// Feeds one sample, discarding closed cycles (for tests of the residue alone).
  StepStatus push(Scalar x) {
    return push(x, [](const Cycle<Scalar>&) {});
  }

  /// Closes the residue as if the history ended now, without changing the counter, and sends
  /// the closing counts to sink: full cycles the last (pending) reversal closes, then each
  /// residue range as a half cycle (ASTM E1049-85 section 5.4.4 step 6). Never allocates.
  template <class Sink>
  void visit_half_cycle_closure(Sink&& sink) const {
    std::array<int, residue_capacity> stack;  // on the stack: a const read, no member scratch
    int* s = stack.data();
    int n = load_final_residue(s, sink);
    for (int i = 0; i + 1 < n; ++i)
      sink(Cycle<Scalar>{grid_.center(s[i]), grid_.center(s[i + 1]), Scalar(0.5)});
  }

  /// Closes the residue as one block of a repeating history (ASTM E1049-85 section 5.4.5),
  /// without changing the counter: the final residue R is followed by itself and counted on, so
  /// every range of R ends up in a full cycle. Sends those cycles to sink. Together with the
  /// cycles already closed, these are the cycles of one work cycle. Never allocates.
  template <class Sink>
  void visit_repeating_closure(Sink&& sink) const {
    // The closure stack and a second copy of R, kept apart from it (the stack overwrites its own
    // entries); on the stack, so that a const counter can be read.
    std::array<int, 2 * residue_capacity> scratch;
    int* s = scratch.data();
    int n = load_final_residue(s, sink);
    int* copy = scratch.data() + residue_capacity;
    for (int i = 0; i < n; ++i) copy[i] = s[i];
    const int m = n;
    auto full = [this, &sink](int a, int b) {
      sink(Cycle<Scalar>{grid_.center(a), grid_.center(b), Scalar(1)});
    };
    for (int i = 0; i < m; ++i) four_point_push(s, n, copy[i], full);
  }

  /// Number of confirmed reversals in the residue (<= 2 NClasses - 1).
  int residue_size() const noexcept { return size_; }
  /// Value (class centre) of residue reversal i, 0 <= i < residue_size().
  Scalar residue(int i) const {
    FLEXSTRESS_ASSERT(i >= 0 && i < size_, "StreamingRainflow::residue: index out of range");
    return grid_.center(residue_[static_cast<std::size_t>(i)]);
  }
  /// True when a last reversal is pending (the extreme since the last confirmed reversal).
  bool has_pending() const noexcept { return filter_.has_pending(); }
  /// Value (class centre) of the pending reversal; only meaningful when has_pending().
  Scalar pending() const { return grid_.center(filter_.pending()); }

  /// Samples accepted so far.
  std::uint64_t samples() const noexcept { return samples_; }
  /// Full cycles closed so far (closure cycles not included).
  std::uint64_t closed_cycles() const noexcept { return closed_cycles_; }
  const ClassGrid<Scalar>& grid() const noexcept { return grid_; }
  int gate_classes() const noexcept { return filter_.gate(); }

  /// Forgets the history (keeps grid and gate).
  void reset() noexcept {
    filter_.reset();
    size_ = 0;
    samples_ = 0;
    closed_cycles_ = 0;
  }

  /// Everything the counter has accumulated (not its grid and gate): what a checkpoint saves.
  struct History {
    typename ReversalFilter<int>::State filter;
    std::array<int, residue_capacity> residue{};
    int size = 0;
    std::uint64_t samples = 0;
    std::uint64_t closed_cycles = 0;
  };
  History history() const noexcept {
    return History{filter_.state(), residue_, size_, samples_, closed_cycles_};
  }

  /// Continues from a saved history. It must be one this counter could have reached: class
  /// indices in the grid, a residue of alternating reversals in which the four-point rule closes
  /// nothing (so the bound 2N - 1 holds), a pending reversal that continues the residue, and
  /// counts that fit the samples. Otherwise an error names the first defect and nothing changes.
  Status restore_history(const History& h) {
    auto bad = [](const auto&... parts) {
      return make_error(ErrorCode::invalid_argument, "rainflow history: ", parts...);
    };
    auto in_grid = [](int c) { return c >= 0 && c < NClasses; };
    const auto& f = h.filter;
    if (h.size < 0 || h.size >= residue_capacity)
      return bad("residue of ", h.size, " reversals (", NClasses, " classes allow 0 to ",
                 residue_capacity - 1, ")");
    for (int i = 0; i < h.size; ++i) {
      const int c = h.residue[static_cast<std::size_t>(i)];
      if (!in_grid(c))
        return bad("residue reversal ", i, " is class ", c, ", outside the ", NClasses, " classes");
      if (i >= 1 && c == h.residue[static_cast<std::size_t>(i - 1)])
        return bad("residue reversals ", i - 1, " and ", i, " are equal");
      if (i >= 2 && (c > h.residue[static_cast<std::size_t>(i - 1)]) ==
                        (h.residue[static_cast<std::size_t>(i - 1)] >
                         h.residue[static_cast<std::size_t>(i - 2)]))
        return bad("residue reversals ", i - 2, " to ", i, " do not alternate");
      if (i >= 3) {
        const int* s = h.residue.data() + i - 3;
        const int z = abs_diff(s[1], s[0]), y = abs_diff(s[2], s[1]), x = abs_diff(s[3], s[2]);
        if (y <= x && y <= z)
          return bad("residue range ", i - 2, " to ", i - 1,
                     " is a closed cycle (four-point rule)");
      }
    }
    if (f.direction < -1 || f.direction > 1 || (!f.started && f.direction != 0))
      return bad("reversal filter direction ", f.direction, f.started ? "" : " before any sample");
    if (f.started && (!in_grid(f.low) || !in_grid(f.high) || !in_grid(f.candidate)))
      return bad("reversal filter classes ", f.low, ", ", f.high, ", ", f.candidate,
                 " outside the ", NClasses, " classes");
    if ((f.direction == 0) != (h.size == 0))
      return bad(f.direction == 0 ? "no pending reversal after " : "a pending reversal with ",
                 h.size, " confirmed ones");
    if (h.size >= 1 && f.direction != 0) {
      const int last = h.residue[static_cast<std::size_t>(h.size - 1)];
      const bool continues =
          f.direction * (f.candidate - last) > filter_.gate() &&
          (h.size < 2 ||
           (last > h.residue[static_cast<std::size_t>(h.size - 2)]) == (f.direction < 0));
      if (!continues)
        return bad("pending reversal class ", f.candidate, " does not continue the residue");
    }
    if (2 * h.closed_cycles + static_cast<std::uint64_t>(h.size) > h.samples)
      return bad(h.closed_cycles, " closed cycles and ", h.size, " residue reversals from ",
                 h.samples, " samples");
    filter_.set_state(f);
    residue_ = h.residue;
    size_ = h.size;
    samples_ = h.samples;
    closed_cycles_ = h.closed_cycles;
    return Status::success();
  }

 private:
  StreamingRainflow(const ClassGrid<Scalar>& grid, int gate_classes)
      : grid_(grid), filter_(gate_classes) {}

  /// Pushes class index v onto the four-point stack s[0..n) and closes what it can, calling
  /// full(a, b) for every closed cycle a-b. Keeps s a reversal sequence: a repeated value is
  /// dropped and a value that continues the last direction replaces the last point (this only
  /// happens where a residue is joined to itself).
  template <class Full>
  static void four_point_push(int* s, int& n, int v, Full&& full) {
    if (n >= 1 && s[n - 1] == v) return;
    if (n >= 2 && (s[n - 1] > s[n - 2]) == (v > s[n - 1])) {
      s[n - 1] = v;
    } else {
      s[n++] = v;
    }
    // Four-point rule: the inner range Y = |s[n-2] - s[n-3]| closes when it is no larger than
    // both neighbours X (after it) and Z (before it).
    while (n >= 4) {
      const int z = abs_diff(s[n - 3], s[n - 4]);
      const int y = abs_diff(s[n - 2], s[n - 3]);
      const int x = abs_diff(s[n - 1], s[n - 2]);
      if (y > x || y > z) break;
      full(s[n - 3], s[n - 2]);
      s[n - 3] = s[n - 1];
      n -= 2;
    }
  }

  static int abs_diff(int a, int b) noexcept { return a > b ? a - b : b - a; }

  /// Copies the residue into s, adds the pending reversal (sending the cycles it closes to
  /// sink as full cycles) and returns the length of the final residue.
  template <class Sink>
  int load_final_residue(int* s, Sink& sink) const {
    int n = size_;
    for (int i = 0; i < n; ++i) s[i] = residue_[static_cast<std::size_t>(i)];
    if (filter_.has_pending()) {
      four_point_push(s, n, filter_.pending(), [this, &sink](int a, int b) {
        sink(Cycle<Scalar>{grid_.center(a), grid_.center(b), Scalar(1)});
      });
    }
    return n;
  }

  ClassGrid<Scalar> grid_;
  ReversalFilter<int> filter_;
  std::array<int, residue_capacity> residue_{};
  int size_ = 0;
  std::uint64_t samples_ = 0;
  std::uint64_t closed_cycles_ = 0;
};

}  // namespace flexstress::fatigue
