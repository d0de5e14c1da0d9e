// Averaging link (RBE3 in Nastran, a distributing coupling in Abaqus): a reference node that
// follows the weighted least-squares rigid fit of a set of face nodes, adding no stiffness. The
// face stays free to warp, unlike under a rigid link (RBE2), so an interface on a solid mesh does
// not stiffen the body it connects.
//
// With face nodes x_i, weights w_i, the reference at x_ref and B_i = [I, -skew(x_i - x_ref)] (the
// translation of face node i under a rigid motion (u, theta) of the reference), the fit
// minimizes sum_i w_i |u_i - B_i (u, theta)|^2:
//
//   [u_ref; theta_ref] = C u_face,   C = A^-1 [w_1 B_1^T ... w_n B_n^T],   A = sum_i w_i B_i^T B_i.
//
// A force and moment F at the reference reach the face as f = C^T F, i.e. f_i = w_i B_i A^-1 F:
// statically equivalent (sum_i B_i^T f_i = F) and, for equal weights and a force through the
// weighted centroid, shared equally. A is singular if the face nodes are collinear (the rotation
// about their line is not defined).
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/skew.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"

namespace flexstress::fe {

using Mat6d = Mat<double, 6, 6>;

struct AveragingLink {
  Index reference = 0;
  std::vector<Index> face;
  std::vector<double> weights;  ///< one per face node; empty means all 1

  double weight(std::size_t i) const { return weights.empty() ? 1.0 : weights[i]; }
};

/// C (6 x 3n): the reference DOFs (ux, uy, uz, rx, ry, rz) from the face translations (three per
/// face node, in the order of link.face). Fails, naming the link, if the weights are not
/// positive and finite or the face nodes do not define a rotation (fewer than three, or
/// collinear: A's smallest eigenvalue below 1e-10 of its largest, in units where the face's
/// extent is 1).
FLEXSTRESS_PRECOMPUTE
Result<MatrixXd> averaging_fit(const AveragingLink& link, std::size_t index,
                               const std::vector<Vector3d>& nodes) {
  const std::size_t n = link.face.size();
  if (!link.weights.empty() && link.weights.size() != n)
    return make_error(ErrorCode::invalid_argument, "averaging link ", index, " has ",
                      link.weights.size(), " weights for ", n, " face nodes");
  for (std::size_t i = 0; i < n; ++i)
    if (!(link.weight(i) > 0.0) || !std::isfinite(link.weight(i)))
      return make_error(ErrorCode::invalid_argument, "averaging link ", index, ": weight ",
                        link.weight(i), " of face node ", link.face[i],
                        " must be positive and finite");
  const Vector3d x_ref = nodes[static_cast<std::size_t>(link.reference)];
  // Lengths scaled by the face's extent, so that A's conditioning does not depend on units.
  double extent = 0.0;
  for (Index f : link.face)
    extent = std::max(extent, (nodes[static_cast<std::size_t>(f)] - x_ref).norm());
  const double scale = extent > 0.0 ? 1.0 / extent : 1.0;
  Mat6d a = Mat6d::Zero();
  MatrixXd bt(6, 3 * static_cast<Index>(n));  // [w_1 B_1^T ... w_n B_n^T], scaled
  for (std::size_t i = 0; i < n; ++i) {
    Eigen::Matrix<double, 3, 6> b;
    b.leftCols<3>().setIdentity();
    b.rightCols<3>() =
        -skew(Vector3d(scale * (nodes[static_cast<std::size_t>(link.face[i])] - x_ref)));
    a += link.weight(i) * b.transpose() * b;
    bt.middleCols<3>(3 * static_cast<Index>(i)) = link.weight(i) * b.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Mat6d> eig(a, Eigen::EigenvaluesOnly);
  if (n < 3 || !(eig.eigenvalues()(0) > 1e-10 * eig.eigenvalues()(5)))
    return make_error(ErrorCode::invalid_mesh, "averaging link ", index, ": its ", n,
                      " face nodes do not define a rotation of the reference node ", link.reference,
                      " (fewer than three, or all on one line)");
  MatrixXd c = a.ldlt().solve(bt);
  c.bottomRows<3>() *= scale;  // rotations per unit length, back in the mesh's units
  return c;
}

}  // namespace flexstress::fe
