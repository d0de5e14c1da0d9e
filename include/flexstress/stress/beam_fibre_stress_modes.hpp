// Fibre-stress modes of a reduced beam body: the axial stress at one fibre of the beam between
// two of its nodes per unit modal coordinate, a row for the body's stress outputs.
//
// Everything the stress needs is in the body data and a few numbers, not in the mesh: the two
// nodes' positions and mode shapes (displacements and rotations) give the element's cubic
// Hermite deflection, and sigma_xx = E (u' - y v'' - z w'') (fe::beam_fibre_stress) needs only
// Young's modulus, the section's orientation and the fibre's offsets. So a program that has
// only a modal body file (the C interface) can still read a beam's stress; for a beam element
// of the reduced mesh the row is exactly what fe::beam_fibre_stress gives mode by mode.
#pragma once

#include <cmath>

#include <Eigen/Core>

#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/fe/beam3d.hpp"
#include "flexstress/fe/material.hpp"
#include "flexstress/fe/mesh.hpp"
#include "flexstress/reduction/modal_body_data.hpp"

namespace flexstress::stress {

/// Where on a beam between two nodes of a body, and which fibre. The nodes are those of one
/// beam element (body data record no elements: between other nodes the row is the stress of a
/// single cubic through them, not the beam's).
struct BeamFibre {
  Index node_a = -1, node_b = -1;
  /// The section's local y axis, projected normal to the beam (fe::BeamElement::orientation;
  /// zero: the mesh's default, global y, or z for a beam along y).
  Vector3d orientation = Vector3d::Zero();
  double youngs_modulus = 210e9;
  double xi = 0.0;          ///< 0 at node_a, 1 at node_b
  double y = 0.0, z = 0.0;  ///< the fibre's offsets along the section's local y and z (m)
};

/// (1 x modes): sigma_xx at the fibre per unit modal coordinate of the body's first `modes`
/// modes. Fails, naming what, for nodes the body does not have or without rotations, coincident
/// nodes, an orientation along the beam, a modulus that is not positive, xi outside [0, 1], or
/// more modes than the data has.
inline Result<Eigen::RowVectorXd> beam_fibre_stress_modes(const reduction::ModalBodyData& body,
                                                          const BeamFibre& f, Index modes) {
  if (modes < 0 || modes > body.num_modes)
    return make_error(ErrorCode::size_mismatch, "fibre stress: ", modes,
                      " modes asked, the body data has ", body.num_modes);
  if (!(f.youngs_modulus > 0.0) || !std::isfinite(f.youngs_modulus))
    return make_error(ErrorCode::invalid_argument, "fibre stress: Young's modulus ",
                      f.youngs_modulus, " must be positive");
  if (!(f.xi >= 0.0 && f.xi <= 1.0) || !std::isfinite(f.y) || !std::isfinite(f.z) ||
      !f.orientation.allFinite())
    return make_error(ErrorCode::invalid_argument, "fibre stress: xi ", f.xi,
                      " must be in [0, 1] and the offsets and orientation finite");
  for (const Index node : {f.node_a, f.node_b}) {
    if (node < 0 || node >= body.num_nodes())
      return make_error(ErrorCode::invalid_argument, "fibre stress: node ", node,
                        " does not exist (the body has ", body.num_nodes(), " nodes)");
    if (!body.node_has_rotation[static_cast<std::size_t>(node)])
      return make_error(ErrorCode::invalid_argument, "fibre stress: node ", node,
                        " has no rotational DOFs (not a beam node)");
  }
  const Vector3d x0 = body.node_positions[static_cast<std::size_t>(f.node_a)];
  const Vector3d x1 = body.node_positions[static_cast<std::size_t>(f.node_b)];
  if (!((x1 - x0).norm() > 0.0))
    return make_error(ErrorCode::invalid_argument, "fibre stress: nodes ", f.node_a, " and ",
                      f.node_b, " coincide");
  if (f.orientation.squaredNorm() > 0.0 &&
      !(f.orientation.normalized().cross((x1 - x0).normalized()).norm() > 1e-6))
    return make_error(ErrorCode::invalid_argument,
                      "fibre stress: the orientation lies along the beam from node ", f.node_a,
                      " to node ", f.node_b);
  // A one-element mesh of the two nodes: the stress does not depend on the section's
  // properties (N / A - Mz y / Iz + My z / Iy = E (u' - y v'' - z w'')), any positive ones do.
  fe::Mesh mesh;
  const Index a = mesh.add_node(x0), b = mesh.add_node(x1);
  fe::Material material;
  material.youngs_modulus = f.youngs_modulus;
  fe::BeamSection section;
  section.area = section.iy = section.iz = section.torsion_constant = 1.0;
  mesh.add_beam(a, b, mesh.add_material(material), mesh.add_section(section), f.orientation);
  const fe::BeamElement& beam = mesh.beams().front();
  Eigen::RowVectorXd row(modes);
  for (Index k = 0; k < modes; ++k) {
    fe::Vector12d u;  // [u_a; theta_a; u_b; theta_b] of mode k
    u << body.phi_r(f.node_a).col(k), body.phi_theta(f.node_a).col(k), body.phi_r(f.node_b).col(k),
        body.phi_theta(f.node_b).col(k);
    row(k) = fe::beam_fibre_stress(mesh, beam, u, f.xi, f.y, f.z);
  }
  return row;
}

}  // namespace flexstress::stress
