// Prescribed motions s(t) for drivers and moving grounds: value, rate and acceleration.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "flexstress/core/status.hpp"

namespace flexstress {

template <class Scalar>
struct MotionValue {
  Scalar value = Scalar(0), rate = Scalar(0), acceleration = Scalar(0);
};

/// s(t) = s0 + v t + a t^2 / 2.
template <class Scalar>
struct PolynomialLaw {
  Scalar s0 = Scalar(0), v = Scalar(0), a = Scalar(0);
  MotionValue<Scalar> operator()(Scalar t) const {
    return {s0 + v * t + a * t * t / 2, v + a * t, a};
  }
};

/// Any callable t -> MotionValue<Scalar> (a lambda, a functor): wraps it as a law type.
template <class Scalar, class F>
struct FunctionLaw {
  F f;
  MotionValue<Scalar> operator()(Scalar t) const { return f(t); }
};
template <class Scalar, class F>
FunctionLaw<Scalar, F> function_law(F f) {
  return FunctionLaw<Scalar, F>{std::move(f)};
}

/// How a table law passes through its rows.
enum class TableInterpolation : std::uint8_t {
  /// A cubic spline with zero slope at both ends ("clamped"): the motion passes through the
  /// inner rows without stopping, its acceleration continuous between the first and the last
  /// row. It starts and ends at rest but with an acceleration: at the first and last rows the
  /// acceleration jumps from and to zero (a two-row table is s0 + (s1 - s0)(3u^2 - 2u^3), whose
  /// acceleration is 6 (s1 - s0) / T^2 at its start), and between rows of equal value the spline
  /// overshoots them.
  spline,
  /// Point to point: the motion stops at every row, and between two rows follows the quintic
  /// s_i + (s_i+1 - s_i)(10u^3 - 15u^4 + 6u^5), u = (t - t_i) / (t_i+1 - t_i), whose rate and
  /// acceleration vanish at both rows: no jump anywhere, no overshoot (the minimum-jerk move of
  /// robot and crane motion planning; Flash and Hogan, J. Neurosci. 5, 1985). Its rate peaks
  /// at 1.875 and its acceleration at 10 / sqrt(3) = 5.77 times a segment's mean rate and
  /// (s_i+1 - s_i) / (t_i+1 - t_i)^2.
  rest_to_rest,
};

/// A table (t_i, s_i) of a driver's or the ground's motion, interpolated as `TableInterpolation`
/// says (a clamped cubic spline by default). At rest at the first and last row, so a run can
/// start from static equilibrium; outside the table the end values are held. Evaluation does
/// not allocate (binary search).
template <class Scalar>
class TableLaw {
 public:
  TableLaw() = default;

  /// Fails for fewer than two points, non-increasing times or non-finite values (naming the
  /// row, counted from 1).
  static Result<TableLaw> create(const std::vector<double>& t, const std::vector<double>& s,
                                 TableInterpolation interpolation = TableInterpolation::spline) {
    if (t.size() != s.size())
      return make_error(ErrorCode::invalid_argument, "table law: ", t.size(), " times but ",
                        s.size(), " values");
    if (t.size() < 2)
      return make_error(ErrorCode::invalid_argument, "table law: needs at least two rows, got ",
                        t.size());
    for (std::size_t i = 0; i < t.size(); ++i) {
      if (!std::isfinite(t[i]) || !std::isfinite(s[i]))
        return make_error(ErrorCode::invalid_argument, "table law: row ", i + 1, " is not finite");
      if (i > 0 && !(t[i] > t[i - 1]))
        return make_error(ErrorCode::invalid_argument, "table law: time at row ", i + 1, " (", t[i],
                          ") does not increase (previous ", t[i - 1], ")");
    }
    TableLaw law;
    law.t_.assign(t.begin(), t.end());
    law.s_.assign(s.begin(), s.end());
    law.interpolation_ = interpolation;
    if (interpolation == TableInterpolation::rest_to_rest) return law;
    // Second derivatives m_i: the tridiagonal system of the clamped cubic spline
    // (de Boor, A Practical Guide to Splines, ch. IV), solved by the Thomas algorithm.
    const std::size_t n = t.size();
    std::vector<double> lo(n, 0.0), di(n, 0.0), up(n, 0.0), rhs(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      const double hl = i > 0 ? t[i] - t[i - 1] : 0.0, hr = i + 1 < n ? t[i + 1] - t[i] : 0.0;
      const double sl = i > 0 ? (s[i] - s[i - 1]) / hl : 0.0;  // zero end slope
      const double sr = i + 1 < n ? (s[i + 1] - s[i]) / hr : 0.0;
      lo[i] = hl;
      di[i] = 2.0 * (hl + hr);
      up[i] = hr;
      rhs[i] = 6.0 * (sr - sl);
    }
    for (std::size_t i = 1; i < n; ++i) {
      const double f = lo[i] / di[i - 1];
      di[i] -= f * up[i - 1];
      rhs[i] -= f * rhs[i - 1];
    }
    std::vector<double> m(n, 0.0);
    m[n - 1] = rhs[n - 1] / di[n - 1];
    for (std::size_t i = n - 1; i-- > 0;) m[i] = (rhs[i] - up[i] * m[i + 1]) / di[i];
    law.m_ = std::move(m);
    return law;
  }

