// Brick stress recovery: stresses at the 2x2x2 Gauss points, extrapolated to the nodes and
// averaged over the bricks that share a node, and stresses at arbitrary points; each also as a
// linear operator S (sparse, 6 rows per point) with sigma = S u, u the all-DOF displacement
// vector of a DofMap, so that sub-model influence matrices can be precomputed.
//
// Stresses are Voigt vectors (xx, yy, zz, xy, yz, zx) in the global frame, in Pa for SI input.
//
// Nodal extrapolation (Hinton & Campbell, Int. J. Num. Meth. Eng. 8 (1974) 461-480; Cook,
// Malkus, Plesha, Witt, Concepts and Applications of FEA, 4th ed., sec. 6.14): the eight
// Gauss-point values define a trilinear field in the Gauss-point coordinates
// eta = sqrt(3) xi, whose value at node a is sum_g N_g(sqrt(3) xi_a) sigma_g. It is exact for
// stress fields that are linear (indeed trilinear) within the element. Averaging the nodal
// values of the bricks around a node is the plain arithmetic mean (no weighting), the usual
// post-processor choice; it is exact for a field that is continuous and linear per element.
//
// For incompatible-mode bricks the condensed modes are rebuilt from the nodal displacements,
// exactly as in hex8_stress_operator (hex8.hpp), so the recovered stress is that of the
// element's full enhanced strain field.
#pragma once

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/fe/brick_locator.hpp"
#include "flexstress/fe/constraint_transform.hpp"
#include "flexstress/fe/dof_map.hpp"
#include "flexstress/fe/hex8.hpp"
#include "flexstress/fe/material.hpp"
#include "flexstress/fe/mesh.hpp"

