// Linearization about an equilibrium (v = 0): mass and stiffness matrices on the tangent space
// of the constraints, and the natural frequencies of small vibrations (model/equilibrium.hpp's
// linearize builds M and K_eff, this reduces them).
//
// M is the mass matrix; K_eff = d/dx (B^T lambda - Q) by central differences along each
// velocity direction (so geometric stiffness of gravity and joint reactions is included); both
// are projected on an orthonormal basis N of the null space of B (the motions the joints allow):
// K_r = N^T K_eff N, M_r = N^T M N; K_r V = M_r V Lambda gives the frequencies and, as N V, the
// mode shapes in the model's velocity coordinates. For tests and design studies; allocates.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/status.hpp"

namespace flexstress {

struct Linearization {
  Eigen::MatrixXd mass, stiffness;  ///< reduced to the joints' null space
  Eigen::VectorXd frequencies_hz;   ///< ascending; negative eigenvalues give negative values
  /// The mode shapes, column i with frequencies_hz(i), as velocity-coordinate motions of the
  /// whole model (nv rows: each body's translation, rotation in its own frame and modal
  /// coordinates, as d.v), orthonormal in the mass matrix (modes^T M modes = I) and allowed by
  /// the joints (B modes = 0).
  Eigen::MatrixXd modes;
  /// The largest entry of the static residual -Q + B^T lambda at the state linearized about
  /// (each coordinate's force or moment, as d.force): near 0 at a static equilibrium with its
  /// multipliers; far from 0, the state is not one (or d.lambda is not its multipliers), and
  /// mass and stiffness describe no small vibration about it. linearize() sets it.
  double static_residual = 0;
};

/// M and K (nv x nv) projected on an orthonormal basis of the null space of B (the motions the
/// joints allow), K symmetrized, and the frequencies of the reduced pair. A template
/// (FLEXSTRESS_PRECOMPUTE), so that only units that call it instantiate its SVD and eigen
/// solver.
FLEXSTRESS_PRECOMPUTE
Result<Linearization> linearization_on_null_space(const Eigen::MatrixXd& m, Eigen::MatrixXd k,
                                                  const Eigen::MatrixXd& b) {
  const Eigen::Index nv = m.rows();
  k = 0.5 * (k + k.transpose()).eval();
  Eigen::MatrixXd n = Eigen::MatrixXd::Identity(nv, nv);
  if (b.rows() > 0) {
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(b, Eigen::ComputeFullV);
    const double tol =
        1e-9 * std::max(1.0, svd.singularValues().size() ? svd.singularValues()(0) : 1.0);
    Eigen::Index rank = 0;
    for (Eigen::Index i = 0; i < svd.singularValues().size(); ++i)
      if (svd.singularValues()(i) > tol) ++rank;
    n = svd.matrixV().rightCols(nv - rank);
  }
  Linearization lin;
  lin.mass = n.transpose() * m * n;
  lin.stiffness = n.transpose() * k * n;
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(lin.stiffness, lin.mass);
  if (es.info() != Eigen::Success)
    return make_error(ErrorCode::not_converged, "linearize: eigen solve failed");
  lin.frequencies_hz.resize(es.eigenvalues().size());
  for (Eigen::Index i = 0; i < lin.frequencies_hz.size(); ++i) {
    const double l = es.eigenvalues()(i);
    lin.frequencies_hz(i) =
        (l >= 0 ? 1 : -1) * std::sqrt(std::abs(l)) / (2 * 3.14159265358979323846);
  }
  lin.modes = n * es.eigenvectors();  // V^T M_r V = I, so (N V)^T M (N V) = I
  return lin;
}

}  // namespace flexstress
