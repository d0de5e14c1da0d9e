// The six rigid-body motions of a mesh as nodal DOF vectors: translations along x, y, z and
// small rotations about axes through a point c: u = e x (x - c), theta = e.
#pragma once

#include <cmath>
#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/fe/dof_map.hpp"
#include "flexstress/fe/mesh.hpp"

namespace flexstress::fe {

/// n_all x 6 matrix: columns translation x, y, z, rotation about x, y, z (about `center`).
FLEXSTRESS_PRECOMPUTE
MatrixXd rigid_body_modes(const Mesh& mesh, const DofMap& dofs, const Vector3d& center)
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  MatrixXd r = MatrixXd::Zero(dofs.size(), 6);
  for (Index n = 0; n < mesh.num_nodes(); ++n) {
    const int nd = dofs.num_node_dofs(n);
    if (nd == 0) continue;
    const Vector3d d = mesh.node(n) - center;
    for (int j = 0; j < 3; ++j) {
      r(dofs.dof(n, j), j) = 1.0;
      const Vector3d u = Vector3d::Unit(j).cross(d);
      for (int c = 0; c < 3; ++c) r(dofs.dof(n, c), 3 + j) = u(c);
      if (nd == 6) r(dofs.dof(n, 3 + j), 3 + j) = 1.0;
    }
  }
  return r;
}
#else
    ;
#endif

/// Centroid of the nodes that carry DOFs.
FLEXSTRESS_PRECOMPUTE
Vector3d dof_node_centroid(const Mesh& mesh, const DofMap& dofs) {
  Vector3d c = Vector3d::Zero();
  Index count = 0;
  for (Index n = 0; n < mesh.num_nodes(); ++n)
    if (dofs.num_node_dofs(n) > 0) {
      c += mesh.node(n);
      ++count;
    }
  return count > 0 ? Vector3d(c / static_cast<double>(count)) : c;
}

/// "translation along x", "rotation about z", ... for rigid mode column j.
FLEXSTRESS_PRECOMPUTE
std::string rigid_mode_name(int j) {
  static const char* names[6] = {"translation along x", "translation along y",
                                 "translation along z", "rotation about x",
                                 "rotation about y",    "rotation about z"};
  return names[j];
}

/// Names the dominant components of a combination v (6) of the rigid modes above, e.g.
/// "rotation about z" or "translation along y + rotation about z".
FLEXSTRESS_PRECOMPUTE
std::string describe_rigid_motion(const Eigen::Ref<const VectorXd>& v) {
  const double vmax = v.cwiseAbs().maxCoeff();
  std::string combo;
  for (int j = 0; j < 6; ++j)
    if (std::abs(v(j)) > 0.2 * vmax) combo += (combo.empty() ? "" : " + ") + rigid_mode_name(j);
  return combo;
}

}  // namespace flexstress::fe

// This header's precompute entry points (core/precompute.hpp).
#define FLEXSTRESS_PRECOMPUTE_FE_RIGID_BODY_MODES(X) \
  X(4, MatrixXd, fe::rigid_body_modes, (const fe::Mesh&, const fe::DofMap&, const Vector3d&))
namespace flexstress {
FLEXSTRESS_PRECOMPUTE_EXTERN(FLEXSTRESS_PRECOMPUTE_FE_RIGID_BODY_MODES)
}  // namespace flexstress
