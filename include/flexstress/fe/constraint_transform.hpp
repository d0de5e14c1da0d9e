// Exact elimination of prescribed DOFs and rigid links by a transformation:
//
//   u_all = T u_free + G v,
//
// with u_free the independent unknowns, v the values of the prescribed DOFs (in the order of
// prescribed_dofs()), T (n_all x n_free) and G (n_all x n_prescribed) sparse. Rigid links
// (RBE2) give slave rows u_s = u_m + theta_m x (x_s - x_m) = u_m - skew(x_s - x_m) theta_m and
// theta_s = theta_m; chains of links (a slave that is the master of another link) are resolved
// recursively, loops are an error. Averaging links (RBE3, averaging_link.hpp) tie their
// reference's six DOFs to the face translations by [u_ref; theta_ref] = C u_face; six face DOFs
// become dependent, u_d = C_d^-1 (u_ref - C_o u_o), chosen among the free face DOFs by full
// pivoting of C (the best-conditioned C_d), so the reference stays an ordinary DOF that can be
// loaded, supported or made an interface. The reduced stiffness is T^T K T and the load
// T^T (f - K G v): no penalty, no Lagrange multipliers.
//
// Keeping G separate from the values lets one factorization of T^T K T serve any prescribed
// values: Craig-Bampton constraint modes and sub-model influence matrices are unit values of v.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/LU>
#include <Eigen/SparseCore>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/skew.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/fe/averaging_link.hpp"
#include "flexstress/fe/boundary_conditions.hpp"
#include "flexstress/fe/dof_map.hpp"
#include "flexstress/fe/mesh.hpp"

namespace flexstress::fe {

using SparseMatrixd = Eigen::SparseMatrix<double>;

class ConstraintTransform {
 public:
  enum class DofKind : unsigned char { free, prescribed, slave };

  /// Builds T and G. Fails, naming the node, DOF and link, for prescribed DOFs on nodes that do
  /// not exist or lack the component, DOFs prescribed twice, prescribed slave DOFs, nodes that
  /// are slaves of two links, and loops of rigid links.
  FLEXSTRESS_PRECOMPUTE
  static Result<ConstraintTransform> build(const Mesh& mesh, const DofMap& dofs,
                                           const BoundaryConditions& bc);

  Index num_all() const { return t_.rows(); }
  Index num_free() const { return num_free_; }
  Index num_prescribed() const { return static_cast<Index>(prescribed_.size()); }
  /// T: all DOFs from free DOFs.
  const SparseMatrixd& free_to_all() const { return t_; }
  /// G: all DOFs from prescribed values.
  const SparseMatrixd& prescribed_to_all() const { return g_; }
  /// The prescribed values given in the boundary conditions.
  const VectorXd& prescribed_values() const { return values_; }
  /// Global DOF of each prescribed value.
  const std::vector<Index>& prescribed_dofs() const { return prescribed_; }
  /// Global DOF of each free unknown.
  const std::vector<Index>& free_dofs() const { return free_; }
  DofKind kind(Index dof) const { return kind_[static_cast<std::size_t>(dof)]; }
  /// Index among the free unknowns (or among prescribed values), -1 for slaves.
  Index column(Index dof) const { return column_[static_cast<std::size_t>(dof)]; }

  /// u_all = T u_free + G v.
  VectorXd expand(const VectorXd& u_free, const VectorXd& values) const {
    return t_ * u_free + g_ * values;
  }
  VectorXd expand(const VectorXd& u_free) const { return expand(u_free, values_); }

