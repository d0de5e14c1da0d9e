// What keeping fewer modes than a body's data holds costs its static shapes: the static
// flexibility the kept modes carry at a node's DOF, against all of the data's modes.
//
// A load f at DOF i of a body deflects it there by f_ii f in its modal coordinates, with the
// direct flexibility f_ii = phi_i^T K^-1 phi_i over the modes kept (phi_i: the row of the mode
// shapes at DOF i, K the modal stiffness; for orthonormal modes the sum of phi_k(i)^2 / omega_k^2).
// Joints load a body at its interface nodes, and after orthonormalization a Craig-Bampton
// basis's static constraint modes, which carry that flexibility, are among its highest modes: a
// body that keeps its lowest modes only can lose most of it, and with it the static shape and
// stress near the joints (docs/reduction.md, "Keeping fewer modes than the basis").
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "flexstress/core/types.hpp"
#include "flexstress/reduction/modal_body.hpp"

namespace flexstress::reduction {

/// The direct static flexibility of the lowest `modes` modes of `data` at DOF `dof` of `node`
/// (0 to 2: translation x, y, z in the body frame, m/N; 3 to 5: rotation about x, y, z,
/// rad/(N m)): phi_i^T K^-1 phi_i with K the kept modes' block of the modal stiffness. 0 for no
/// modes; NaN for a node or DOF the data does not have, or a modal stiffness that is not
/// positive definite.
inline double modal_flexibility(const ModalBodyData& data, Index node, int dof, Index modes) {
  const Index n = std::min<Index>(std::max<Index>(modes, 0), data.num_modes);
  if (node < 0 || node >= data.num_nodes() || dof < 0 || dof > 5)
    return std::numeric_limits<double>::quiet_NaN();
  if (n == 0) return 0.0;
  const MatrixXd& shapes = dof < 3 ? data.phi_translation : data.phi_rotation;
  const VectorXd row = shapes.row(3 * node + dof % 3).head(n).transpose();
  const Eigen::LLT<MatrixXd> k(data.modal_stiffness.topLeftCorner(n, n));
  if (k.info() != Eigen::Success) return std::numeric_limits<double>::quiet_NaN();
  return row.dot(k.solve(row));
}

/// The share of one interface DOF's flexibility that the lowest `kept` modes carry.
struct KeptFlexibility {
  Index node = -1;        ///< the interface node
  int dof = -1;           ///< 0 to 2 translation, 3 to 5 rotation
  double fraction = 1.0;  ///< kept flexibility over the whole basis's, at that DOF
};

/// The share of the flexibility at each interface DOF that the lowest `kept` modes carry, by
/// node and DOF (DOFs the modes do not move are left out: a clamped interface node of a body
/// reduced with one interface). A share well below 1 at a DOF a joint loads means the kept
/// modes cannot take the static shape that load makes. An axial or torsional DOF whose share is
/// 0 is a body kept rigid along or about its axis, which may be what was meant.
inline std::vector<KeptFlexibility> kept_interface_flexibility(const ModalBodyData& data,
                                                               Index kept) {
  std::vector<KeptFlexibility> out;
  if (data.num_modes == 0) return out;
  // A DOF no mode moves beyond round-off of the largest motion of its kind (translation or
  // rotation) anywhere on the body has no flexibility to keep (its share would be 0 / 0).
  const double largest[2] = {data.phi_translation.cwiseAbs().maxCoeff(),
                             data.phi_rotation.cwiseAbs().maxCoeff()};
  for (const Index node : data.interface_nodes)
    for (int dof = 0; dof < 6; ++dof) {
      const MatrixXd& shapes = dof < 3 ? data.phi_translation : data.phi_rotation;
      if (!(shapes.row(3 * node + dof % 3).cwiseAbs().maxCoeff() > 1e-9 * largest[dof / 3]))
        continue;
      const double all = modal_flexibility(data, node, dof, data.num_modes);
      out.push_back({node, dof, modal_flexibility(data, node, dof, kept) / all});
    }
  return out;
}

/// The interface DOF whose flexibility the lowest `kept` modes carry the smallest share of, if
/// that share is under `share` (docs/reduction.md asks for 0.99 at the DOFs joints load); none
/// when the body keeps all its data's modes. What ModelBuilder warns of (Model::warnings).
inline std::optional<KeptFlexibility> least_kept_interface_flexibility(const ModalBodyData& data,
                                                                       Index kept,
                                                                       double share = 0.99) {
  if (kept >= data.num_modes) return std::nullopt;
  std::optional<KeptFlexibility> least;
  for (const KeptFlexibility& k : kept_interface_flexibility(data, kept))
    if (k.fraction < share && (!least || k.fraction < least->fraction)) least = k;
  return least;
}

/// "translation along x" ... "rotation about z" for DOF 0 to 5 of a node.
inline const char* dof_name(int dof) {
  static const char* const names[6] = {"translation along x", "translation along y",
                                       "translation along z", "rotation about x",
                                       "rotation about y",    "rotation about z"};
  return dof >= 0 && dof < 6 ? names[dof] : "no DOF";
}

/// What ModelBuilder warns of for body `name` keeping the lowest `kept` modes of `data`: the
/// least kept share under 99 %, naming the node and DOF; "" if there is none (or no modes).
inline std::string truncation_warning(const std::string& name, const ModalBodyData& data,
                                      Index kept) {
  const auto least = kept > 0 ? least_kept_interface_flexibility(data, kept) : std::nullopt;
  if (!least) return {};
  char percent[32];
  std::snprintf(percent, sizeof percent, "%.6g", std::round(1000 * least->fraction) / 10);
  return "body '" + name + "': its lowest " + std::to_string(kept) + " of the data's " +
         std::to_string(data.num_modes) + " modes carry " + percent +
         " % of the static flexibility at interface node " + std::to_string(least->node) + ", " +
         dof_name(least->dof) +
         ": a joint loading it there cannot take its static shape; choose the count in the "
         "reduction and keep all its modes";
}

}  // namespace flexstress::reduction
