// Stress modes of a reduced brick body: the stress at chosen points per unit modal coordinate,
// so that sigma(x_i, t) = S_i p(t) (the modal stress recovery of Adams Durability and Exudyn,
// for the body itself rather than a sub-model; stress/modal_stress_modes.hpp is the sub-model's
// version). Rigid motion carries no stress, so the deformation modes are all it takes.
//
// Precompute: S = N_x U, with U the body's mode shapes as all-DOF vectors of the mesh it was
// reduced from (translations at every node, rotations where the node has them) and N_x the FE
// kernel's stress operator at the points (the stress of the brick that contains each point,
// fe::point_stress_operator). Per step: a (6 m x n) product.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/fe/brick_locator.hpp"
#include "flexstress/fe/dof_map.hpp"
#include "flexstress/fe/mesh.hpp"
#include "flexstress/fe/stress_recovery.hpp"
#include "flexstress/reduction/modal_body_data.hpp"

namespace flexstress::reduction {

/// Stress (Voigt: xx yy zz xy yz zx) at points of a reduced body per unit modal coordinate.
struct BodyStressModes {
  std::vector<Vector3d> points;  ///< body frame, undeformed
  MatrixXd modes;                ///< 6 points.size() x num_modes; rows 6 i .. 6 i + 5: point i

  Index num_points() const { return static_cast<Index>(points.size()); }
  /// Stress at point i for the modal coordinates p (the first modes.cols() entries).
  Vec6<double> stress(Index i, const VectorXd& p) const {
    return modes.middleRows<6>(6 * i) * p.head(modes.cols());
  }
};

/// The body's mode shapes as all-DOF vectors of `mesh` (the mesh it was reduced from): the
/// inverse of the extraction in make_modal_body. Fails if the data has another node count or
/// another set of rotational nodes.
FLEXSTRESS_PRECOMPUTE
Result<MatrixXd> all_dof_mode_shapes(const fe::Mesh& mesh, const fe::DofMap& dofs,
                                     const ModalBodyData& body)
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  if (body.num_nodes() != mesh.num_nodes() || dofs.num_nodes() != mesh.num_nodes())
    return make_error(ErrorCode::size_mismatch, "mode shapes: the modal body data has ",
                      body.num_nodes(), " nodes, the mesh ", mesh.num_nodes(),
                      " (stress modes need the mesh the body was reduced from)");
  MatrixXd u = MatrixXd::Zero(dofs.size(), body.num_modes);
  for (Index n = 0; n < mesh.num_nodes(); ++n) {
    if (dofs.has_rotations(n) != (body.node_has_rotation[static_cast<std::size_t>(n)] != 0))
      return make_error(ErrorCode::invalid_argument, "mode shapes: node ", n,
                        dofs.has_rotations(n) ? " has rotations in the mesh but not in the data"
                                              : " has rotations in the data but not in the mesh");
    for (int c = 0; c < dofs.num_node_dofs(n); ++c)
      u.row(dofs.dof(n, c)) = (c < 3 ? body.phi_translation : body.phi_rotation).row(3 * n + c % 3);
  }
  return u;
}
#else
    ;
#endif

/// Stress modes at physical points (body frame) of the brick part of `mesh`, the mesh `body` was
/// reduced from. Fails, naming the point, for a point outside the bricks, and for data that
/// does not belong to the mesh.
FLEXSTRESS_PRECOMPUTE
Result<BodyStressModes> body_stress_modes(const fe::Mesh& mesh, const ModalBodyData& body,
                                          const std::vector<Vector3d>& points)
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  auto dofs = fe::DofMap::build(mesh);
  if (!dofs) return dofs.error();
  auto shapes = all_dof_mode_shapes(mesh, *dofs, body);
  if (!shapes) return shapes.error();
  auto locator = fe::BrickLocator::build(mesh);
  if (!locator) return locator.error();
  auto op = fe::point_stress_operator(mesh, *dofs, *locator, points);
  if (!op) return op.error();
  BodyStressModes s;
  s.points = points;
  s.modes = *op * *shapes;
  return s;
}
#else
    ;
#endif

}  // namespace flexstress::reduction

// This header's precompute entry points (core/precompute.hpp).
#define FLEXSTRESS_PRECOMPUTE_REDUCTION_BODY_STRESS_MODES(X)               \
  X(9, Result<MatrixXd>, reduction::all_dof_mode_shapes,                   \
    (const fe::Mesh&, const fe::DofMap&, const reduction::ModalBodyData&)) \
  X(9, Result<reduction::BodyStressModes>, reduction::body_stress_modes,   \
    (const fe::Mesh&, const reduction::ModalBodyData&, const std::vector<Vector3d>&))
namespace flexstress {
FLEXSTRESS_PRECOMPUTE_EXTERN(FLEXSTRESS_PRECOMPUTE_REDUCTION_BODY_STRESS_MODES)
}  // namespace flexstress
