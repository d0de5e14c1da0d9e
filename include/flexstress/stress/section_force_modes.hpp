// Section-force modes of a reduced beam host: the force and moment a beam element carries at one
// of its nodes per unit modal coordinate, K_e Phi_e restricted to that node (body frame).
//
// Why: a sub-model driven by the host's displacements (the paper's method) turns any difference
// between its own stiffness and that of the beam segment it replaces straight into stress (the
// crane's brick segment is about 5 % stiffer than its beam, docs/accuracy-vs-time.md). Driven at
// one end by the section forces instead (AttachmentDrive::force in sub_model.hpp), it is
// statically determinate and takes the moment at the detail from the beam. The element's nodal
// forces f_e = K_e u_e are what its nodes apply to it; a sub-model that takes the place of the
// element (and of the beam on the element's side of the node) is loaded at the node by exactly
// these. Being linear in the modal coordinates, they fuse into one row per output like the
// boundary displacement modes (fused_stress.hpp).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/fe/beam3d.hpp"
#include "flexstress/fe/mesh.hpp"
#include "flexstress/reduction/modal_body_data.hpp"
#include "flexstress/stress/host_point.hpp"

namespace flexstress::stress {

/// (6 x n): the force and moment that beam element `element` of `host_mesh` receives at its node
/// `node` per unit modal coordinate of `host` (the reduction of `host_mesh`), body frame. Fails,
/// naming them, for an element that does not exist, a node that is not one of its two, and the
/// errors of boundary_modes (a node the reduction does not know, or without rotations).
FLEXSTRESS_PRECOMPUTE
Result<MatrixXd> section_force_modes(const fe::Mesh& host_mesh,
                                     const reduction::ModalBodyData& host, Index element,
                                     Index node)
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  const auto& beams = host_mesh.beams();
  if (element < 0 || element >= static_cast<Index>(beams.size()))
    return make_error(ErrorCode::invalid_argument, "section forces: beam element ", element,
                      " does not exist (the host mesh has ", beams.size(), " beam elements)");
  const fe::BeamElement& b = beams[static_cast<std::size_t>(element)];
  const int slot = b.nodes[0] == node ? 0 : b.nodes[1] == node ? 1 : -1;
  if (slot < 0)
    return make_error(ErrorCode::invalid_argument, "section forces: node ", node,
                      " is not a node of beam element ", element, " (its nodes are ", b.nodes[0],
                      " and ", b.nodes[1], ")");
  auto phi = boundary_modes(host, {HostPoint::at_node(b.nodes[0]), HostPoint::at_node(b.nodes[1])});
  if (!phi) return phi.error();
  const fe::Matrix12d k = fe::beam_stiffness(host_mesh, b);
  return MatrixXd(k.middleRows<6>(6 * slot) * *phi);
}
#else
    ;
#endif

}  // namespace flexstress::stress

// This header's precompute entry points (core/precompute.hpp).
#define FLEXSTRESS_PRECOMPUTE_STRESS_SECTION_FORCE_MODES(X) \
  X(10, Result<MatrixXd>, stress::section_force_modes,      \
    (const fe::Mesh&, const reduction::ModalBodyData&, Index, Index))
namespace flexstress {
FLEXSTRESS_PRECOMPUTE_EXTERN(FLEXSTRESS_PRECOMPUTE_STRESS_SECTION_FORCE_MODES)
}  // namespace flexstress
