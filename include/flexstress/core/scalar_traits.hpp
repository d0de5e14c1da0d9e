// Per-Scalar tolerances, so float and double code share one implementation.
#pragma once

#include <limits>

namespace flexstress {

/// Default tolerances for a Scalar type. Specialize for custom scalar types.
template <class Scalar>
struct ScalarTraits {
  static constexpr Scalar epsilon = std::numeric_limits<Scalar>::epsilon();
  /// Relative tolerance for iterative solves (Newton, augmented Lagrangian).
  static constexpr Scalar solve_tolerance = Scalar(1e3) * epsilon;
  /// Below this norm a rotation vector is treated with series expansions.
  static constexpr Scalar small_angle = Scalar(1e-4);
};

template <>
struct ScalarTraits<float> {
  static constexpr float epsilon = std::numeric_limits<float>::epsilon();
  static constexpr float solve_tolerance = 1e2f * epsilon;
  static constexpr float small_angle = 1e-2f;
};

}  // namespace flexstress
