// Linear static solve of an assembled model: factorize T^T K T once (sparse LDL^T), then solve
// for any number of load cases and prescribed values.
//
// A stiffness matrix that is singular after constraints is reported, not solved: the error says
// which rigid-body motions the supports leave free, or which DOF has no stiffness (a mechanism).
#pragma once

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/fe/assembly.hpp"
#include "flexstress/fe/rigid_body_modes.hpp"

namespace flexstress::fe {

namespace detail {

/// Explains why the constrained stiffness of `model` is singular.
FLEXSTRESS_PRECOMPUTE
Error explain_singular_stiffness(const Mesh& mesh, const AssembledModel& model,
                                 Index bad_free_dof) {
  // Rigid motions restricted to the free DOFs: those with (near) zero strain energy are free.
  // Rotations about the centroid of the supported nodes read naturally ("rotation about z"
  // for a beam pinned at one end); without supports, about the centroid of the mesh.
  Vector3d center = Vector3d::Zero();
  const auto& presc = model.constraints.prescribed_dofs();
  for (Index d : presc) center += mesh.node(model.dofs.node_of(d));
  center = presc.empty() ? dof_node_centroid(mesh, model.dofs)
                         : Vector3d(center / static_cast<double>(presc.size()));
  const MatrixXd r_all = rigid_body_modes(mesh, model.dofs, center);
  const auto& free = model.constraints.free_dofs();
  MatrixXd r(static_cast<Index>(free.size()), 6);
  for (std::size_t i = 0; i < free.size(); ++i) r.row(static_cast<Index>(i)) = r_all.row(free[i]);
  const VectorXd diag = model.stiffness.diagonal();
  std::string free_motions;
  if (r.rows() > 0) {
    const MatrixXd energy = r.transpose() * (model.stiffness * r);
    const MatrixXd scale = r.transpose() * diag.asDiagonal() * r;
    Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> eig;
    // Regularize the scale so that rigid motions with no free DOF at all drop out.
    const MatrixXd b = scale + 1e-30 * MatrixXd::Identity(6, 6) * (1.0 + scale.trace());
    eig.compute(energy, b);
    if (eig.info() == Eigen::Success) {
      for (int k = 0; k < 6; ++k) {
        if (eig.eigenvalues()(k) > 1e-9) continue;
        const VectorXd v = eig.eigenvectors().col(k);
        if ((r * v).norm() < 1e-12 * (1.0 + v.norm())) continue;  // no motion at free DOFs
        free_motions += (free_motions.empty() ? "" : "; ") + describe_rigid_motion(v);
      }
    }
  }
  if (!free_motions.empty())
    return make_error(ErrorCode::singular_matrix,
                      "the stiffness matrix is singular after constraints: the supports leave "
                      "these rigid-body motions free: ",
                      free_motions);
  std::string where =
      bad_free_dof >= 0 ? model.dofs.describe(
                              model.constraints.free_dofs()[static_cast<std::size_t>(bad_free_dof)])
                        : std::string("an unknown DOF");
  return make_error(ErrorCode::singular_matrix,
                    "the stiffness matrix is singular after constraints: a mechanism at ", where,
                    " (no stiffness against that motion; check element connectivity and "
                    "rotational DOFs that no element resists)");
}

}  // namespace detail

class StaticSolver {
 public:
  /// Factorizes the constrained stiffness of `model` (built from `mesh`). Fails with an
  /// explanation if it is singular or indefinite. The solver keeps a reference to `model`,
  /// which must outlive it.
  FLEXSTRESS_PRECOMPUTE
  static Result<StaticSolver> factorize(const Mesh& mesh, const AssembledModel& model);

  /// Free-DOF displacements for a free-DOF load.
  FLEXSTRESS_PRECOMPUTE
  VectorXd solve_free(const VectorXd& f_free) const;

  /// All-DOF displacements for an all-DOF load and prescribed values.
  FLEXSTRESS_PRECOMPUTE
  VectorXd solve(const VectorXd& f_all, const VectorXd& prescribed_values) const;
  /// All-DOF displacements with the prescribed values of the boundary conditions.
  FLEXSTRESS_PRECOMPUTE
  VectorXd solve(const VectorXd& f_all) const;

  const AssembledModel& model() const { return *model_; }

 private:
  const AssembledModel* model_ = nullptr;
  std::unique_ptr<Eigen::SimplicialLDLT<SparseMatrixd>> ldlt_;  // Eigen solvers do not move
};

#if FLEXSTRESS_PRECOMPUTE_BODIES
template <class>
Result<StaticSolver> StaticSolver::factorize(const Mesh& mesh, const AssembledModel& model) {
  StaticSolver s;
  s.model_ = &model;
  const SparseMatrixd& k = model.stiffness;
  if (k.rows() == 0)
    return make_error(ErrorCode::invalid_argument, "the model has no free DOFs to solve for");
  // A DOF with exactly zero stiffness is a mechanism the factorization may not notice.
  const VectorXd diag = k.diagonal();
  for (Index i = 0; i < diag.size(); ++i)
    if (!(diag(i) > 0.0)) return detail::explain_singular_stiffness(mesh, model, i);
  s.ldlt_ = std::make_unique<Eigen::SimplicialLDLT<SparseMatrixd>>();
  Eigen::SimplicialLDLT<SparseMatrixd>& ldlt = *s.ldlt_;
  ldlt.compute(k);
  if (ldlt.info() != Eigen::Success) return detail::explain_singular_stiffness(mesh, model, -1);
  // Pivots relative to the diagonal they came from: a pivot lost to cancellation means a
  // (near) singular matrix; a negative one means K is not positive semi-definite.
  const VectorXd d = ldlt.vectorD();
  // P A P^T = L D L^T: permuted position k holds original DOF P^-1(k).
  const Eigen::PermutationMatrix<Eigen::Dynamic> pinv = ldlt.permutationP().inverse();
  for (Index i = 0; i < d.size(); ++i) {
    const Index original = pinv.indices()(i);
    if (!(d(i) > 1e-11 * diag(original)))
      return detail::explain_singular_stiffness(mesh, model, original);
  }
  return s;
}

template <class>
VectorXd StaticSolver::solve_free(const VectorXd& f_free) const {
  return ldlt_->solve(f_free);
}

template <class>
VectorXd StaticSolver::solve(const VectorXd& f_all, const VectorXd& prescribed_values) const {
  const auto& ct = model_->constraints;
  const VectorXd rhs =
      ct.free_to_all().transpose() * f_all - model_->stiffness_prescribed * prescribed_values;
  return ct.expand(ldlt_->solve(rhs), prescribed_values);
}

template <class>
VectorXd StaticSolver::solve(const VectorXd& f_all) const {
  return solve(f_all, model_->constraints.prescribed_values());
}
#endif

}  // namespace flexstress::fe

// This header's precompute entry points (core/precompute.hpp).
#define FLEXSTRESS_PRECOMPUTE_FE_STATIC_SOLVER(X)                                    \
  X(11, Result<fe::StaticSolver>, fe::StaticSolver::factorize,                       \
    (const fe::Mesh&, const fe::AssembledModel&))                                    \
  X(11, VectorXd, fe::StaticSolver::solve_free, (const VectorXd&) const)             \
  X(11, VectorXd, fe::StaticSolver::solve, (const VectorXd&, const VectorXd&) const) \
  X(11, VectorXd, fe::StaticSolver::solve, (const VectorXd&) const)
namespace flexstress {
FLEXSTRESS_PRECOMPUTE_EXTERN(FLEXSTRESS_PRECOMPUTE_FE_STATIC_SOLVER)
}  // namespace flexstress