  /// A default-constructed (empty) table is s = 0 at all times.
  MotionValue<Scalar> operator()(Scalar time) const {
    if (t_.empty()) return {};
    const double tt = static_cast<double>(time);
    if (tt <= t_.front()) return {static_cast<Scalar>(s_.front()), Scalar(0), Scalar(0)};
    if (tt >= t_.back()) return {static_cast<Scalar>(s_.back()), Scalar(0), Scalar(0)};
    const std::size_t i =
        static_cast<std::size_t>(std::upper_bound(t_.begin(), t_.end(), tt) - t_.begin()) - 1;
    const double h = t_[i + 1] - t_[i], a = (t_[i + 1] - tt) / h, b = (tt - t_[i]) / h;
    if (interpolation_ == TableInterpolation::rest_to_rest) {
      const double ds = s_[i + 1] - s_[i], u = b, u2 = u * u;
      const double value = s_[i] + ds * u2 * u * (10 - 15 * u + 6 * u2);
      const double rate = ds / h * 30 * u2 * (1 - 2 * u + u2);
      const double acc = ds / (h * h) * 60 * u * (1 - 3 * u + 2 * u2);
      return {static_cast<Scalar>(value), static_cast<Scalar>(rate), static_cast<Scalar>(acc)};
    }
    const double m0 = m_[i], m1 = m_[i + 1];
    const double value =
        a * s_[i] + b * s_[i + 1] + ((a * a * a - a) * m0 + (b * b * b - b) * m1) * h * h / 6;
    const double rate =
        (s_[i + 1] - s_[i]) / h + ((1 - 3 * a * a) * m0 + (3 * b * b - 1) * m1) * h / 6;
    const double acc = a * m0 + b * m1;
    return {static_cast<Scalar>(value), static_cast<Scalar>(rate), static_cast<Scalar>(acc)};
  }

  /// The row interval (its first row, counted from 1) that steps of size h follow worst, if
  /// they cannot follow it, else 0: over it the law's mean rate times h, or its acceleration at
  /// one of its rows (point to point: its peak within the segment) times h^2, exceeds the
  /// table's whole range of values. A jump between close
  /// rows gives rates and accelerations that grow as 1/dt and 1/dt^2 there; a sine of
  /// frequency w is flagged when w h > sqrt(2), fewer than about 4.4 steps per period.
  std::size_t row_too_fast(double h) const {
    if (t_.size() < 2) return 0;
    const auto [lo, hi] = std::minmax_element(s_.begin(), s_.end());
    const double range = *hi - *lo;
    std::size_t worst = 0;
    double worst_move = range;  // what a step may move at most
    for (std::size_t i = 0; i + 1 < t_.size(); ++i) {
      const double rate = (s_[i + 1] - s_[i]) / (t_[i + 1] - t_[i]);
      const double acc = interpolation_ == TableInterpolation::spline
                             ? std::max(std::abs(m_[i]), std::abs(m_[i + 1]))
                             : kRestToRestPeakAcceleration * std::abs(s_[i + 1] - s_[i]) /
                                   ((t_[i + 1] - t_[i]) * (t_[i + 1] - t_[i]));
      const double move = std::max(std::abs(rate) * h, acc * h * h);
      if (move > worst_move) {
        worst = i + 1;
        worst_move = move;
      }
    }
    return worst;
  }

  double start_time() const { return t_.front(); }
  TableInterpolation interpolation() const { return interpolation_; }
  /// The rows it was made from (create(times(), values(), interpolation()) makes the same law).
  const std::vector<double>& times() const { return t_; }
  const std::vector<double>& values() const { return s_; }
  double end_time() const { return t_.back(); }

 private:
  /// 10 / sqrt(3): the quintic's largest |s''| over (s1 - s0) / T^2, at u = 1/2 -+ sqrt(3)/6.
  static constexpr double kRestToRestPeakAcceleration = 5.773502691896258;
  std::vector<double> t_, s_, m_;  // m_: the spline's second derivatives at the rows
  TableInterpolation interpolation_ = TableInterpolation::spline;
};

}  // namespace flexstress