namespace flexstress::fe {

/// Stress operators of one brick at its 8 Gauss points (or nodes): sigma_k = S_k u_e.
using Hex8StressOperators = std::array<Hex8StressOperator, 8>;
/// Stresses of one brick at its 8 Gauss points, one Voigt column per point (Gauss point g has
/// the sign pattern of node g, see hex8::gauss_point).
using Hex8GaussStresses = Eigen::Matrix<double, 6, 8>;

namespace hex8 {

/// Extrapolation matrix E (8 x 8): nodal value at node a = sum_g E(a, g) * value at Gauss
/// point g; E(a, g) = N_g(sqrt(3) xi_a), the trilinear shape function of the Gauss-point box
/// evaluated at the node. Rows sum to one (a constant field stays constant).
FLEXSTRESS_PRECOMPUTE
Eigen::Matrix<double, 8, 8> gauss_to_node_extrapolation() {
  Eigen::Matrix<double, 8, 8> e;
  const double r = std::sqrt(3.0);
  for (int a = 0; a < 8; ++a)
    e.row(a) = shape(Vector3d(node_xi[a][0], node_xi[a][1], node_xi[a][2]) * r).transpose();
  return e;
}

}  // namespace hex8

/// Stress operators at the 8 Gauss points of a brick, sharing one Jacobian check and one
/// condensation of the incompatible modes (the same operators hex8_stress_operator gives at
/// hex8::gauss_point(g), at an eighth of the cost). Fails for a degenerate brick.
FLEXSTRESS_PRECOMPUTE
Result<Hex8StressOperators> hex8_gauss_stress_operators(const Hex8Coordinates& x,
                                                        const Material& mat,
                                                        Hex8Formulation formulation,
                                                        Index element_id) {
  auto kin = hex8_kinematics(x, element_id);
  if (!kin) return kin.error();
  const Matrix6d d = elasticity_matrix(mat);
  Hex8StressOperators ops;
  if (formulation == Hex8Formulation::full_integration) {
    for (std::size_t g = 0; g < 8; ++g) ops[g] = d * kin->b[g];
    return ops;
  }
  Matrix24d kuu;
  Eigen::Matrix<double, 24, 9> kua;
  Eigen::Matrix<double, 9, 9> kaa;
  detail::hex8_incompatible_blocks(*kin, d, kuu, kua, kaa);
  const Eigen::Matrix<double, 9, 24> alpha = -kaa.ldlt().solve(kua.transpose());
  for (int g = 0; g < 8; ++g) {
    const auto gi = static_cast<std::size_t>(g);
    const Eigen::Matrix<double, 6, 9> ba = hex8::incompatible_strain_matrix(
        hex8::gauss_point(g), kin->j0_inv_t, kin->det_j0 / kin->det_j[gi]);
    ops[gi] = d * (kin->b[gi] + ba * alpha);
  }
  return ops;
}

/// Stress operators at the 8 nodes of a brick, extrapolated from the Gauss points
/// (not averaged with neighbours): S_a = sum_g E(a, g) S_g.
FLEXSTRESS_PRECOMPUTE
Result<Hex8StressOperators> hex8_nodal_stress_operators(const Hex8Coordinates& x,
                                                        const Material& mat,
                                                        Hex8Formulation formulation,
                                                        Index element_id) {
  auto gauss = hex8_gauss_stress_operators(x, mat, formulation, element_id);
  if (!gauss) return gauss.error();
  const Eigen::Matrix<double, 8, 8> e = hex8::gauss_to_node_extrapolation();
  Hex8StressOperators ops;
  for (std::size_t a = 0; a < 8; ++a) {
    ops[a].setZero();
    for (std::size_t g = 0; g < 8; ++g)
      ops[a] += e(static_cast<Index>(a), static_cast<Index>(g)) * (*gauss)[g];
  }
  return ops;
}

namespace detail {

FLEXSTRESS_PRECOMPUTE
Status check_recovery_input(const Mesh& mesh, const DofMap& dofs, Index u_size, const char* what) {
  if (dofs.num_nodes() != mesh.num_nodes())
    return make_error(ErrorCode::size_mismatch, what, ": the DOF map numbers ", dofs.num_nodes(),
                      " nodes but the mesh has ", mesh.num_nodes(), " (a DofMap of another mesh?)");
  if (u_size >= 0 && u_size != dofs.size())
    return make_error(ErrorCode::size_mismatch, what, ": the displacement vector has ", u_size,
                      " entries, the DOF map ", dofs.size(), " (pass the all-DOF vector)");
  return Status::success();
}

// Global DOFs of a brick, in element DOF order.
FLEXSTRESS_PRECOMPUTE
std::array<Index, 24> brick_dofs(const DofMap& dofs, const Hex8Element& h) {
  std::array<Index, 24> d{};
  for (std::size_t a = 0; a < 8; ++a)
    for (int c = 0; c < 3; ++c) d[3 * a + static_cast<std::size_t>(c)] = dofs.dof(h.nodes[a], c);
  return d;
}

// Adds a 6 x 24 block at rows row0.. and the brick's DOF columns, scaled.
FLEXSTRESS_PRECOMPUTE
void add_block(std::vector<Eigen::Triplet<double>>& trip, Index row0, const Hex8StressOperator& s,
               const std::array<Index, 24>& cols, double scale) {
  for (Index i = 0; i < 6; ++i)
    for (std::size_t j = 0; j < 24; ++j) {
      const double v = scale * s(i, static_cast<Index>(j));
      if (v != 0.0) trip.emplace_back(row0 + i, cols[j], v);
    }
}

}  // namespace detail

/// A brick's element displacement vector [u v w] per node, gathered from the all-DOF vector.
/// Precondition: u has dofs.size() entries and dofs was built from the brick's mesh.
FLEXSTRESS_PRECOMPUTE
Vector24d hex8_element_displacements(const DofMap& dofs, const Hex8Element& h, const VectorXd& u) {
  Vector24d ue;
  const auto d = detail::brick_dofs(dofs, h);
  for (std::size_t j = 0; j < 24; ++j) ue(static_cast<Index>(j)) = u(d[j]);
  return ue;
}

/// Stresses at the 8 Gauss points of every brick (in mesh order) for the all-DOF
/// displacements u. Fails on size mismatches and degenerate bricks (naming the element).
FLEXSTRESS_PRECOMPUTE
Result<std::vector<Hex8GaussStresses>> gauss_point_stresses(const Mesh& mesh, const DofMap& dofs,
                                                            const VectorXd& u)
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  if (Status s = detail::check_recovery_input(mesh, dofs, u.size(), "gauss_point_stresses"); !s)
    return s.error();
  std::vector<Hex8GaussStresses> out(mesh.hexes().size());
  for (std::size_t e = 0; e < mesh.hexes().size(); ++e) {
    const Hex8Element& h = mesh.hexes()[e];
    auto ops = hex8_gauss_stress_operators(hex8_coordinates(mesh, h), mesh.material(h.material),
                                           h.formulation, static_cast<Index>(e));
    if (!ops) return ops.error();
    const Vector24d ue = hex8_element_displacements(dofs, h, u);
    for (std::size_t g = 0; g < 8; ++g) out[e].col(static_cast<Index>(g)) = (*ops)[g] * ue;
  }
  return out;
}
#else
    ;
#endif

/// Nodal stresses, extrapolated from the Gauss points and averaged over the bricks sharing
/// each node. Nodes that belong to no brick (beam nodes, link masters) have count 0 and zero
/// stress.
struct NodalStresses {
  MatrixXd stress;                 ///< 6 x num_nodes, Voigt columns
  std::vector<int> element_count;  ///< bricks that contributed to each node

