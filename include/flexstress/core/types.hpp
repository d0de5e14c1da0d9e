// Small fixed-size aliases used across flexstress. Scalar first, sizes next.
#pragma once

#include <algorithm>

#include <Eigen/Core>

/// For the few small helpers of the step's inner loops that the compiler would otherwise call
/// out of line from a large caller (a joint kind's switch): measured on the crane's step.
/// FLEXSTRESS_NOINLINE_FLATTEN: a function kept out of line whose body has every call inlined
/// (the small Eigen operations it is made of): one compact copy that all its callers share.
#if defined(__GNUC__) || defined(__clang__)
#define FLEXSTRESS_ALWAYS_INLINE inline __attribute__((always_inline))
#define FLEXSTRESS_NOINLINE_FLATTEN __attribute__((noinline, flatten))
#else
#define FLEXSTRESS_ALWAYS_INLINE inline
#define FLEXSTRESS_NOINLINE_FLATTEN
#endif

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

#ifndef FLEXSTRESS_MAX_MODES
#define FLEXSTRESS_MAX_MODES 64
#endif
/// Largest mode count of a body whose count is chosen at run time (NModes = Eigen::Dynamic):
/// its per-step vectors and small matrices live in storage bounded by this, so a step with a
/// runtime count allocates nothing either.
inline constexpr int max_runtime_modes = FLEXSTRESS_MAX_MODES;

/// n + k for a compile-time size, Dynamic for a runtime one.
constexpr int size_sum(int n, int k) {
  return n == Eigen::Dynamic ? Eigen::Dynamic : n + k;
}
/// n * k for a compile-time size, Dynamic for a runtime one.
constexpr int size_product(int n, int k) {
  return n == Eigen::Dynamic ? Eigen::Dynamic : n * k;
}
/// The storage bound of a mode-dependent size: the size itself, or its bound at run time.
constexpr int size_bound(int n, int bound) {
  return n == Eigen::Dynamic ? bound : n;
}

/// A matrix of Rows x Cols (either may be Dynamic) stored inline up to MaxRows x MaxCols: the
/// same type as Mat<Scalar, Rows, Cols> when both sizes are fixed.
template <class Scalar, int Rows, int Cols, int MaxRows = Rows, int MaxCols = Cols>
using BoundedMat =
    Eigen::Matrix<Scalar, Rows, Cols,
                  (Rows == 1 && Cols != 1)   ? Eigen::RowMajor
                  : (Cols == 1 && Rows != 1) ? Eigen::ColMajor
                                             : EIGEN_DEFAULT_MATRIX_STORAGE_ORDER_OPTION,
                  MaxRows, MaxCols>;

/// Modal-size types of a body with NModes modes (Eigen::Dynamic: chosen at run time, bounded
/// by max_runtime_modes). R and C give each dimension as a multiple of the mode count plus an
/// offset, e.g. ModalMat<S, N, 0, 3, 3, 0> is 3 x 3N.
template <class Scalar, int NModes>
struct ModalSizes {
  static constexpr int n = NModes, bound = size_bound(NModes, max_runtime_modes);
  static constexpr int nv = size_sum(NModes, 6), nv_bound = bound + 6;
  using VecN = BoundedMat<Scalar, NModes, 1, bound, 1>;
  using RowN = BoundedMat<Scalar, 1, NModes, 1, bound>;
  using MatN = BoundedMat<Scalar, NModes, NModes, bound, bound>;
  using Mat3N = BoundedMat<Scalar, 3, NModes, 3, bound>;
  /// 3 x N with each row contiguous: mode shapes read row by row (a Jacobian row's modal part
  /// is a weighted sum of them).
  using Mat3NRows = Eigen::Matrix<Scalar, 3, NModes, Eigen::RowMajor, 3, bound>;
  using VecV = BoundedMat<Scalar, nv, 1, nv_bound, 1>;
  using RowV = BoundedMat<Scalar, 1, nv, 1, nv_bound>;
  using MatV = BoundedMat<Scalar, nv, nv, nv_bound, nv_bound>;
  using Mat3V = BoundedMat<Scalar, 3, nv, 3, nv_bound>;
};

/// Double-precision shorthands for precompute code (the FE kernel works in double).
using Vector3d = Vec3<double>;
using Matrix3d = Mat3<double>;
using VectorXd = Eigen::VectorXd;
using MatrixXd = Eigen::MatrixXd;

/// Index type for nodes, elements and DOFs (Eigen's index type).
using Index = Eigen::Index;

/// Largest absolute entry, 0 for an empty vector (a model without constraints has nc = 0;
/// Eigen's maxCoeff() asserts on empty input), NaN if any entry is NaN (Eigen's default
/// maxCoeff() may skip NaN, and a tolerance test on it would then pass a NaN state).
/// Two vectorized passes where they can tell: the sum is NaN if an entry is NaN (and also when
/// +inf and -inf both occur or the partial sums overflow: then the slow path answers); without
/// a NaN entry the default maximum is the exact one. Eigen's NaN-propagating maximum goes entry
/// by entry (a step makes a handful of these tests). Eigen's isnan, which holds under
/// -ffinite-math-only too, where sum != sum may be folded to false.
template <class Derived>
typename Derived::Scalar max_abs(const Eigen::MatrixBase<Derived>& v) {
  using Scalar = typename Derived::Scalar;
  if (v.size() == 0) return Scalar(0);
  const Scalar sum = v.sum();
  if (!(Eigen::numext::isnan)(sum)) return v.cwiseAbs().maxCoeff();
  return v.cwiseAbs().template maxCoeff<Eigen::PropagateNaN>();
}

/// dst = src for two vectors of one size: a plain copy, without the resize test and the
/// alignment peeling of Eigen's assignment, which cost more than moving the 20 to 100 entries of
/// the state a step saves and restores a dozen times (and the C library's copy uses the widest
/// vectors the processor has).
template <class Vector>
void copy_same_size(Vector& dst, const Vector& src) {
  eigen_assert(dst.size() == src.size());
  std::copy_n(src.data(), src.size(), dst.data());
}

}  // namespace flexstress
