// Modal body data: everything an FFRF body needs from a reduced FE model (Model side,
// immutable, double precision, runtime mode count). reduce() (reduction/modal_body_data.hpp)
// builds it from an FE model, read_modal_body() (reduction/modal_body_io.hpp) from a file; the
// dynamics layer turns it into a compile-time-sized body by truncation and cast. This header is
// the data alone, so that what runs a model does not compile the FE kernel.
//
// Frames: the body frame is the mesh frame (x, y, z of the nodes as given); the frame origin is
// the mesh origin, not necessarily the centre of mass (the FFRF equations keep the general
// first-moment terms).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/fe/mass_options.hpp"
#include "flexstress/reduction/inertia_moments.hpp"
#include "flexstress/reduction/reduction_method.hpp"

namespace flexstress::reduction {

struct ModalBodyData {
  ReductionMethod method = ReductionMethod::craig_bampton;
  fe::MassOptions mass_options;
  Index num_modes = 0;

  // Inertia integrals (body frame): index 0 = undeformed position, 1..n = modes.
  InertiaIntegrals inertia;

  VectorXd eigenvalues;     ///< omega^2 of the deformation modes, ascending
  VectorXd damping_ratios;  ///< modal damping ratio zeta per mode (0 = undamped)
  /// Modal stiffness Phi^T K Phi (n x n): diag(eigenvalues) for orthonormalized modes. Kept as a
  /// matrix so that bodies with any mode set (not orthonormal, not mass-orthogonal to rigid
  /// motion) run through the same, general equations.
  MatrixXd modal_stiffness;

  // Mode shapes at every node of the mesh (body frame): rows 3i..3i+2 belong to node i.
  // Rotations are zero at nodes without rotational DOFs (node_has_rotation == 0).
  std::vector<Vector3d> node_positions;
  std::vector<unsigned char> node_has_rotation;
  MatrixXd phi_translation;  ///< 3 n_nodes x n
  MatrixXd phi_rotation;     ///< 3 n_nodes x n

  std::vector<Index> interface_nodes;
  double mass_residual = 0.0;       ///< || Phi^T M Phi - I ||_max of the orthonormalization
  double stiffness_residual = 0.0;  ///< || Phi^T K Phi - diag ||_max / lambda_max

  double mass() const { return inertia.mass; }
  /// Centre of mass of the undeformed body, body frame.
  Vector3d center_of_mass() const { return inertia.first[0] / inertia.mass; }
  /// Inertia tensor of the undeformed body about the frame origin: tr(L00) 1 - L00.
  Matrix3d inertia_about_origin() const {
    const Matrix3d& l = inertia.lambda(0, 0);
    return l.trace() * Matrix3d::Identity() - l;
  }
  Index num_nodes() const { return static_cast<Index>(node_positions.size()); }
  /// The node nearest to x (body frame; the first of equally near ones), -1 for a body
  /// without nodes: where a program that has only the body data finds a marker's node.
  Index nearest_node(const Vector3d& x) const {
    Index best = -1;
    double best_distance = 0.0;
    for (Index i = 0; i < num_nodes(); ++i) {
      const double d = (node_positions[static_cast<std::size_t>(i)] - x).squaredNorm();
      if (best < 0 || d < best_distance) {
        best = i;
        best_distance = d;
      }
    }
    return best;
  }
  /// Translational mode shapes (3 x n) at a node.
  auto phi_r(Index node) const { return phi_translation.middleRows<3>(3 * node); }
  /// Rotational mode shapes (3 x n) at a node.
  auto phi_theta(Index node) const { return phi_rotation.middleRows<3>(3 * node); }

  /// The same body with only the lowest k modes (k <= num_modes). Every invariant of the
  /// truncated body is a sub-block of this one, so nothing is recomputed.
  Result<ModalBodyData> truncated(Index k) const {
    if (k < 0 || k > num_modes)
      return make_error(ErrorCode::size_mismatch, "truncation to ", k, " modes: the body has ",
                        num_modes);
    ModalBodyData t = *this;
    t.num_modes = k;
    t.eigenvalues = eigenvalues.head(k);
    t.damping_ratios = damping_ratios.head(k);
    t.modal_stiffness = modal_stiffness.topLeftCorner(k, k);
    t.phi_translation = phi_translation.leftCols(k);
    t.phi_rotation = phi_rotation.leftCols(k);
    t.inertia.num_modes = k;
    t.inertia.first.resize(static_cast<std::size_t>(k + 1));
    t.inertia.second.assign(static_cast<std::size_t>((k + 1) * (k + 1)), Matrix3d::Zero());
    for (Index a = 0; a <= k; ++a)
      for (Index b = 0; b <= k; ++b) t.inertia.lambda(a, b) = inertia.lambda(a, b);
    return t;
  }
};

}  // namespace flexstress::reduction
