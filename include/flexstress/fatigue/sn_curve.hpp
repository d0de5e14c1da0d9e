// S-N (Woehler) curves of welded details: piecewise power laws N * Delta_sigma^m = const in
// log-log coordinates, with an optional cut-off, plus the named curves of EN 1993-1-9 and the
// IIW recommendations and the IIW thickness correction.
//
// A curve is a reference point (Delta_sigma_ref at N_ref cycles; the detail category or FAT
// class at 2e6) and up to four segments in order of increasing N. Segment i has slope m_i and
// runs to end_cycles_i; the next one starts there (the curve is continuous). The last segment
// either stays open (end_cycles = +inf) or ends at a finite N_L: then it is a cut-off, and
// stress ranges below Delta_sigma(N_L) do no damage (EN 1993-1-9 section 7.1).
//
// Stress ranges in MPa (N/mm^2) by convention; any unit works if the curve and the history
// agree. These are characteristic (resistance) curves: partial factors, thickness and mean
// stress enter through DamageModel (damage.hpp) or SnCurve::scaled.
//
// Named curves and their sources:
//   en1993_normal_curve   EN 1993-1-9:2005 section 7.1, Figure 7.1: m = 3 to
//                         5e6 (Delta_sigma_D = (2/5)^(1/3) Delta_sigma_C = 0.737 Delta_sigma_C),
//                         m = 5 to 1e8 (Delta_sigma_L = (5/100)^(1/5) Delta_sigma_D = 0.405
//                         Delta_sigma_C), cut-off below.
//   en1993_shear_curve    EN 1993-1-9:2005 section 7.1, Figure 7.2: m = 5 to 1e8
//                         (Delta_tau_L = (2/100)^(1/5) Delta_tau_C = 0.457 Delta_tau_C), cut-off.
//   iiw_normal_curve      Hobbacher, IIW-2259-15 chapter 3: FAT at 2e6, m = 3 to the knee at
//                         1e7, then m = 22 (standard applications) or m' = 2m - 1 = 5 (Haibach,
//                         for variable-amplitude Miner sums).
//   iiw_shear_curve       IIW-2259-15 chapter 3: m = 5 to the knee at 1e8, then m = 22 or
//                         the Haibach slope 2m - 1 = 9.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "flexstress/core/assert.hpp"
#include "flexstress/core/status.hpp"

namespace flexstress::fatigue {

/// One segment of an S-N curve: slope m, valid up to end_cycles (+inf: open to the right).
template <class Scalar>
struct SnSegment {
  Scalar slope;
  Scalar end_cycles;
  /// Segment of slope m up to end cycles; open to the right when end is left out, so a curve
  /// reads {{3, 5e6}, {5, 1e8}} or {{3, 1e7}, {22}}. (A constructor, not default member
  /// initializers: GCC 12 crashes on those in nested braced lists of a template.)
  constexpr SnSegment(Scalar m, Scalar end = std::numeric_limits<Scalar>::infinity())  // NOLINT
      : slope(m), end_cycles(end) {}
};

/// Piecewise power-law S-N curve with at most max_segments segments. Immutable after create();
/// evaluation never allocates.
template <class Scalar>
class SnCurve {
 public:
  static constexpr int max_segments = 4;

