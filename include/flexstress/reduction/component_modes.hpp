// Component mode synthesis bases: Craig-Bampton and Craig-Chang.
//
// Craig-Bampton (Craig & Bampton, AIAA J. 6 (1968) 1313-1319): DOFs split into interior o and
// interface a. Fixed-interface modes solve (K_oo - lambda M_oo) phi = 0 (lowest n kept);
// constraint modes Psi = [-K_oo^-1 K_oa; I] give the static response to a unit displacement of
// each interface DOF with the others fixed; S = [[Phi_o; 0], Psi]. With n = 0 it is Guyan
// reduction.
//
// Craig-Chang (Craig & Chang, "Free-interface methods of substructure coupling for dynamic
// analysis", AIAA J. 14 (1976); Craig, Structural Dynamics, sec. 19): free-free modes (the
// rigid ones mass-normalized, A_R^T M A_R = I) and inertia-relief attachment modes. A unit force
// at an interface DOF is made self-equilibrated by the inertia forces of the rigid acceleration it
// causes, f_e = (I - M A_R A_R^T) f_a, solved statically on a statically determinate support (six
// DOFs chosen by pivoted QR of the rigid modes, so no reaction arises), and cleaned of rigid
// motion, x_e = (I - A_R A_R^T M) x. S = [A_R, A_omega, A_s].
//
// Both bases live in the all-DOF space of the mesh (rigid-link slaves included), so every node
// has its mode shape. Here the body is free-floating: supports are not part of a superelement.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/QR>
#include <Eigen/SVD>
#include <Eigen/SparseCholesky>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/fe/assembly.hpp"
#include "flexstress/fe/eigen_solver.hpp"
#include "flexstress/fe/rigid_body_modes.hpp"
#include "flexstress/fe/static_solver.hpp"
#include "flexstress/reduction/interface.hpp"
#include "flexstress/reduction/reduction_method.hpp"

namespace flexstress::reduction {

/// How many dynamic modes (fixed-interface for Craig-Bampton, elastic free-free for Craig-Chang)
/// a basis keeps: a count, or all below a cut-off frequency (whichever is set; count wins).
struct ModeSelection {
  int count = -1;                   ///< >= 0: keep this many
  double cutoff_frequency_hz = -1;  ///< > 0 and count < 0: keep all below this frequency
  /// Upper bound on the number of modes computed when selecting by cut-off.
  int max_count_for_cutoff = 200;
};

/// A reduction basis in the all-DOF space, before orthonormalization.
struct ComponentModes {
  ReductionMethod method = ReductionMethod::craig_bampton;
  fe::AssembledModel model;           ///< the free-floating body: DOF map, links, K and M
  MatrixXd basis;                     ///< n_all x r, columns as documented per method
  Index num_dynamic = 0;              ///< fixed-interface (CB) or elastic free-free (CC) modes
  Index num_static = 0;               ///< constraint (CB) or attachment (CC) modes
  Index num_rigid = 0;                ///< CC: the six rigid modes first; CB: 0
  VectorXd dynamic_eigenvalues;       ///< omega^2 of the dynamic modes
  std::vector<Index> interface_dofs;  ///< all-DOF indices of the interface DOFs, in basis order
};

namespace detail {

/// All-DOF indices of the interface DOFs, validated.
FLEXSTRESS_PRECOMPUTE
Result<std::vector<Index>> interface_dof_list(const fe::Mesh& mesh, const fe::DofMap& dofs,
                                              const std::vector<InterfaceNode>& nodes) {
  std::vector<Index> list;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const InterfaceNode& in = nodes[i];
    if (in.node < 0 || in.node >= mesh.num_nodes())
      return make_error(ErrorCode::invalid_argument, "interface node ", in.node,
                        " does not exist (the mesh has ", mesh.num_nodes(), " nodes)");
    if (dofs.num_node_dofs(in.node) == 0)
      return make_error(ErrorCode::invalid_argument, "interface node ", in.node,
                        " is not used by any element");
    for (int c = 0; c < 6; ++c) {
      if (!in.dofs[static_cast<std::size_t>(c)]) continue;
      const Index d = dofs.dof(in.node, c);
      if (d < 0) {
        if (c >= 3) continue;  // a solid node has no rotations: use a spider for them
        return make_error(ErrorCode::invalid_argument, "interface node ", in.node, " lacks DOF ",
                          fe::dof_component_name(c));
      }
      if (std::find(list.begin(), list.end(), d) != list.end())
        return make_error(ErrorCode::invalid_argument, "interface DOF ", dofs.describe(d),
                          " is listed twice");
      list.push_back(d);
    }
  }
  return list;
}

/// Fails unless the interface DOFs can hold all six rigid motions of the body (otherwise the
/// body would be a mechanism on its interface), naming the motions it cannot hold.
FLEXSTRESS_PRECOMPUTE
Status check_interface_holds_rigid_motion(const fe::Mesh& mesh, const fe::DofMap& dofs,
                                          const std::vector<Index>& interface_dofs) {
  Vector3d center = Vector3d::Zero();
  for (Index d : interface_dofs) center += mesh.node(dofs.node_of(d));
  if (!interface_dofs.empty()) center /= static_cast<double>(interface_dofs.size());
  const MatrixXd rigid = fe::rigid_body_modes(mesh, dofs, center);
  MatrixXd ri(static_cast<Index>(interface_dofs.size()), 6);
  for (std::size_t i = 0; i < interface_dofs.size(); ++i)
    ri.row(static_cast<Index>(i)) = rigid.row(interface_dofs[i]);
  Eigen::JacobiSVD<MatrixXd> svd(ri, Eigen::ComputeFullV);
  const VectorXd sv = svd.singularValues();
  const double scale = std::max(1.0, ri.cwiseAbs().maxCoeff());
  std::string missing;
  for (int k = 0; k < 6; ++k) {
    const double sigma = k < sv.size() ? sv(k) : 0.0;
    if (sigma > 1e-9 * scale) continue;
    missing += (missing.empty() ? "" : "; ") + fe::describe_rigid_motion(svd.matrixV().col(k));
  }
  if (!missing.empty())
    return make_error(ErrorCode::invalid_argument,
                      "the interface cannot carry all six rigid-body motions (missing: ", missing,
                      "); add interface DOFs (rotations, or more nodes)");
  return Status::success();
}

FLEXSTRESS_PRECOMPUTE
int modes_to_keep(const ModeSelection& sel, Index available) {
  if (sel.count >= 0) return sel.count;
  if (sel.cutoff_frequency_hz > 0)
    return static_cast<int>(std::min<Index>(sel.max_count_for_cutoff, available));
  return 0;
}

/// Drops the modes above the cut-off (when selecting by frequency).
FLEXSTRESS_PRECOMPUTE
void apply_cutoff(const ModeSelection& sel, fe::EigenSolution& s) {
  if (sel.count >= 0 || !(sel.cutoff_frequency_hz > 0)) return;
  const double w = 2.0 * 3.14159265358979323846 * sel.cutoff_frequency_hz;
  Index keep = 0;
  while (keep < s.eigenvalues.size() && s.eigenvalues(keep) <= w * w) ++keep;
  s.eigenvalues.conservativeResize(keep);
  s.vectors.conservativeResize(Eigen::NoChange, keep);
}

}  // namespace detail

