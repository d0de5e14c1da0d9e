// A counted stress cycle (from, to, count) and the summaries built on lists of them.
//
// Every counter in flexstress/fatigue (batch ASTM E1049-85 rainflow, the streaming four-point
// counter) reports cycles as `Cycle<Scalar>`: the two reversal values it joins, in the order
// they occurred, and a count of 1 (a closed hysteresis loop) or 0.5 (a half cycle, ASTM
// E1049-85 section 5.4.4 step 5 and 6). Range and mean follow from the two values, so the same
// list feeds the (range, mean, count) table, the range-mean matrix and the from-to matrix.
//
// Units: whatever the stress history is in (MPa throughout the docs).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace flexstress::fatigue {

/// How a counter closes what is left of a history when it ends.
enum class CycleClosure : std::uint8_t {
  /// Each range of the residue is one half cycle (ASTM E1049-85 section 5.4.4, step 6). Right
  /// for a finished, non-repeating history.
  half_cycles,
  /// The history is one block of a history that repeats (a work cycle): the residue is closed
  /// with the next repetition, so every count is a full cycle (ASTM E1049-85 section 5.4.5).
  repeating,
};

/// One counted cycle: reversal `from` then reversal `to`, counted `count` times (1 or 0.5).
template <class Scalar>
struct Cycle {
  Scalar from = Scalar(0);   ///< First reversal of the range, in the order of the history.
  Scalar to = Scalar(0);     ///< Second reversal of the range.
  Scalar count = Scalar(1);  ///< 1 for a closed cycle, 0.5 for a half cycle.

  /// Stress range |to - from| (peak to valley, not amplitude).
  Scalar range() const {
    using std::abs;
    return abs(to - from);
  }
  /// Mean stress (from + to) / 2.
  Scalar mean() const { return (from + to) / Scalar(2); }
  /// Larger of the two reversals (sigma_max of the cycle).
  Scalar max() const { return from > to ? from : to; }
  /// Smaller of the two reversals (sigma_min of the cycle).
  Scalar min() const { return from > to ? to : from; }
};

/// One row of a (range, mean, count) table.
template <class Scalar>
struct RangeMeanCount {
  Scalar range = Scalar(0);
  Scalar mean = Scalar(0);
  Scalar count = Scalar(0);
};

/// Merges cycles with the same range and mean, summing their counts; rows sorted by range,
/// then mean, both ascending. This is the form of the ASTM E1049-85 example tables (there by
/// range only) and the form in which two counters can be compared: the four-point and the
/// three-point algorithm may split a tie into one full cycle or two half cycles, which merge to
/// the same row.
template <class Scalar>
std::vector<RangeMeanCount<Scalar>> aggregate_cycles(const std::vector<Cycle<Scalar>>& cycles) {
  std::vector<RangeMeanCount<Scalar>> rows;
  rows.reserve(cycles.size());
  for (const Cycle<Scalar>& c : cycles) rows.push_back({c.range(), c.mean(), c.count});
  std::sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) {
    return a.range < b.range || (a.range == b.range && a.mean < b.mean);
  });
  // Merge equal (range, mean) neighbours in place.
  std::size_t out = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (out > 0 && rows[out - 1].range == rows[i].range && rows[out - 1].mean == rows[i].mean) {
      rows[out - 1].count += rows[i].count;
    } else {
      rows[out++] = rows[i];
    }
  }
  rows.resize(out);
  return rows;
}

/// Sum of the counts (half cycles count 0.5).
template <class Scalar>
Scalar total_count(const std::vector<Cycle<Scalar>>& cycles) {
  Scalar n(0);
  for (const Cycle<Scalar>& c : cycles) n += c.count;
  return n;
}

/// Range content sum(2 * count * range): the total distance travelled by the history between
/// its reversals. A full cycle travels its range twice, a half cycle once, so rainflow counting
/// conserves it: for a finished history (half-cycle closure) it equals sum |r[i+1] - r[i]| over
/// the reversals r; for a repeating block it equals the same sum around the closed loop.
template <class Scalar>
Scalar range_content(const std::vector<Cycle<Scalar>>& cycles) {
  Scalar s(0);
  for (const Cycle<Scalar>& c : cycles) s += Scalar(2) * c.count * c.range();
  return s;
}

}  // namespace flexstress::fatigue