  /// Curve through (reference_cycles, reference_range) with the given segments (see the file
  /// comment). Errors: non-positive or non-finite reference values, no or too many segments,
  /// a non-positive slope, end_cycles not strictly increasing, an infinite end before the last
  /// segment, or a reference point beyond the cut-off.
  static Result<SnCurve> create(Scalar reference_range, Scalar reference_cycles,
                                const std::vector<SnSegment<Scalar>>& segments) {
    if (!std::isfinite(reference_range) || !(reference_range > Scalar(0)))
      return make_error(ErrorCode::invalid_argument,
                        "S-N reference stress range must be positive, got ", reference_range);
    if (!std::isfinite(reference_cycles) || !(reference_cycles > Scalar(0)))
      return make_error(ErrorCode::invalid_argument,
                        "S-N reference cycle count must be positive, got ", reference_cycles);
    const int k = static_cast<int>(segments.size());
    if (k < 1 || k > max_segments)
      return make_error(ErrorCode::invalid_argument, "an S-N curve needs 1 to ", max_segments,
                        " segments, got ", k);
    for (int i = 0; i < k; ++i) {
      const SnSegment<Scalar>& s = segments[static_cast<std::size_t>(i)];
      if (!std::isfinite(s.slope) || !(s.slope > Scalar(0)))
        return make_error(ErrorCode::invalid_argument, "S-N segment ", i,
                          ": slope must be positive and finite, got ", s.slope);
      if (std::isnan(s.end_cycles) || !(s.end_cycles > Scalar(0)))
        return make_error(ErrorCode::invalid_argument, "S-N segment ", i,
                          ": end cycle count must be positive, got ", s.end_cycles);
      if (i + 1 < k && !std::isfinite(s.end_cycles))
        return make_error(ErrorCode::invalid_argument, "S-N segment ", i,
                          ": only the last segment may be open (infinite end)");
      if (i >= 1 && !(s.end_cycles > segments[static_cast<std::size_t>(i - 1)].end_cycles))
        return make_error(ErrorCode::invalid_argument, "S-N segment ", i, ": end cycle count ",
                          s.end_cycles, " must exceed the previous one");
    }
    if (reference_cycles > segments.back().end_cycles)
      return make_error(ErrorCode::invalid_argument, "S-N reference point at ", reference_cycles,
                        " cycles lies beyond the cut-off at ", segments.back().end_cycles);

    SnCurve c;
    c.count_ = k;
    for (int i = 0; i < k; ++i) {
      c.slope_[i] = segments[static_cast<std::size_t>(i)].slope;
      c.end_n_[i] = segments[static_cast<std::size_t>(i)].end_cycles;
    }
    // Segment j holds the reference point: the first whose end is at or beyond N_ref.
    int j = 0;
    while (c.end_n_[j] < reference_cycles) ++j;
    // Stress range at each finite segment end: from the reference point along segment j, then
    // outwards knee by knee (S_b = S_a (N_a / N_b)^(1/m) along a segment of slope m).
    using std::pow;
    for (int i = 0; i < k; ++i) c.end_s_[i] = Scalar(0);
    if (std::isfinite(c.end_n_[j]))
      c.end_s_[j] = reference_range * pow(reference_cycles / c.end_n_[j], Scalar(1) / c.slope_[j]);
    for (int i = j + 1; i < k && std::isfinite(c.end_n_[i]); ++i)
      c.end_s_[i] = c.end_s_[i - 1] * pow(c.end_n_[i - 1] / c.end_n_[i], Scalar(1) / c.slope_[i]);
    for (int i = j - 1; i >= 0; --i)
      c.end_s_[i] =
          c.end_s_[i + 1] * pow(c.end_n_[i + 1] / c.end_n_[i], Scalar(1) / c.slope_[i + 1]);
    // Anchor point of each segment: its start knee, or for the first segment its end (or the
    // reference point when it is the only, open segment).
    for (int i = 0; i < k; ++i) {
      if (i >= 1) {
        c.anchor_n_[i] = c.end_n_[i - 1];
        c.anchor_s_[i] = c.end_s_[i - 1];
      } else if (std::isfinite(c.end_n_[0])) {
        c.anchor_n_[0] = c.end_n_[0];
        c.anchor_s_[0] = c.end_s_[0];
      } else {
        c.anchor_n_[0] = reference_cycles;
        c.anchor_s_[0] = reference_range;
      }
    }
    return c;
  }

  /// Number of cycles to failure at constant stress range ds (+inf at or below 0 and below a
  /// cut-off).
  Scalar cycles_to_failure(Scalar ds) const {
    const int i = segment_of_range(ds);
    if (i < 0) return std::numeric_limits<Scalar>::infinity();
    using std::pow;
    return anchor_n_[i] * pow(anchor_s_[i] / ds, slope_[i]);
  }

  /// Palmgren-Miner damage of one cycle of range ds, 1 / N(ds); 0 at or below 0 and below a
  /// cut-off. Computed as (ds / S_a)^m / N_a so that steep slopes (m = 22) neither overflow nor
  /// lose precision in float.
  Scalar damage_per_cycle(Scalar ds) const {
    const int i = segment_of_range(ds);
    if (i < 0) return Scalar(0);
    using std::pow;
    return pow(ds / anchor_s_[i], slope_[i]) / anchor_n_[i];
  }