  bool defined(Index node) const { return element_count[static_cast<std::size_t>(node)] > 0; }
  Vector6d at(Index node) const { return stress.col(node); }
};

/// Averaged nodal stresses of all nodes for the all-DOF displacements u.
FLEXSTRESS_PRECOMPUTE
Result<NodalStresses> nodal_stresses(const Mesh& mesh, const DofMap& dofs, const VectorXd& u)
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  if (Status s = detail::check_recovery_input(mesh, dofs, u.size(), "nodal_stresses"); !s)
    return s.error();
  NodalStresses out;
  out.stress = MatrixXd::Zero(6, mesh.num_nodes());
  out.element_count.assign(static_cast<std::size_t>(mesh.num_nodes()), 0);
  for (std::size_t e = 0; e < mesh.hexes().size(); ++e) {
    const Hex8Element& h = mesh.hexes()[e];
    auto ops = hex8_nodal_stress_operators(hex8_coordinates(mesh, h), mesh.material(h.material),
                                           h.formulation, static_cast<Index>(e));
    if (!ops) return ops.error();
    const Vector24d ue = hex8_element_displacements(dofs, h, u);
    for (std::size_t a = 0; a < 8; ++a) {
      out.stress.col(h.nodes[a]) += (*ops)[a] * ue;
      ++out.element_count[static_cast<std::size_t>(h.nodes[a])];
    }
  }
  for (Index n = 0; n < mesh.num_nodes(); ++n)
    if (out.defined(n)) out.stress.col(n) /= out.element_count[static_cast<std::size_t>(n)];
  return out;
}
#else
    ;
#endif

/// Linear operator of the averaged nodal stresses at `nodes`: a sparse
/// (6 * nodes.size()) x dofs.size() matrix S, rows 6 i .. 6 i + 5 for nodes[i], with
/// sigma(nodes[i]) = S.middleRows(6 i, 6) u, equal to nodal_stresses(...).at(nodes[i]).
/// Fails, naming the node, for a node that does not exist or belongs to no brick.
FLEXSTRESS_PRECOMPUTE
Result<SparseMatrixd> nodal_stress_operator(const Mesh& mesh, const DofMap& dofs,
                                            const std::vector<Index>& nodes)
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  if (Status s = detail::check_recovery_input(mesh, dofs, -1, "nodal_stress_operator"); !s)
    return s.error();
  const auto nn = static_cast<std::size_t>(mesh.num_nodes());
  // Which output rows each node feeds (a node may be requested twice), and brick counts.
  std::vector<std::vector<Index>> rows_of(nn);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (nodes[i] < 0 || nodes[i] >= mesh.num_nodes())
      return make_error(ErrorCode::invalid_argument, "nodal_stress_operator: node ", nodes[i],
                        " (entry ", i, ") does not exist (the mesh has ", mesh.num_nodes(),
                        " nodes)");
    rows_of[static_cast<std::size_t>(nodes[i])].push_back(6 * static_cast<Index>(i));
  }
  std::vector<int> count(nn, 0);
  for (const Hex8Element& h : mesh.hexes())
    for (Index n : h.nodes) ++count[static_cast<std::size_t>(n)];
  for (Index n : nodes)
    if (count[static_cast<std::size_t>(n)] == 0)
      return make_error(ErrorCode::invalid_argument, "nodal_stress_operator: node ", n,
                        " belongs to no hex8 element, so it has no brick stress");
  std::vector<Eigen::Triplet<double>> trip;
  for (std::size_t e = 0; e < mesh.hexes().size(); ++e) {
    const Hex8Element& h = mesh.hexes()[e];
    bool wanted = false;
    for (Index n : h.nodes) wanted = wanted || !rows_of[static_cast<std::size_t>(n)].empty();
    if (!wanted) continue;
    auto ops = hex8_nodal_stress_operators(hex8_coordinates(mesh, h), mesh.material(h.material),
                                           h.formulation, static_cast<Index>(e));
    if (!ops) return ops.error();
    const auto cols = detail::brick_dofs(dofs, h);
    for (std::size_t a = 0; a < 8; ++a) {
      const auto n = static_cast<std::size_t>(h.nodes[a]);
      for (Index row0 : rows_of[n]) detail::add_block(trip, row0, (*ops)[a], cols, 1.0 / count[n]);
    }
  }
  SparseMatrixd s(6 * static_cast<Index>(nodes.size()), dofs.size());
  s.setFromTriplets(trip.begin(), trip.end());
  return s;
}
#else
    ;
#endif