/// Craig-Bampton basis of the free-floating body `mesh` with the given interface.
/// Errors: interface nodes that do not exist or lack DOFs, an empty interface, more
/// fixed-interface modes than interior DOFs, a singular interior block (a part of the body that
/// the interface does not hold, naming the DOF).
FLEXSTRESS_PRECOMPUTE
Result<ComponentModes> craig_bampton(const fe::Mesh& mesh,
                                     const std::vector<InterfaceNode>& interface,
                                     const ModeSelection& modes, const fe::MassOptions& mass = {},
                                     const fe::EigenOptions& eigen = {})
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  auto dofs = fe::DofMap::build(mesh);
  if (!dofs) return dofs.error();
  auto list = detail::interface_dof_list(mesh, *dofs, interface);
  if (!list) return list.error();
  if (list->empty())
    return make_error(ErrorCode::invalid_argument,
                      "Craig-Bampton needs at least one interface DOF (use Craig-Chang for a "
                      "body without interface)");
  if (Status s = detail::check_interface_holds_rigid_motion(mesh, *dofs, *list); !s)
    return s.error();
  fe::BoundaryConditions bc;
  for (Index d : *list) bc.fix(dofs->node_of(d), dofs->component_of(d));
  auto assembled = fe::assemble(mesh, bc, mass);
  if (!assembled) return assembled.error();
  const fe::AssembledModel& am = *assembled;
  const Index n_o = am.constraints.num_free(), n_a = am.constraints.num_prescribed();
  ComponentModes cm;
  // Fixed-interface modes.
  const int want = detail::modes_to_keep(modes, n_o);
  if (want > n_o)
    return make_error(ErrorCode::size_mismatch, "Craig-Bampton: asked for ", want,
                      " fixed-interface modes but the interior has only ", n_o, " DOFs");
  fe::EigenSolution fixed;
  if (want > 0) {
    fe::EigenOptions eo = eigen;
    eo.num_modes = want;
    auto s = fe::solve_eigen(am.stiffness, am.mass, eo);
    if (!s)
      return make_error(s.error().code, "Craig-Bampton fixed-interface modes: ", s.error().message);
    fixed = std::move(*s);
    detail::apply_cutoff(modes, fixed);
  }
  // Constraint modes: K_oo Psi_o = -K_oa (one factorization, n_a right-hand sides).
  auto solver = fe::StaticSolver::factorize(mesh, am);
  if (!solver)
    return make_error(ErrorCode::singular_matrix,
                      "Craig-Bampton: the interior block K_oo is singular with the interface "
                      "fixed (",
                      solver.error().message, ")");
  const MatrixXd rhs = -MatrixXd(am.stiffness_prescribed);
  MatrixXd psi_o(n_o, n_a);
  for (Index j = 0; j < n_a; ++j) psi_o.col(j) = solver->solve_free(rhs.col(j));
  const fe::SparseMatrixd& t = am.constraints.free_to_all();
  const fe::SparseMatrixd& g = am.constraints.prescribed_to_all();
  cm.num_dynamic = fixed.eigenvalues.size();
  cm.num_static = n_a;
  cm.basis.resize(am.dofs.size(), cm.num_dynamic + n_a);
  if (cm.num_dynamic > 0) cm.basis.leftCols(cm.num_dynamic) = t * fixed.vectors;
  cm.basis.rightCols(n_a) = t * psi_o + MatrixXd(g);
  cm.dynamic_eigenvalues = fixed.eigenvalues;
  cm.interface_dofs = am.constraints.prescribed_dofs();
  // The body itself is free-floating: reassemble without the interface supports.
  auto free_body = fe::assemble(mesh, {}, mass);
  if (!free_body) return free_body.error();
  cm.model = std::move(*free_body);
  cm.method = ReductionMethod::craig_bampton;
  return cm;
}
#else
    ;