  /// Stress range at n cycles (n > 0). Beyond a cut-off the curve is horizontal: returns the
  /// cut-off range.
  Scalar stress_range_at(Scalar n) const {
    FLEXSTRESS_ASSERT(n > Scalar(0), "SnCurve::stress_range_at: cycle count must be positive");
    using std::pow;
    for (int i = 0; i < count_; ++i) {
      if (n <= end_n_[i]) return anchor_s_[i] * pow(anchor_n_[i] / n, Scalar(1) / slope_[i]);
    }
    return end_s_[count_ - 1];  // beyond the cut-off
  }

  /// Slope m of the segment holding n cycles; +inf beyond a cut-off (horizontal).
  Scalar slope_at(Scalar n) const {
    for (int i = 0; i < count_; ++i)
      if (n <= end_n_[i]) return slope_[i];
    return std::numeric_limits<Scalar>::infinity();
  }

  /// The same curve with every stress range multiplied by factor (> 0): a thickness factor,
  /// 1 / gamma_Mf for the design curve, a mean-stress enhancement f(R). Errors: factor not
  /// positive and finite.
  Result<SnCurve> scaled(Scalar factor) const {
    if (!std::isfinite(factor) || !(factor > Scalar(0)))
      return make_error(ErrorCode::invalid_argument,
                        "S-N scale factor must be positive and finite, got ", factor);
    SnCurve c = *this;
    for (int i = 0; i < count_; ++i) {
      c.anchor_s_[i] *= factor;
      c.end_s_[i] *= factor;
    }
    return c;
  }

  /// Number of segments.
  int segments() const noexcept { return count_; }
  /// Slope of segment i.
  Scalar slope(int i) const { return slope_[checked(i)]; }
  /// Cycle count where segment i ends (+inf for an open last segment).
  Scalar end_cycles(int i) const { return end_n_[checked(i)]; }
  /// Stress range where segment i ends (0 for an open last segment).
  Scalar end_range(int i) const { return end_s_[checked(i)]; }
  /// Cut-off stress range (no damage below it), or 0 when the curve is open.
  Scalar cutoff_range() const noexcept { return end_s_[count_ - 1]; }

 private:
  SnCurve() = default;

  int checked(int i) const {
    FLEXSTRESS_ASSERT(i >= 0 && i < count_, "SnCurve: segment index out of range");
    return i;
  }

  /// Segment that holds stress range ds, or -1 when ds does no damage (ds <= 0, NaN, or below a
  /// cut-off). Segments are ordered by decreasing range; segment i holds [end_s_i, end_s_{i-1}].
  int segment_of_range(Scalar ds) const {
    if (!(ds > Scalar(0))) return -1;
    for (int i = 0; i < count_; ++i)
      if (ds >= end_s_[i]) return i;
    return -1;  // below the cut-off
  }