/// Linear operator of the stresses at located brick points (not averaged: the stress of the
/// element that contains each point): (6 * points.size()) x dofs.size(), rows 6 i .. 6 i + 5
/// for points[i]. Fails for an element id that does not exist or a degenerate brick.
FLEXSTRESS_PRECOMPUTE
Result<SparseMatrixd> point_stress_operator(const Mesh& mesh, const DofMap& dofs,
                                            const std::vector<BrickPoint>& points)
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  if (Status s = detail::check_recovery_input(mesh, dofs, -1, "point_stress_operator"); !s)
    return s.error();
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(points.size() * 6 * 24);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const BrickPoint& p = points[i];
    if (p.element < 0 || p.element >= static_cast<Index>(mesh.hexes().size()))
      return make_error(ErrorCode::invalid_argument, "point_stress_operator: point ", i,
                        " refers to hex8 element ", p.element, ", which does not exist");
    const Hex8Element& h = mesh.hexes()[static_cast<std::size_t>(p.element)];
    auto op = hex8_stress_operator(hex8_coordinates(mesh, h), mesh.material(h.material),
                                   h.formulation, p.xi, p.element);
    if (!op) return op.error();
    detail::add_block(trip, 6 * static_cast<Index>(i), *op, detail::brick_dofs(dofs, h), 1.0);
  }
  SparseMatrixd s(6 * static_cast<Index>(points.size()), dofs.size());
  s.setFromTriplets(trip.begin(), trip.end());
  return s;
}
#else
    ;
#endif

/// As above for physical points, located with `locator` (built from the same mesh). Fails,
/// naming the point, for a point outside the brick mesh.
FLEXSTRESS_PRECOMPUTE
Result<SparseMatrixd> point_stress_operator(const Mesh& mesh, const DofMap& dofs,
                                            const BrickLocator& locator,
                                            const std::vector<Vector3d>& points)
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  std::vector<BrickPoint> located;
  located.reserve(points.size());
  for (const Vector3d& p : points) {
    auto bp = locator.locate(p);
    if (!bp) return bp.error();
    located.push_back(*bp);
  }
  return point_stress_operator(mesh, dofs, located);
}
#else
    ;
#endif

/// Stress at a physical point for the all-DOF displacements u (the stress of the brick that
/// contains the point; see BrickLocator::locate for points on shared faces).
FLEXSTRESS_PRECOMPUTE
Result<Vector6d> stress_at_point(const Mesh& mesh, const DofMap& dofs, const BrickLocator& locator,
                                 const VectorXd& u, const Vector3d& p)
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  if (Status s = detail::check_recovery_input(mesh, dofs, u.size(), "stress_at_point"); !s)
    return s.error();
  auto bp = locator.locate(p);
  if (!bp) return bp.error();
  const Hex8Element& h = mesh.hexes()[static_cast<std::size_t>(bp->element)];
  auto op = hex8_stress_operator(hex8_coordinates(mesh, h), mesh.material(h.material),
                                 h.formulation, bp->xi, bp->element);
  if (!op) return op.error();
  return Vector6d(*op * hex8_element_displacements(dofs, h, u));
}
#else
    ;
#endif

}  // namespace flexstress::fe

// This header's precompute entry points (core/precompute.hpp).
#define FLEXSTRESS_PRECOMPUTE_FE_STRESS_RECOVERY(X)                                              \
  X(5, Result<fe::SparseMatrixd>, fe::nodal_stress_operator,                                     \
    (const fe::Mesh&, const fe::DofMap&, const std::vector<Index>&))                             \
  X(5, Result<fe::SparseMatrixd>, fe::point_stress_operator,                                     \
    (const fe::Mesh&, const fe::DofMap&, const std::vector<fe::BrickPoint>&))                    \
  X(5, Result<fe::SparseMatrixd>, fe::point_stress_operator,                                     \
    (const fe::Mesh&, const fe::DofMap&, const fe::BrickLocator&, const std::vector<Vector3d>&)) \
  X(6, Result<fe::NodalStresses>, fe::nodal_stresses,                                            \
    (const fe::Mesh&, const fe::DofMap&, const VectorXd&))                                       \
  X(6, Result<std::vector<fe::Hex8GaussStresses>>, fe::gauss_point_stresses,                     \
    (const fe::Mesh&, const fe::DofMap&, const VectorXd&))                                       \
  X(6, Result<fe::Vector6d>, fe::stress_at_point,                                                \
    (const fe::Mesh&, const fe::DofMap&, const fe::BrickLocator&, const VectorXd&,               \
     const Vector3d&))
namespace flexstress {
FLEXSTRESS_PRECOMPUTE_EXTERN(FLEXSTRESS_PRECOMPUTE_FE_STRESS_RECOVERY)
}  // namespace flexstress
