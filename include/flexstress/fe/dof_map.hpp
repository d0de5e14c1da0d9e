// Numbering of nodal DOFs: solid nodes carry 3 translations, beam nodes 6 (translations, then
// rotations about the global axes); mixed meshes mix both.
//
// A node gets rotations if a beam uses it, if it is the master of a rigid link or the reference
// of an averaging link, if a point mass with rotational inertia sits on it, or if
// require_rotations() asked for it. Otherwise it has 3 translations if any element, point mass
// or link uses it, and none at all if nothing does.
#pragma once

#include <string>
#include <vector>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/fe/mesh.hpp"

namespace flexstress::fe {

class DofMap {
 public:
  /// Numbers the DOFs of a validated mesh. Fails if the mesh does not validate.
  FLEXSTRESS_PRECOMPUTE
  static Result<DofMap> build(const Mesh& mesh);

  /// Total number of nodal DOFs.
  Index size() const { return size_; }
  Index num_nodes() const { return static_cast<Index>(count_.size()); }
  /// 0, 3 or 6.
  int num_node_dofs(Index node) const { return count_[static_cast<std::size_t>(node)]; }
  bool has_rotations(Index node) const { return num_node_dofs(node) == 6; }
  /// Global DOF index of a node's component (0..5 = ux, uy, uz, rx, ry, rz), or -1 if the node
  /// does not have that component.
  Index dof(Index node, int component) const {
    if (node < 0 || node >= num_nodes() || component < 0 || component >= num_node_dofs(node))
      return -1;
    return first_[static_cast<std::size_t>(node)] + component;
  }
  Index node_of(Index dof) const { return node_of_[static_cast<std::size_t>(dof)]; }
  int component_of(Index dof) const { return component_of_[static_cast<std::size_t>(dof)]; }
  /// "node 12 uz", for messages.
  std::string describe(Index dof) const {
    return "node " + std::to_string(node_of(dof)) + " " + dof_component_name(component_of(dof));
  }

 private:
  std::vector<Index> first_;
  std::vector<int> count_;
  std::vector<Index> node_of_;
  std::vector<int> component_of_;
  Index size_ = 0;
};

#if FLEXSTRESS_PRECOMPUTE_BODIES
template <class>
Result<DofMap> DofMap::build(const Mesh& mesh) {
  if (Status s = mesh.validate(); !s) return s.error();
  const auto nn = static_cast<std::size_t>(mesh.num_nodes());
  std::vector<int> count(nn, 0);
  auto at_least = [&](Index node, int c) {
    int& n = count[static_cast<std::size_t>(node)];
    if (n < c) n = c;
  };
  for (const auto& b : mesh.beams())
    for (Index n : b.nodes) at_least(n, 6);
  for (const auto& h : mesh.hexes())
    for (Index n : h.nodes) at_least(n, 3);
  for (const auto& p : mesh.point_masses()) at_least(p.node, p.inertia.isZero(0.0) ? 3 : 6);
  for (const auto& l : mesh.rigid_links()) {
    at_least(l.master, 6);
    for (Index s : l.slaves) at_least(s, 3);
  }
  for (const auto& l : mesh.averaging_links()) {
    at_least(l.reference, 6);
    for (Index f : l.face) at_least(f, 3);
  }
  for (const auto& m : mesh.matrix_elements())
    for (Index n : m.nodes) at_least(n, 3);
  for (Index n : mesh.rotation_nodes()) at_least(n, 6);

  DofMap map;
  map.first_.resize(nn);
  map.count_ = count;
  Index next = 0;
  for (std::size_t i = 0; i < nn; ++i) {
    map.first_[i] = next;
    for (int c = 0; c < count[i]; ++c) {
      map.node_of_.push_back(static_cast<Index>(i));
      map.component_of_.push_back(c);
    }
    next += count[i];
  }
  map.size_ = next;
  return map;
}
#endif

}  // namespace flexstress::fe

// This header's precompute entry points (core/precompute.hpp).
#define FLEXSTRESS_PRECOMPUTE_FE_DOF_MAP(X) \
  X(1, Result<fe::DofMap>, fe::DofMap::build, (const fe::Mesh&))
namespace flexstress {
FLEXSTRESS_PRECOMPUTE_EXTERN(FLEXSTRESS_PRECOMPUTE_FE_DOF_MAP)
}  // namespace flexstress