  int count_ = 0;
  std::array<Scalar, max_segments> slope_{};
  std::array<Scalar, max_segments> end_n_{};     // N at the end of each segment
  std::array<Scalar, max_segments> end_s_{};     // range at the end (0 if open)
  std::array<Scalar, max_segments> anchor_n_{};  // a point (N, S) on each segment
  std::array<Scalar, max_segments> anchor_s_{};
};

namespace detail {
template <class Scalar>
Status check_category(Scalar value, const char* name) {
  if (!std::isfinite(value) || !(value > Scalar(0)))
    return make_error(ErrorCode::invalid_argument, name, " must be positive, got ", value);
  return Status::success();
}
}  // namespace detail

/// EN 1993-1-9:2005 direct-stress curve of detail category Delta_sigma_C (MPa at 2e6 cycles):
/// m = 3 to N_D = 5e6, m = 5 to N_L = 1e8, cut-off below Delta_sigma_L (section 7.1, Fig. 7.1).
template <class Scalar>
Result<SnCurve<Scalar>> en1993_normal_curve(Scalar delta_sigma_c) {
  if (Status s = detail::check_category(delta_sigma_c, "detail category Delta_sigma_C"); !s)
    return s.error();
  return SnCurve<Scalar>::create(delta_sigma_c, Scalar(2e6),
                                 {{Scalar(3), Scalar(5e6)}, {Scalar(5), Scalar(1e8)}});
}

/// EN 1993-1-9:2005 shear-stress curve of detail category Delta_tau_C (MPa at 2e6 cycles):
/// m = 5 to N_L = 1e8, cut-off below Delta_tau_L (section 7.1, Fig. 7.2).
template <class Scalar>
Result<SnCurve<Scalar>> en1993_shear_curve(Scalar delta_tau_c) {
  if (Status s = detail::check_category(delta_tau_c, "detail category Delta_tau_C"); !s)
    return s.error();
  return SnCurve<Scalar>::create(delta_tau_c, Scalar(2e6), {{Scalar(5), Scalar(1e8)}});
}

/// What an IIW curve does beyond its knee point.
enum class IiwBeyondKnee : std::uint8_t {
  slope_22,  ///< m = 22 (about 10 % less strength per decade): IIW-2259-15 standard applications.
  haibach,   ///< m' = 2m - 1 (Haibach): the variable-amplitude Miner-sum curve of IIW.
};

/// IIW normal-stress curve of class FAT (MPa at 2e6 cycles), slope m (3 for steel welds) to the
/// knee at 1e7 cycles, then beyond as chosen (Hobbacher, IIW-2259-15 chapter 3).
template <class Scalar>
Result<SnCurve<Scalar>> iiw_normal_curve(Scalar fat, IiwBeyondKnee beyond = IiwBeyondKnee::slope_22,
                                         Scalar m = Scalar(3)) {
  if (Status s = detail::check_category(fat, "FAT"); !s) return s.error();
  if (Status s = detail::check_category(m, "S-N slope m"); !s) return s.error();
  const Scalar m2 = beyond == IiwBeyondKnee::slope_22 ? Scalar(22) : Scalar(2) * m - Scalar(1);
  return SnCurve<Scalar>::create(fat, Scalar(2e6), {{m, Scalar(1e7)}, {m2}});
}

/// IIW shear-stress curve of class FAT (MPa at 2e6 cycles): m = 5 to the knee at 1e8 cycles,
/// then m = 22 or the Haibach slope 2m - 1 = 9 (IIW-2259-15 chapter 3).
template <class Scalar>
Result<SnCurve<Scalar>> iiw_shear_curve(Scalar fat,
                                        IiwBeyondKnee beyond = IiwBeyondKnee::slope_22) {
  if (Status s = detail::check_category(fat, "FAT"); !s) return s.error();
  const Scalar m2 = beyond == IiwBeyondKnee::slope_22 ? Scalar(22) : Scalar(9);
  return SnCurve<Scalar>::create(fat, Scalar(2e6), {{Scalar(5), Scalar(1e8)}, {m2}});
}

/// IIW thickness correction f(t) = (t_ref / t)^n for t > t_ref, 1 otherwise (IIW-2259-15 section
/// 3.5.2; EN 1993-1-9 uses the same form, k_s = (25 / t)^0.2, for the details that call for
/// it). Multiply the FAT class (or the curve, SnCurve::scaled) by f(t). t is the plate
/// thickness (or the effective thickness where IIW defines one), mm; the exponent n comes from
/// the IIW table for the joint type. Errors: t or t_ref not positive, n outside [0, 1].
template <class Scalar>
Result<Scalar> iiw_thickness_factor(Scalar t, Scalar n, Scalar t_ref = Scalar(25)) {
  if (!std::isfinite(t) || !(t > Scalar(0)))
    return make_error(ErrorCode::invalid_argument, "plate thickness must be positive, got ", t);
  if (!std::isfinite(t_ref) || !(t_ref > Scalar(0)))
    return make_error(ErrorCode::invalid_argument, "reference thickness must be positive, got ",
                      t_ref);
  if (!(n >= Scalar(0) && n <= Scalar(1)))
    return make_error(ErrorCode::invalid_argument, "thickness exponent must be in [0, 1], got ", n);
  using std::pow;
  return t > t_ref ? pow(t_ref / t, n) : Scalar(1);
}

}  // namespace flexstress::fatigue