#endif

/// Six DOFs (free, not rigid-link slaves) that support the body statically determinately:
/// chosen by column-pivoted QR of the rigid modes restricted to the free DOFs.
FLEXSTRESS_PRECOMPUTE
Result<fe::BoundaryConditions> statically_determinate_support(const fe::AssembledModel& m,
                                                              const MatrixXd& rigid_all) {
  const auto& free = m.constraints.free_dofs();
  MatrixXd rt(6, static_cast<Index>(free.size()));
  for (std::size_t i = 0; i < free.size(); ++i)
    rt.col(static_cast<Index>(i)) = rigid_all.row(free[i]).transpose();
  Eigen::ColPivHouseholderQR<MatrixXd> qr(rt);
  if (qr.rank() < 6)
    return make_error(ErrorCode::singular_matrix,
                      "the body's free DOFs cannot represent all six rigid-body motions");
  fe::BoundaryConditions bc;
  for (int k = 0; k < 6; ++k) {
    const Index d = free[static_cast<std::size_t>(qr.colsPermutation().indices()(k))];
    bc.fix(m.dofs.node_of(d), m.dofs.component_of(d));
  }
  return bc;
}

/// Craig-Chang basis (free-free modes + inertia-relief attachment modes) of the free-floating
/// body. An empty interface is allowed: then the basis is the free-free modes alone.
FLEXSTRESS_PRECOMPUTE
Result<ComponentModes> craig_chang(const fe::Mesh& mesh,
                                   const std::vector<InterfaceNode>& interface,
                                   const ModeSelection& modes, const fe::MassOptions& mass = {},
                                   const fe::EigenOptions& eigen = {})
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  auto assembled = fe::assemble(mesh, {}, mass);
  if (!assembled) return assembled.error();
  ComponentModes cm;
  cm.model = std::move(*assembled);
  const fe::AssembledModel& am = cm.model;
  auto list = detail::interface_dof_list(mesh, am.dofs, interface);
  if (!list) return list.error();
  const Index n_free = am.constraints.num_free();
  const int want = detail::modes_to_keep(modes, n_free - 6);
  if (want + 6 > n_free)
    return make_error(ErrorCode::size_mismatch, "Craig-Chang: asked for ", want,
                      " elastic modes but the body has only ", n_free - 6);
  if (want == 0 && list->empty())
    return make_error(ErrorCode::invalid_argument,
                      "Craig-Chang: no interface and no free-free modes: the basis would hold "
                      "only rigid motion");
  const fe::SparseMatrixd& t = am.constraints.free_to_all();
  // Rigid modes, mass-normalized (A_R^T M A_R = I) in the free coordinates.
  const MatrixXd rigid_all =
      fe::rigid_body_modes(mesh, am.dofs, fe::dof_node_centroid(mesh, am.dofs));
  const auto& free = am.constraints.free_dofs();
  MatrixXd ar(n_free, 6);
  for (std::size_t i = 0; i < free.size(); ++i)
    ar.row(static_cast<Index>(i)) = rigid_all.row(free[i]);
  {
    const MatrixXd mr = ar.transpose() * (am.mass * ar);
    Eigen::SelfAdjointEigenSolver<MatrixXd> es(mr);
    if (es.info() != Eigen::Success || es.eigenvalues().minCoeff() <= 0.0)
      return make_error(ErrorCode::singular_matrix,
                        "Craig-Chang: the body's mass cannot represent all six rigid motions");
    ar = ar * es.operatorInverseSqrt();
  }
  // Elastic free-free modes: the lowest 6 + want, minus the rigid ones.
  fe::EigenSolution elastic;
  if (want > 0) {
    fe::EigenOptions eo = eigen;
    eo.num_modes = 6 + want;
    auto s = fe::solve_eigen(am.stiffness, am.mass, eo);
    if (!s) return make_error(s.error().code, "Craig-Chang free-free modes: ", s.error().message);
    elastic.eigenvalues = s->eigenvalues.tail(want);
    elastic.vectors = s->vectors.rightCols(want);
    detail::apply_cutoff(modes, elastic);
  }
  // Inertia-relief attachment modes.
  const Index n_a = static_cast<Index>(list->size());
  MatrixXd attach(n_free, n_a);
  if (n_a > 0) {
    auto support = statically_determinate_support(am, rigid_all);
    if (!support) return support.error();
    auto supported = fe::assemble(mesh, *support, mass);
    if (!supported) return supported.error();
    auto solver = fe::StaticSolver::factorize(mesh, *supported);
    if (!solver)
      return make_error(ErrorCode::singular_matrix,
                        "Craig-Chang: the body is singular on a statically determinate support (",
                        solver.error().message, ")");
    for (Index j = 0; j < n_a; ++j) {
      // Unit force at the interface DOF, as a load on the free coordinates: T^T e_d.
      VectorXd fa_all = VectorXd::Zero(am.dofs.size());
      fa_all((*list)[static_cast<std::size_t>(j)]) = 1.0;
      const VectorXd fa = t.transpose() * fa_all;
      const VectorXd fe_ = fa - am.mass * (ar * (ar.transpose() * fa));  // self-equilibrated
      // The free coordinates of `am` are the all-DOF values of the non-slave DOFs, so placing
      // the load there gives the same generalized load on the supported model; its supports
      // carry no reaction because the load is self-equilibrated.
      VectorXd f_all = VectorXd::Zero(am.dofs.size());
      for (std::size_t i = 0; i < free.size(); ++i) f_all(free[i]) = fe_(static_cast<Index>(i));
      const VectorXd x_all = solver->solve(f_all);
      VectorXd x(n_free);
      for (std::size_t i = 0; i < free.size(); ++i) x(static_cast<Index>(i)) = x_all(free[i]);
      attach.col(j) = x - ar * (ar.transpose() * (am.mass * x));  // remove rigid motion
    }
  }
  cm.num_rigid = 6;
  cm.num_dynamic = elastic.eigenvalues.size();
  cm.num_static = n_a;
  cm.basis.resize(am.dofs.size(), 6 + cm.num_dynamic + n_a);
  cm.basis.leftCols(6) = t * ar;
  if (cm.num_dynamic > 0) cm.basis.middleCols(6, cm.num_dynamic) = t * elastic.vectors;
  if (n_a > 0) cm.basis.rightCols(n_a) = t * attach;
  cm.dynamic_eigenvalues = elastic.eigenvalues;
  cm.interface_dofs = *list;
  cm.method = ReductionMethod::craig_chang;
  return cm;
}
#else
    ;
#endif

}  // namespace flexstress::reduction

// This header's precompute entry points (core/precompute.hpp).
#define FLEXSTRESS_PRECOMPUTE_REDUCTION_COMPONENT_MODES(X)                              \
  X(7, Result<reduction::ComponentModes>, reduction::craig_bampton,                     \
    (const fe::Mesh&, const std::vector<reduction::InterfaceNode>&,                     \
     const reduction::ModeSelection&, const fe::MassOptions&, const fe::EigenOptions&)) \
  X(7, Result<reduction::ComponentModes>, reduction::craig_chang,                       \
    (const fe::Mesh&, const std::vector<reduction::InterfaceNode>&,                     \
     const reduction::ModeSelection&, const fe::MassOptions&, const fe::EigenOptions&))
namespace flexstress {
FLEXSTRESS_PRECOMPUTE_EXTERN(FLEXSTRESS_PRECOMPUTE_REDUCTION_COMPONENT_MODES)
}  // namespace flexstress
