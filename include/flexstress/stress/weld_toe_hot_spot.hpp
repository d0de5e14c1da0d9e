// The hot spots at the two weld toes of the generated RHS detail (fe/rhs_attachment_mesh.hpp),
// each read away from its weld. Written by hand, a HotSpotLocation keeps the +x direction at
// both toes easily; at the -x toe its read-out points then fall under the weld's foot and read
// what the weld carries, well below the toe's stress (docs/stress.md).
#pragma once

#include <Eigen/Core>

#include "flexstress/core/types.hpp"
#include "flexstress/fe/rhs_attachment_mesh.hpp"
#include "flexstress/stress/hot_spot.hpp"

namespace flexstress::stress {

/// Which toe of the detail's rib: on its +x side (RhsAttachmentMesh::weld_toe_x) or its -x side
/// (opposite_weld_toe_x).
enum class WeldToe { plus_x, minus_x };

/// The hot spot on the flange surface at `toe`, at z across the flange (0: the centre line),
/// read along the surface away from the weld, with the flange's wall as the plate thickness t.
inline HotSpotLocation weld_toe_hot_spot(const fe::RhsAttachmentMesh& detail, WeldToe toe,
                                         double z = 0.0,
                                         HotSpotRule rule = HotSpotRule::iiw_type_a_linear) {
  HotSpotLocation h;
  const bool plus = toe == WeldToe::plus_x;
  h.toe =
      Vector3d(plus ? detail.weld_toe_x : detail.opposite_weld_toe_x, detail.flange_surface_y, z);
  h.away = plus ? Vector3d::UnitX() : Vector3d(-Vector3d::UnitX());
  h.thickness = detail.spec.wall;
  h.rule = rule;
  return h;
}

}  // namespace flexstress::stress
