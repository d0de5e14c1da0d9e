// Modal geometric stiffness for geometric stiffening (ModelBuilder::add_geometric_stiffening): the
// stiffening (or softening) that the stress of a body's own inertial and gravity loads gives its
// modes, as a linear combination of precomputed unit load cases (Wallrapp, "Standardization of
// flexible body modeling in multibody system codes", Mech. Struct. Mach. 22 (1994): the geometric
// stiffness terms of the standard input data; Shabana, Dynamics of Multibody Systems, ch. 5 on
// centrifugal stiffening).
//
// A material point at x (body frame) of a body whose frame has origin acceleration a (body
// axes), angular velocity w and angular acceleration alpha, in gravity g (body axes), carries
// the load density -rho (a - g + alpha x x + (w w^T - |w|^2 1) x). That is linear in 12
// coefficients: a - g (3), alpha (3) and the six entries of the symmetric w w^T - |w|^2 1. For
// each unit coefficient the precompute solves the FE model statically under the consistent
// inertial load -M a_field (held at `supports`, where the joints hold the body), takes the
// stress of that solution, assembles its geometric stiffness K_G and reduces it to the modes,
// G_j = Phi^T K_G,j Phi. At run time K_G(state) = sum_j c_j(state) G_j, an N x N matrix.
//
// Quasi-static: the stress is that of the rigid-body inertial loads alone (the deformation's
// own accelerations are not loads here), which is the standard approximation and exact for the
// steady spin of a rotating beam.
#pragma once

#include <Eigen/Core>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/skew.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/fe/assembly.hpp"
#include "flexstress/fe/boundary_conditions.hpp"
#include "flexstress/fe/geometric_stiffness.hpp"
#include "flexstress/fe/mesh.hpp"
#include "flexstress/fe/static_solver.hpp"
#include "flexstress/reduction/modal_body_data.hpp"
#include "flexstress/reduction/modal_geometric_stiffness_data.hpp"

namespace flexstress::reduction {

/// The supports most bodies want: every interface node of the reduction clamped.
inline fe::BoundaryConditions clamp_interface_nodes(const ModalBodyData& data) {
  fe::BoundaryConditions bc;
  for (Index n : data.interface_nodes) bc.clamp(n);
  return bc;
}

/// Modal geometric stiffness of the body `data` reduced from `mesh`, with the inertial loads
/// reacted at `supports` (these must hold every rigid motion of the mesh). Fails with the FE
/// solver's explanation if the supports leave a mechanism.
FLEXSTRESS_PRECOMPUTE
Result<ModalGeometricStiffness> modal_geometric_stiffness(const fe::Mesh& mesh,
                                                          const ModalBodyData& data,
                                                          const fe::BoundaryConditions& supports)
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  if (data.num_nodes() != mesh.num_nodes())
    return make_error(ErrorCode::size_mismatch, "modal geometric stiffness: the modal data has ",
                      data.num_nodes(), " nodes, the mesh ", mesh.num_nodes(),
                      " (was it reduced from this mesh?)");
  auto model = fe::assemble(mesh, supports, data.mass_options);
  if (!model) return model.error();
  auto solver = fe::StaticSolver::factorize(mesh, *model);
  if (!solver)
    return make_error(
        ErrorCode::singular_matrix,
        "modal geometric stiffness: the supports do not hold the body: ", solver.error().what());
  const fe::DofMap& dofs = model->dofs;
  const Index n = data.num_modes, ndof = dofs.size();
  // Modes over the FE DOFs, from the nodal mode shapes.
  MatrixXd phi = MatrixXd::Zero(ndof, n);
  for (Index node = 0; node < mesh.num_nodes(); ++node)
    for (int c = 0; c < 6; ++c) {
      const Index d = dofs.dof(node, c);
      if (d < 0) continue;
      phi.row(d) =
          c < 3 ? data.phi_translation.row(3 * node + c) : data.phi_rotation.row(3 * node + c - 3);
    }
  ModalGeometricStiffness out;
  out.num_modes = n;
  for (int j = 0; j < num_inertial_load_cases; ++j) {
    // Acceleration field of the unit case: translation a(x) and rotation rate of the field.
    Matrix3d field = Matrix3d::Zero();  // a(x) = t + field x
    Vector3d t = Vector3d::Zero(), rot = Vector3d::Zero();
    if (j < 3) {
      t(j) = 1.0;
    } else if (j < 6) {
      rot(j - 3) = 1.0;
      field = skew(Vector3d(rot));
    } else if (j < 9) {
      field(j - 6, j - 6) = 1.0;
    } else {
      const int a = j - 9, b = (a + 1) % 3;
      field(a, b) = field(b, a) = 1.0;
    }
    VectorXd acc = VectorXd::Zero(ndof);
    for (Index node = 0; node < mesh.num_nodes(); ++node) {
      const Vector3d a = t + field * mesh.node(node);
      for (int c = 0; c < 6; ++c) {
        const Index d = dofs.dof(node, c);
        if (d >= 0) acc(d) = c < 3 ? a(c) : rot(c - 3);
      }
    }
    const VectorXd u = solver->solve(-(model->mass_all * acc));
    auto kg = fe::assemble_geometric_stiffness(mesh, dofs, u);
    if (!kg) return kg.error();
    MatrixXd g = phi.transpose() * (*kg * phi);
    out.cases[static_cast<std::size_t>(j)] = 0.5 * (g + g.transpose());
  }
  return out;
}
#else
    ;
#endif

}  // namespace flexstress::reduction

// This header's precompute entry points (core/precompute.hpp).
#define FLEXSTRESS_PRECOMPUTE_REDUCTION_MODAL_GEOMETRIC_STIFFNESS(X)                     \
  X(9, Result<reduction::ModalGeometricStiffness>, reduction::modal_geometric_stiffness, \
    (const fe::Mesh&, const reduction::ModalBodyData&, const fe::BoundaryConditions&))
namespace flexstress {
FLEXSTRESS_PRECOMPUTE_EXTERN(FLEXSTRESS_PRECOMPUTE_REDUCTION_MODAL_GEOMETRIC_STIFFNESS)
}  // namespace flexstress
