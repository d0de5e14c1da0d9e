// Orthonormalization of a component-mode basis (the paper's "orthonormalized Craig-Bampton
// modes"; Wallrapp, Wiedemann 2003; Rantalainen et al. 2013, sec. 2): solve the reduced
// eigenproblem (K_red - lambda M_red) A_new = 0 with K_red = S^T K S, M_red = S^T M S, and take
// A_ort = S A_new, so A_ort^T M A_ort = I and A_ort^T K A_ort = diag(lambda).
//
// For a floating body the six zero-frequency (rigid) columns are removed: the reduced
// eigenproblem is solved in the M_red-orthogonal complement of the rigid motions (found exactly
// in the basis), so the deformation modes are mass-orthogonal to rigid motion by construction,
// not by the accident of an eigen solver's ordering of near-zero eigenvalues.
#pragma once

#include <cmath>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/fe/rigid_body_modes.hpp"
#include "flexstress/reduction/component_modes.hpp"

namespace flexstress::reduction {

/// Orthonormalized deformation modes in the all-DOF space of the mesh.
struct DeformationModes {
  MatrixXd modes;                   ///< n_all x m, m = r - 6 for a basis of r columns
  VectorXd eigenvalues;             ///< omega^2, ascending
  double mass_residual = 0.0;       ///< || A^T M A - I ||_max
  double stiffness_residual = 0.0;  ///< || A^T K A - diag(lambda) ||_max / lambda_max
};

/// Orthonormalizes `cm` and drops its rigid-body motions. Fails if the basis cannot represent
/// all six rigid motions (an interface that cannot carry them), or if it contains a mechanism
/// (a deformation mode with zero frequency).
FLEXSTRESS_PRECOMPUTE
Result<DeformationModes> orthonormalize(const fe::Mesh& mesh, const ComponentModes& cm)
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  const MatrixXd& s = cm.basis;
  const Index r = s.cols();
  if (r <= 6)
    return make_error(ErrorCode::size_mismatch, "orthonormalization: the basis has ", r,
                      " columns; a floating body needs more than the six rigid motions");
  const MatrixXd ks = cm.model.stiffness_all * s, ms = cm.model.mass_all * s;
  MatrixXd k_red = s.transpose() * ks, m_red = s.transpose() * ms;
  k_red = 0.5 * (k_red + k_red.transpose()).eval();
  m_red = 0.5 * (m_red + m_red.transpose()).eval();
  // Rigid motions in the basis: M-weighted least squares, then check they are represented.
  const MatrixXd rigid =
      fe::rigid_body_modes(mesh, cm.model.dofs, fe::dof_node_centroid(mesh, cm.model.dofs));
  Eigen::LDLT<MatrixXd> m_red_ldlt(m_red);
  if (m_red_ldlt.info() != Eigen::Success || !(m_red_ldlt.vectorD().array() > 0.0).all())
    return make_error(ErrorCode::singular_matrix,
                      "orthonormalization: the reduced mass matrix is singular (linearly "
                      "dependent basis vectors or massless modes)");
  const MatrixXd r_red = m_red_ldlt.solve(s.transpose() * (cm.model.mass_all * rigid));
  const MatrixXd miss = s * r_red - rigid;
  std::string missing;
  for (int j = 0; j < 6; ++j) {
    const double err = std::sqrt(miss.col(j).dot(cm.model.mass_all * miss.col(j)));
    const double ref = std::sqrt(rigid.col(j).dot(cm.model.mass_all * rigid.col(j)));
    if (!(err <= 1e-7 * ref)) missing += (missing.empty() ? "" : ", ") + fe::rigid_mode_name(j);
  }
  if (!missing.empty())
    return make_error(ErrorCode::invalid_argument,
                      "the interface cannot carry all six rigid-body motions (missing: ", missing,
                      "); add interface DOFs (rotations, or more nodes)");
  // Complement: Z with r_red^T M_red Z = 0.
  Eigen::HouseholderQR<MatrixXd> qr(m_red * r_red);
  const MatrixXd q = qr.householderQ();
  const MatrixXd z = q.rightCols(r - 6);
  const MatrixXd kz = z.transpose() * k_red * z, mz = z.transpose() * m_red * z;
  Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> es(0.5 * (kz + kz.transpose()),
                                                        0.5 * (mz + mz.transpose()));
  if (es.info() != Eigen::Success)
    return make_error(ErrorCode::not_converged, "orthonormalization: reduced eigen solve failed");
  DeformationModes out;
  out.eigenvalues = es.eigenvalues();
  const double lmax = out.eigenvalues.cwiseAbs().maxCoeff();
  for (Index i = 0; i < out.eigenvalues.size(); ++i)
    if (!(out.eigenvalues(i) > 1e-10 * lmax))
      return make_error(ErrorCode::singular_matrix, "orthonormalization: deformation mode ", i,
                        " has zero frequency (lambda = ", out.eigenvalues(i),
                        "): the body contains a mechanism");
  out.modes = s * (z * es.eigenvectors());
  const MatrixXd mm = out.modes.transpose() * (cm.model.mass_all * out.modes);
  const MatrixXd kk = out.modes.transpose() * (cm.model.stiffness_all * out.modes);
  out.mass_residual = (mm - MatrixXd::Identity(mm.rows(), mm.cols())).cwiseAbs().maxCoeff();
  out.stiffness_residual =
      (kk - MatrixXd(out.eigenvalues.asDiagonal())).cwiseAbs().maxCoeff() / lmax;
  return out;
}
#else
    ;
#endif

}  // namespace flexstress::reduction

// This header's precompute entry points (core/precompute.hpp).
#define FLEXSTRESS_PRECOMPUTE_REDUCTION_ORTHONORMALIZE(X)              \
  X(8, Result<reduction::DeformationModes>, reduction::orthonormalize, \
    (const fe::Mesh&, const reduction::ComponentModes&))
namespace flexstress {
FLEXSTRESS_PRECOMPUTE_EXTERN(FLEXSTRESS_PRECOMPUTE_REDUCTION_ORTHONORMALIZE)
}  // namespace flexstress
