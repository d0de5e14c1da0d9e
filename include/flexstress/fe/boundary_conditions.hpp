// Prescribed nodal displacements (supports, imposed motion, sub-model boundary DOFs).
#pragma once

#include <vector>

#include "flexstress/core/types.hpp"

namespace flexstress::fe {

/// Component selectors beyond a single component 0..5.
inline constexpr int all_components = -1;          ///< every DOF the node has
inline constexpr int translation_components = -2;  ///< ux, uy, uz

/// One prescribed displacement: node, component (0..5, or a selector above), value.
struct PrescribedDisplacement {
  Index node = 0;
  int component = 0;
  double value = 0.0;
};

/// A list of prescribed displacements. Checked when a ConstraintTransform is built (nodes that
/// do not exist, components a node does not have, DOFs that a rigid link already drives).
class BoundaryConditions {
 public:
  /// Prescribes one component (0..5 = ux, uy, uz, rx, ry, rz) of a node.
  BoundaryConditions& fix(Index node, int component, double value = 0.0) {
    prescribed_.push_back({node, component, value});
    return *this;
  }
  /// Clamps every DOF of a node.
  BoundaryConditions& clamp(Index node) { return fix(node, all_components); }
  /// Fixes the translations of a node (a pin for a solid node).
  BoundaryConditions& pin(Index node) { return fix(node, translation_components); }

  const std::vector<PrescribedDisplacement>& prescribed() const { return prescribed_; }
  bool empty() const { return prescribed_.empty(); }

 private:
  std::vector<PrescribedDisplacement> prescribed_;
};

}  // namespace flexstress::fe
