// Skew-symmetric (cross-product) matrices: skew(a) b = a x b.
#pragma once

#include <Eigen/Core>

#include "flexstress/core/types.hpp"

namespace flexstress {

/// skew(a) with skew(a) b = a x b (the tilde operator of Shabana and of the paper, eq. 10).
template <class Derived>
Mat3<typename Derived::Scalar> skew(const Eigen::MatrixBase<Derived>& a) {
  EIGEN_STATIC_ASSERT_VECTOR_SPECIFIC_SIZE(Derived, 3);
  using S = typename Derived::Scalar;
  Mat3<S> m;
  m << S(0), -a(2), a(1),  //
      a(2), S(0), -a(0),   //
      -a(1), a(0), S(0);
  return m;
}

/// The axial vector of the skew-symmetric part of m: unskew(skew(a)) = a, and for any m,
/// unskew(m) = axial((m - m^T) / 2).
template <class Derived>
Vec3<typename Derived::Scalar> unskew(const Eigen::MatrixBase<Derived>& m) {
  EIGEN_STATIC_ASSERT_MATRIX_SPECIFIC_SIZE(Derived, 3, 3);
  using S = typename Derived::Scalar;
  return Vec3<S>(m(2, 1) - m(1, 2), m(0, 2) - m(2, 0), m(1, 0) - m(0, 1)) * S(0.5);
}

}  // namespace flexstress
