// Scalar measures of a stress state given as a Voigt vector (xx, yy, zz, xy, yz, zx), the order
// used by every flexstress stress (hex8.hpp): the symmetric tensor, von Mises equivalent stress
// and principal stresses with their directions.
//
// All functions are templated on the Scalar of the Voigt vector, work in any consistent unit
// (Pa in the FE kernel) and any frame (the principal directions come out in the frame of the
// input), use fixed-size storage only and never allocate: they may run in a time step.
#pragma once

#include <cmath>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include "flexstress/core/types.hpp"

namespace flexstress::fe {

/// The symmetric 3x3 tensor of a Voigt stress (xx, yy, zz, xy, yz, zx).
template <class Derived>
Mat3<typename Derived::Scalar> stress_tensor(const Eigen::MatrixBase<Derived>& s) {
  EIGEN_STATIC_ASSERT_VECTOR_SPECIFIC_SIZE(Derived, 6);
  Mat3<typename Derived::Scalar> m;
  m << s(0), s(3), s(5),  //
      s(3), s(1), s(4),   //
      s(5), s(4), s(2);
  return m;
}

/// Von Mises equivalent stress
/// sqrt(((sxx - syy)^2 + (syy - szz)^2 + (szz - sxx)^2) / 2 + 3 (sxy^2 + syz^2 + szx^2)),
/// i.e. sqrt(3 J2) (Hill, The Mathematical Theory of Plasticity, 1950, ch. 2). Uniaxial stress s
/// gives |s|, pure shear tau gives sqrt(3) |tau|, hydrostatic stress gives 0.
template <class Derived>
typename Derived::Scalar von_mises(const Eigen::MatrixBase<Derived>& s) {
  EIGEN_STATIC_ASSERT_VECTOR_SPECIFIC_SIZE(Derived, 6);
  using S = typename Derived::Scalar;
  const S a = s(0) - s(1), b = s(1) - s(2), c = s(2) - s(0);
  const S shear = s(3) * s(3) + s(4) * s(4) + s(5) * s(5);
  return std::sqrt(S(0.5) * (a * a + b * b + c * c) + S(3) * shear);
}

/// Principal stresses in descending order (values(0) = s1 >= s2 >= s3) and their unit
/// directions as the columns of a right-handed rotation matrix (same frame as the input).
template <class Scalar>
struct PrincipalStresses {
  Vec3<Scalar> values = Vec3<Scalar>::Zero();
  Mat3<Scalar> directions = Mat3<Scalar>::Identity();
};

/// Principal stresses of a Voigt stress: eigenvalues and eigenvectors of the symmetric tensor
/// (Eigen's iterative self-adjoint solver, accurate also for repeated principal values).
/// Directions of repeated principal values are any orthonormal basis of their eigenspace.
template <class Derived>
PrincipalStresses<typename Derived::Scalar> principal_stresses(
    const Eigen::MatrixBase<Derived>& s) {
  EIGEN_STATIC_ASSERT_VECTOR_SPECIFIC_SIZE(Derived, 6);
  using S = typename Derived::Scalar;
  Eigen::SelfAdjointEigenSolver<Mat3<S>> es(stress_tensor(s), Eigen::ComputeEigenvectors);
  PrincipalStresses<S> p;
  for (int k = 0; k < 3; ++k) {  // the solver sorts ascending; we want descending
    p.values(k) = es.eigenvalues()(2 - k);
    p.directions.col(k) = es.eigenvectors().col(2 - k);
  }
  // Right-handed: the third direction is the cross product of the first two.
  p.directions.col(2) = p.directions.col(0).cross(p.directions.col(1));
  return p;
}

}  // namespace flexstress::fe
