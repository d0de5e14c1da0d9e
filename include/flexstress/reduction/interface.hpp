// Interfaces of a superelement: the nodes (and DOFs) that connect it to joints and sub-models.
//
// On beam models an interface node is a mesh node with its six DOFs. On solid meshes a node has
// translations only, so an interface is usually a *spider*: a new node tied to a face set of the
// mesh, either rigidly (RBE2: the face moves as a rigid body with the spider node) or as a
// weighted average (RBE3: the spider node follows the least-squares rigid fit of the face, and
// the face stays free to deform). Both give the body translational and rotational interface
// DOFs, and therefore rotational mode shapes Phi_theta there.
#pragma once

#include <array>
#include <vector>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/fe/mesh.hpp"

namespace flexstress::reduction {

/// One interface node and the DOFs of it that are interface DOFs (default: all it has).
struct InterfaceNode {
  Index node = 0;
  std::array<bool, 6> dofs{true, true, true, true, true, true};

  static InterfaceNode translations_only(Index node) {
    return InterfaceNode{node, {true, true, true, false, false, false}};
  }
};

/// The centroid of a node set (the origin for an empty set; the mesh's validation reports
/// nodes that do not exist when the spider is used).
inline Vector3d face_centroid(const fe::Mesh& mesh, const std::vector<Index>& face_nodes) {
  Vector3d c = Vector3d::Zero();
  for (Index n : face_nodes)
    if (n >= 0 && n < mesh.num_nodes()) c += mesh.node(n);
  return face_nodes.empty() ? c : Vector3d(c / static_cast<double>(face_nodes.size()));
}

/// Adds a node at `position` (default: the centroid of `face_nodes`) and ties the face to it
/// rigidly (RBE2). Returns the new node; its six DOFs can serve as an interface.
FLEXSTRESS_PRECOMPUTE
Index add_rigid_spider(fe::Mesh& mesh, const std::vector<Index>& face_nodes,
                       const Vector3d& position) {
  const Index master = mesh.add_node(position);
  mesh.add_rigid_link(master, face_nodes);
  return master;
}

FLEXSTRESS_PRECOMPUTE
Index add_rigid_spider(fe::Mesh& mesh, const std::vector<Index>& face_nodes) {
  return add_rigid_spider(mesh, face_nodes, face_centroid(mesh, face_nodes));
}

/// Adds a node at `position` (default: the centroid of `face_nodes`) that follows the face's
/// least-squares rigid fit (RBE3, equal weights) without stiffening it. Returns the new node; its
/// six DOFs can serve as an interface.
FLEXSTRESS_PRECOMPUTE
Index add_averaging_spider(fe::Mesh& mesh, const std::vector<Index>& face_nodes,
                           const Vector3d& position) {
  const Index reference = mesh.add_node(position);
  mesh.add_averaging_link(reference, face_nodes);
  return reference;
}

FLEXSTRESS_PRECOMPUTE
Index add_averaging_spider(fe::Mesh& mesh, const std::vector<Index>& face_nodes) {
  return add_averaging_spider(mesh, face_nodes, face_centroid(mesh, face_nodes));
}

}  // namespace flexstress::reduction
