// The whole reduction of an FE model to a flexible body's modal data (reduction/modal_body.hpp):
// component modes, orthonormalization and inertia integrals, in one precompute call, reduce().
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/fe/mass_options.hpp"
#include "flexstress/reduction/component_modes.hpp"
#include "flexstress/reduction/inertia_integrals.hpp"
#include "flexstress/reduction/modal_body.hpp"
#include "flexstress/reduction/orthonormalize.hpp"

namespace flexstress::reduction {

/// What reduce() should do.
struct ReductionSpec {
  ReductionMethod method = ReductionMethod::craig_bampton;
  std::vector<InterfaceNode> interface;
  ModeSelection dynamic_modes;  ///< fixed-interface (CB) or free-free (CC) modes
  /// Deformation modes kept after orthonormalization (the lowest ones); < 0 keeps all
  /// (6k - 6 + n for Craig-Bampton with k six-DOF interface nodes).
  Index keep_modes = -1;
  fe::MassOptions mass;
  fe::EigenOptions eigen;
  double damping_ratio = 0.0;  ///< the same modal damping ratio for every mode
  /// Body frame attached to the interface instead of floating: keep the Craig-Bampton
  /// fixed-interface modes themselves (no motion at the interface node), without
  /// orthonormalization, so that the body frame is the interface node's frame. Needs
  /// Craig-Bampton with one six-DOF interface node. This is the frame of rotor-blade codes and
  /// of the "conventional" linear model of Kane, Ryan & Banerjee (1987); its modes are not
  /// mass-orthogonal to rigid motion, and the FFRF equations keep every coupling term.
  bool interface_attached_frame = false;
};

/// The fixed-interface modes of a Craig-Bampton basis as they are (interface_attached_frame),
/// with the residuals of their M- and K-orthogonality.
FLEXSTRESS_PRECOMPUTE
Result<DeformationModes> attached_frame_modes(const ComponentModes& cm, const ReductionSpec& spec) {
  if (cm.method != ReductionMethod::craig_bampton || spec.interface.size() != 1 ||
      cm.num_static != 6)
    return make_error(ErrorCode::invalid_argument,
                      "an interface-attached body frame needs Craig-Bampton with exactly one "
                      "six-DOF interface node (got ",
                      spec.interface.size(), " interface nodes, ", cm.num_static, " static modes)");
  if (cm.num_dynamic == 0)
    return make_error(ErrorCode::invalid_argument,
                      "an interface-attached body frame needs fixed-interface modes "
                      "(dynamic_modes.count > 0)");
  DeformationModes d;
  d.modes = cm.basis.leftCols(cm.num_dynamic);
  d.eigenvalues = cm.dynamic_eigenvalues;
  const MatrixXd m = d.modes.transpose() * (cm.model.mass_all * d.modes);
  const MatrixXd k = d.modes.transpose() * (cm.model.stiffness_all * d.modes);
  d.mass_residual = (m - MatrixXd::Identity(m.rows(), m.cols())).cwiseAbs().maxCoeff();
  d.stiffness_residual =
      (k - MatrixXd(d.eigenvalues.asDiagonal())).cwiseAbs().maxCoeff() / d.eigenvalues.maxCoeff();
  return d;
}

/// From a component-mode basis to modal body data.
FLEXSTRESS_PRECOMPUTE
Result<ModalBodyData> make_modal_body(const fe::Mesh& mesh, const ComponentModes& cm,
                                      const ReductionSpec& spec)
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  auto deformation =
      spec.interface_attached_frame ? attached_frame_modes(cm, spec) : orthonormalize(mesh, cm);
  if (!deformation) return deformation.error();
  const Index available = deformation->eigenvalues.size();
  const Index k = spec.keep_modes < 0 ? available : spec.keep_modes;
  if (k > available)
    return make_error(ErrorCode::size_mismatch, "asked for ", k,
                      " deformation modes but the reduction basis has only ", available,
                      " (Craig-Bampton gives 6k - 6 + n for k six-DOF interface nodes and n "
                      "fixed-interface modes)");
  const MatrixXd modes = deformation->modes.leftCols(k);
  auto integrals = inertia_integrals(mesh, cm.model.dofs, modes, spec.mass);
  if (!integrals) return integrals.error();
  ModalBodyData d;
  d.method = cm.method;
  d.mass_options = spec.mass;
  d.num_modes = k;
  d.inertia = std::move(*integrals);
  d.eigenvalues = deformation->eigenvalues.head(k);
  d.damping_ratios = VectorXd::Constant(k, spec.damping_ratio);
  d.modal_stiffness = spec.interface_attached_frame
                          ? MatrixXd(modes.transpose() * (cm.model.stiffness_all * modes))
                          : MatrixXd(d.eigenvalues.asDiagonal());
  d.mass_residual = deformation->mass_residual;
  d.stiffness_residual = deformation->stiffness_residual;
  const Index nn = mesh.num_nodes();
  d.phi_translation = MatrixXd::Zero(3 * nn, k);
  d.phi_rotation = MatrixXd::Zero(3 * nn, k);
  for (Index n = 0; n < nn; ++n) {
    d.node_positions.push_back(mesh.node(n));
    d.node_has_rotation.push_back(cm.model.dofs.has_rotations(n) ? 1 : 0);
    for (int c = 0; c < cm.model.dofs.num_node_dofs(n); ++c)
      (c < 3 ? d.phi_translation : d.phi_rotation).row(3 * n + c % 3) =
          modes.row(cm.model.dofs.dof(n, c));
  }
  for (const auto& in : spec.interface) d.interface_nodes.push_back(in.node);
  return d;
}
#else
    ;
#endif

/// The whole precompute: component modes (Craig-Bampton or Craig-Chang), orthonormalization,
/// inertia integrals, mode shapes at every node.
FLEXSTRESS_PRECOMPUTE
Result<ModalBodyData> reduce(const fe::Mesh& mesh, const ReductionSpec& spec)
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  if (!(spec.damping_ratio >= 0.0) || !(spec.damping_ratio < 1.0))
    return make_error(ErrorCode::invalid_argument, "modal damping ratio must lie in [0, 1), got ",
                      spec.damping_ratio);
  auto cm = spec.method == ReductionMethod::craig_bampton
                ? craig_bampton(mesh, spec.interface, spec.dynamic_modes, spec.mass, spec.eigen)
                : craig_chang(mesh, spec.interface, spec.dynamic_modes, spec.mass, spec.eigen);
  if (!cm) return cm.error();
  return make_modal_body(mesh, *cm, spec);
}
#else
    ;
#endif

}  // namespace flexstress::reduction

// This header's precompute entry points (core/precompute.hpp).
#define FLEXSTRESS_PRECOMPUTE_REDUCTION_MODAL_BODY_DATA(X)                                \
  X(12, Result<reduction::ModalBodyData>, reduction::make_modal_body,                     \
    (const fe::Mesh&, const reduction::ComponentModes&, const reduction::ReductionSpec&)) \
  X(12, Result<reduction::ModalBodyData>, reduction::reduce,                              \
    (const fe::Mesh&, const reduction::ReductionSpec&))
namespace flexstress {
FLEXSTRESS_PRECOMPUTE_EXTERN(FLEXSTRESS_PRECOMPUTE_REDUCTION_MODAL_BODY_DATA)
}  // namespace flexstress
