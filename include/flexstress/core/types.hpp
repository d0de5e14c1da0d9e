// Small fixed-size aliases used across flexstress. Scalar first, sizes next.
#pragma once

#include <Eigen/Core>

namespace flexstress {

template <class Scalar>
using Vec3 = Eigen::Matrix<Scalar, 3, 1>;
template <class Scalar>
using Vec4 = Eigen::Matrix<Scalar, 4, 1>;
template <class Scalar>
using Vec6 = Eigen::Matrix<Scalar, 6, 1>;
template <class Scalar>
using Mat3 = Eigen::Matrix<Scalar, 3, 3>;
template <class Scalar>
using Mat34 = Eigen::Matrix<Scalar, 3, 4>;
template <class Scalar>
using Mat6 = Eigen::Matrix<Scalar, 6, 6>;
template <class Scalar, int N>
using Vec = Eigen::Matrix<Scalar, N, 1>;
template <class Scalar, int Rows, int Cols>
using Mat = Eigen::Matrix<Scalar, Rows, Cols>;

/// Double-precision shorthands for precompute code (the FE kernel works in double).
using Vector3d = Vec3<double>;
using Matrix3d = Mat3<double>;
using VectorXd = Eigen::VectorXd;
using MatrixXd = Eigen::MatrixXd;

/// Index type for nodes, elements and DOFs (Eigen's index type).
using Index = Eigen::Index;

/// Largest absolute entry, 0 for an empty vector (a scene without constraints has nc = 0;
/// Eigen's maxCoeff() asserts on empty input), NaN if any entry is NaN (Eigen's default
/// maxCoeff() may skip NaN, and a tolerance test on it would then pass a NaN state).
template <class Derived>
typename Derived::Scalar max_abs(const Eigen::MatrixBase<Derived>& v) {
  return v.size() == 0 ? typename Derived::Scalar(0)
                       : v.cwiseAbs().template maxCoeff<Eigen::PropagateNaN>();
}

}  // namespace flexstress