 private:
  SparseMatrixd t_, g_;
  VectorXd values_;
  std::vector<DofKind> kind_;
  std::vector<Index> column_;
  std::vector<Index> prescribed_;
  std::vector<Index> free_;
  Index num_free_ = 0;
};

#if FLEXSTRESS_PRECOMPUTE_BODIES
template <class>
Result<ConstraintTransform> ConstraintTransform::build(const Mesh& mesh, const DofMap& dofs,
                                                       const BoundaryConditions& bc) {
  ConstraintTransform ct;
  const Index n = dofs.size();
  ct.kind_.assign(static_cast<std::size_t>(n), DofKind::free);
  ct.column_.assign(static_cast<std::size_t>(n), -1);

  // Which link drives each node (as a slave).
  std::vector<Index> slave_of(static_cast<std::size_t>(mesh.num_nodes()), -1);
  for (std::size_t l = 0; l < mesh.rigid_links().size(); ++l) {
    for (Index s : mesh.rigid_links()[l].slaves) {
      Index& owner = slave_of[static_cast<std::size_t>(s)];
      if (owner >= 0 && owner != static_cast<Index>(l))
        return make_error(ErrorCode::invalid_mesh, "node ", s, " is a slave of rigid links ", owner,
                          " and ", l, "; a node can follow only one master");
      owner = static_cast<Index>(l);
    }
  }
  // Loops: follow master chains.
  for (std::size_t l = 0; l < mesh.rigid_links().size(); ++l) {
    Index node = mesh.rigid_links()[l].master;
    std::size_t steps = 0;
    while (slave_of[static_cast<std::size_t>(node)] >= 0) {
      if (++steps > mesh.rigid_links().size())
        return make_error(ErrorCode::invalid_mesh, "rigid link ", l,
                          " is part of a loop of rigid links (its master node ",
                          mesh.rigid_links()[l].master,
                          " is, through a chain of links, a slave of itself)");
      node = mesh.rigid_links()[static_cast<std::size_t>(slave_of[static_cast<std::size_t>(node)])]
                 .master;
    }
  }
  for (Index node = 0; node < mesh.num_nodes(); ++node)
    if (slave_of[static_cast<std::size_t>(node)] >= 0)
      for (int c = 0; c < dofs.num_node_dofs(node); ++c)
        ct.kind_[static_cast<std::size_t>(dofs.dof(node, c))] = DofKind::slave;

  // Prescribed DOFs, in the order given (selectors expand in component order).
  std::vector<double> values;
  auto prescribe = [&](Index node, int c, double value) -> Status {
    const Index d = dofs.dof(node, c);
    if (d < 0)
      return make_error(ErrorCode::invalid_argument, "prescribed displacement on node ", node,
                        " component ", dof_component_name(c), ": the node has ",
                        dofs.num_node_dofs(node), " DOFs");
    auto& k = ct.kind_[static_cast<std::size_t>(d)];
    if (k == DofKind::slave)
      return make_error(ErrorCode::invalid_argument, "prescribed displacement on ",
                        dofs.describe(d), ", which rigid link ",
                        slave_of[static_cast<std::size_t>(node)],
                        " drives; prescribe the link's master instead");
    if (k == DofKind::prescribed)
      return make_error(ErrorCode::invalid_argument, dofs.describe(d), " is prescribed twice");
    k = DofKind::prescribed;
    ct.column_[static_cast<std::size_t>(d)] = static_cast<Index>(ct.prescribed_.size());
    ct.prescribed_.push_back(d);
    values.push_back(value);
    return Status::success();
  };
  for (const auto& p : bc.prescribed()) {
    if (p.node < 0 || p.node >= mesh.num_nodes())
      return make_error(ErrorCode::invalid_argument, "prescribed displacement on node ", p.node,
                        ", which does not exist (the mesh has ", mesh.num_nodes(), " nodes)");
    if (!std::isfinite(p.value))
      return make_error(ErrorCode::invalid_argument, "prescribed displacement on node ", p.node,
                        " component ", dof_component_name(p.component), " is not finite");
    if (dofs.num_node_dofs(p.node) == 0)
      return make_error(ErrorCode::invalid_argument, "prescribed displacement on node ", p.node,
                        ", which no element uses (it has no DOFs)");
    if (p.component == all_components || p.component == translation_components) {
      const int last = p.component == all_components ? dofs.num_node_dofs(p.node) : 3;
      for (int c = 0; c < last; ++c)
        if (Status s = prescribe(p.node, c, p.value); !s) return s.error();
    } else if (p.component < 0 || p.component > 5) {
      return make_error(ErrorCode::invalid_argument, "prescribed displacement on node ", p.node,
                        ": component ", p.component, " is not one of 0..5");
    } else if (Status s = prescribe(p.node, p.component, p.value); !s) {
      return s.error();
    }
  }
  ct.values_ = Eigen::Map<const VectorXd>(values.data(), static_cast<Index>(values.size()));

  // Averaging links: six dependent face DOFs each, as combinations of the link's other DOFs.
  using Terms = std::vector<std::pair<Index, double>>;  // (global DOF, coefficient)
  std::vector<Terms> averaged(static_cast<std::size_t>(n));
  std::vector<Index> averaged_by(static_cast<std::size_t>(n), -1);
  for (std::size_t l = 0; l < mesh.averaging_links().size(); ++l) {
    const AveragingLink& link = mesh.averaging_links()[l];
    auto fit = averaging_fit(link, l, mesh.nodes());
    if (!fit) return fit.error();
    std::vector<Index> face_dofs, candidates;  // candidates: positions in face_dofs
    for (Index f : link.face)
      for (int c = 0; c < 3; ++c) {
        const Index d = dofs.dof(f, c);
        if (ct.kind_[static_cast<std::size_t>(d)] == DofKind::free)
          candidates.push_back(static_cast<Index>(face_dofs.size()));
        face_dofs.push_back(d);
      }
    MatrixXd cand(6, static_cast<Index>(std::max<std::size_t>(candidates.size(), 6)));
    cand.setZero();  // zero columns (too few candidates) fail the rank test below
    for (std::size_t j = 0; j < candidates.size(); ++j)
      cand.col(static_cast<Index>(j)) = fit->col(candidates[j]);
    const Eigen::FullPivLU<MatrixXd> lu(cand);
    if (candidates.size() < 6 || lu.rank() < 6)
      return make_error(ErrorCode::invalid_mesh, "averaging link ", l,
                        ": too few of its face DOFs are free (the others are prescribed or "
                        "follow other links) for the reference node ",
                        link.reference, " to follow the face");
    std::vector<char> dependent(face_dofs.size(), 0);
    Mat6d c_d;
    for (int k = 0; k < 6; ++k) {
      const Index j = candidates[static_cast<std::size_t>(lu.permutationQ().indices()(k))];
      dependent[static_cast<std::size_t>(j)] = 1;
      c_d.col(k) = fit->col(j);
    }
    const Mat6d c_d_inv = c_d.inverse();
    for (int k = 0; k < 6; ++k) {
      const Index j = candidates[static_cast<std::size_t>(lu.permutationQ().indices()(k))];
      const Index d = face_dofs[static_cast<std::size_t>(j)];
      Terms& terms = averaged[static_cast<std::size_t>(d)];
      for (int r = 0; r < 6; ++r) terms.push_back({dofs.dof(link.reference, r), c_d_inv(k, r)});
      for (std::size_t o = 0; o < face_dofs.size(); ++o)
        if (!dependent[o])
          terms.push_back({face_dofs[o], -c_d_inv.row(k).dot(fit->col(static_cast<Index>(o)))});
      ct.kind_[static_cast<std::size_t>(d)] = DofKind::slave;
      averaged_by[static_cast<std::size_t>(d)] = static_cast<Index>(l);
    }
  }

  // Free columns.
  for (Index d = 0; d < n; ++d)
    if (ct.kind_[static_cast<std::size_t>(d)] == DofKind::free) {
      ct.column_[static_cast<std::size_t>(d)] = ct.num_free_;
      ct.free_.push_back(d);
      ++ct.num_free_;
    }

  // Rows as sparse combinations of [free | prescribed] columns, resolved recursively.
  using Row = std::vector<std::pair<Index, double>>;  // (column in [free|prescribed], coeff)
  std::vector<Row> rows(static_cast<std::size_t>(n));
  std::vector<char> done(static_cast<std::size_t>(n), 0);  // 2: being resolved
  Index loop_dof = -1;
  const Index nf = ct.num_free_;
  auto resolve = [&](auto&& self, Index d) -> const Row& {
    auto& row = rows[static_cast<std::size_t>(d)];
    if (done[static_cast<std::size_t>(d)] == 2) loop_dof = d;
    if (done[static_cast<std::size_t>(d)]) return row;
    done[static_cast<std::size_t>(d)] = 2;
    const auto k = ct.kind_[static_cast<std::size_t>(d)];
    if (k == DofKind::free) {
      row.push_back({ct.column_[static_cast<std::size_t>(d)], 1.0});
    } else if (k == DofKind::prescribed) {
      row.push_back({nf + ct.column_[static_cast<std::size_t>(d)], 1.0});
    } else if (averaged_by[static_cast<std::size_t>(d)] >= 0) {
      Row combined;
      for (const auto& [dof, f] : averaged[static_cast<std::size_t>(d)]) {
        if (f == 0.0) continue;
        for (const auto& [col, v] : self(self, dof)) combined.push_back({col, f * v});
      }
      row = std::move(combined);
    } else {
      const Index node = dofs.node_of(d);
      const int c = dofs.component_of(d);
      const Index master =
          mesh.rigid_links()[static_cast<std::size_t>(slave_of[static_cast<std::size_t>(node)])]
              .master;
      Row combined;
      auto add = [&](const Row& r, double f) {
        if (f == 0.0) return;
        for (const auto& [col, v] : r) combined.push_back({col, f * v});
      };
      if (c < 3) {
        const Matrix3d s = skew(Vector3d(mesh.node(node) - mesh.node(master)));
        add(self(self, dofs.dof(master, c)), 1.0);
        for (int b = 0; b < 3; ++b) add(self(self, dofs.dof(master, 3 + b)), -s(c, b));
      } else {
        add(self(self, dofs.dof(master, c)), 1.0);
      }
      row = std::move(combined);
    }
    done[static_cast<std::size_t>(d)] = 1;
    return row;
  };
  std::vector<Eigen::Triplet<double>> t_trip, g_trip;
  for (Index d = 0; d < n; ++d)
    for (const auto& [col, v] : resolve(resolve, d))
      (col < nf ? t_trip : g_trip).emplace_back(d, col < nf ? col : col - nf, v);
  if (loop_dof >= 0)
    return make_error(ErrorCode::invalid_mesh, "links form a loop through ",
                      dofs.describe(loop_dof),
                      " (an averaging link's face follows, through other links, its own "
                      "reference)");
  ct.t_.resize(n, nf);
  ct.t_.setFromTriplets(t_trip.begin(), t_trip.end());
  ct.g_.resize(n, static_cast<Index>(ct.prescribed_.size()));
  ct.g_.setFromTriplets(g_trip.begin(), g_trip.end());
  return ct;
}
#endif

}  // namespace flexstress::fe

// This header's precompute entry points (core/precompute.hpp).
#define FLEXSTRESS_PRECOMPUTE_FE_CONSTRAINT_TRANSFORM(X)                \
  X(2, Result<fe::ConstraintTransform>, fe::ConstraintTransform::build, \
    (const fe::Mesh&, const fe::DofMap&, const fe::BoundaryConditions&))
namespace flexstress {
FLEXSTRESS_PRECOMPUTE_EXTERN(FLEXSTRESS_PRECOMPUTE_FE_CONSTRAINT_TRANSFORM)
}  // namespace flexstress
