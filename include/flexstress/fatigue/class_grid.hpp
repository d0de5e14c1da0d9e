// Uniform stress classes for class-bin rainflow counting.
//
// The window [lower, upper] is split into `size()` classes of equal width; a sample is replaced
// by the centre of its class. Counting on quantized samples is what on-board load monitors do
// (ranges are then whole multiples of the class width) and what bounds the residue of the
// streaming counter: on N levels, a four-point residue has strictly increasing then strictly
// decreasing ranges, so it never holds more than 2N - 1 reversals (see streaming_rainflow.hpp).
//
// Quantization error: a sample moves by at most half a class width, so a range changes by at
// most one class width. With 64 classes over the stress window that is about 1.6 % of the
// window; the damage of a range Delta changes by about m * width / Delta (m the S-N slope).
#pragma once

#include <cmath>
#include <cstddef>

#include "flexstress/core/assert.hpp"
#include "flexstress/core/status.hpp"

namespace flexstress::fatigue {

/// `size()` classes of equal width covering [lower, upper]. Class i covers
/// [lower + i w, lower + (i + 1) w), the last class also holds `upper`.
template <class Scalar>
class ClassGrid {
 public:
  /// Largest supported number of classes (class indices are int).
  static constexpr int max_classes = 1 << 20;

  /// Errors: non-finite bounds, lower >= upper, classes < 2 or > max_classes.
  static Result<ClassGrid> create(Scalar lower, Scalar upper, int classes) {
    if (!std::isfinite(lower) || !std::isfinite(upper))
      return make_error(ErrorCode::invalid_argument, "class window bounds must be finite, got [",
                        lower, ", ", upper, "]");
    if (!(lower < upper))
      return make_error(ErrorCode::invalid_argument, "class window needs lower < upper, got [",
                        lower, ", ", upper, "]");
    if (classes < 2 || classes > max_classes)
      return make_error(ErrorCode::invalid_argument, "number of classes must be in [2, ",
                        max_classes, "], got ", classes);
    const Scalar width = (upper - lower) / Scalar(classes);
    if (!(width > Scalar(0)))  // the window is too narrow for the Scalar type
      return make_error(ErrorCode::invalid_argument, "class width underflows for window [", lower,
                        ", ", upper, "] and ", classes, " classes");
    return ClassGrid(lower, upper, classes);
  }

  int size() const noexcept { return classes_; }
  Scalar lower() const noexcept { return lower_; }
  Scalar upper() const noexcept { return upper_; }
  /// Class width (stress units).
  Scalar width() const noexcept { return width_; }

  /// True when x lies in the window (false for NaN).
  bool contains(Scalar x) const noexcept { return x >= lower_ && x <= upper_; }

  /// Class of x. Precondition: contains(x) (asserted).
  int index(Scalar x) const {
    FLEXSTRESS_ASSERT(contains(x), "ClassGrid::index: sample outside the class window");
    using std::floor;
    const int i = static_cast<int>(floor((x - lower_) / width_));
    // Rounding can put x == upper (or a value a hair below an edge) one class off the end.
    return i < 0 ? 0 : (i >= classes_ ? classes_ - 1 : i);
  }

  /// Centre of class i, lower + (i + 1/2) w. Precondition: 0 <= i < size().
  Scalar center(int i) const {
    FLEXSTRESS_ASSERT(i >= 0 && i < classes_, "ClassGrid::center: class index out of range");
    return lower_ + (Scalar(i) + Scalar(0.5)) * width_;
  }

  /// The centre of the class of x. Precondition: contains(x).
  Scalar quantize(Scalar x) const { return center(index(x)); }

 private:
  ClassGrid(Scalar lower, Scalar upper, int classes)
      : lower_(lower),
        upper_(upper),
        width_((upper - lower) / Scalar(classes)),
        classes_(classes) {}

  Scalar lower_;
  Scalar upper_;
  Scalar width_;
  int classes_;
};

namespace detail {

/// Checks that every sample of a (finite) history lies in the class window; the message names
/// the first sample outside it.
template <class Scalar>
Status check_in_grid(const Scalar* samples, std::size_t n, const ClassGrid<Scalar>& grid,
                     const char* what) {
  for (std::size_t i = 0; i < n; ++i) {
    if (!grid.contains(samples[i]))
      return make_error(ErrorCode::invalid_argument, what, ": sample ", i, " (", samples[i],
                        ") is outside the class window [", grid.lower(), ", ", grid.upper(), "]");
  }
  return Status::success();
}

}  // namespace detail

}  // namespace flexstress::fatigue
