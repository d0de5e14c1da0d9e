// Where a sub-model's attachment point sits on its host body, and how the host's elastic
// deformation there is read: at a host node, or between two nodes of a straight beam element
// with linear interpolation of translations and rotations (as in Rantalainen et al. 2013) or
// with the beam's own cubic Hermite shape functions (exact for an Euler-Bernoulli beam loaded
// only at its nodes).
//
// The result is the boundary mode matrix Phi_b (6 k x n): rows 6a..6a+5 hold the translation
// and small rotation of attachment point a per unit modal coordinate, body frame. Then
// u_b = Phi_b p, and a sub-model output with influence row h has the fused modal row h Phi_b.
#pragma once

#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/skew.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/reduction/modal_body.hpp"

namespace flexstress::stress {

enum class BoundaryInterpolation {
  linear,   ///< translations and rotations linear between the nodes (the paper)
  hermite,  ///< cubic Hermite transverse displacement, its slope as rotation; linear axial, twist
};

/// How a sub-model attachment passes the host's state at its point (sub_model.hpp).
enum class AttachmentDrive {
  displacement,  ///< the master follows the host's displacement and rotation (the paper)
  force,         ///< the master carries the host's section force and moment
};

/// A host point: at `node_a` (node_b < 0), or at fraction `xi` in [0, 1] from node_a to node_b
/// of a straight beam element.
struct HostPoint {
  Index node_a = -1;
  Index node_b = -1;
  double xi = 0.0;
  BoundaryInterpolation interpolation = BoundaryInterpolation::linear;

  static HostPoint at_node(Index n) { return {n, -1, 0.0, BoundaryInterpolation::linear}; }
  static HostPoint between(Index a, Index b, double xi,
                           BoundaryInterpolation k = BoundaryInterpolation::linear) {
    return {a, b, xi, k};
  }
};

/// The 6 x 12 matrix that maps the nodal displacements [u_a, theta_a, u_b, theta_b] of a straight
/// beam from xa to xb to [u, theta] at fraction xi. Hermite: with axis e, length L and P = I - e
/// e^T, u_perp(xi) = H1 P u_a + H2 L (theta_a x e) + H3 P u_b + H4 L (theta_b x e) (since du/ds =
/// theta x e for a Bernoulli beam), theta_perp = e x du_perp/ds, axial displacement and twist
/// linear.
inline Eigen::Matrix<double, 6, 12> beam_point_interpolation(const Vector3d& xa, const Vector3d& xb,
                                                             double xi,
                                                             BoundaryInterpolation kind) {
  Eigen::Matrix<double, 6, 12> n = Eigen::Matrix<double, 6, 12>::Zero();
  const Matrix3d id = Matrix3d::Identity();
  if (kind == BoundaryInterpolation::linear) {
    for (int k = 0; k < 2; ++k) {
      const double w = k == 0 ? 1.0 - xi : xi;
      n.block<3, 3>(0, 6 * k) = w * id;
      n.block<3, 3>(3, 6 * k + 3) = w * id;
    }
    return n;
  }
  const Vector3d d = xb - xa;
  const double len = d.norm();
  const Vector3d e = d / len;
  const Matrix3d axial = e * e.transpose(), perp = id - axial;
  // theta x e = -skew(e) theta.
  const Matrix3d slope_of_theta = -skew(e);
  const double x = xi, x2 = xi * xi, x3 = x2 * xi;
  const double h1 = 1 - 3 * x2 + 2 * x3, h2 = x - 2 * x2 + x3, h3 = 3 * x2 - 2 * x3, h4 = x3 - x2;
  // Derivatives with respect to s = xi L.
  const double d1 = (-6 * x + 6 * x2) / len, d2 = 1 - 4 * x + 3 * x2, d3 = (6 * x - 6 * x2) / len,
               d4 = 3 * x2 - 2 * x;
  n.block<3, 3>(0, 0) = (1 - x) * axial + h1 * perp;
  n.block<3, 3>(0, 3) = h2 * len * perp * slope_of_theta;
  n.block<3, 3>(0, 6) = x * axial + h3 * perp;
  n.block<3, 3>(0, 9) = h4 * len * perp * slope_of_theta;
  const Matrix3d ex = skew(e);
  n.block<3, 3>(3, 0) = ex * (d1 * perp);
  n.block<3, 3>(3, 3) = (1 - x) * axial + ex * (d2 * perp * slope_of_theta);
  n.block<3, 3>(3, 6) = ex * (d3 * perp);
  n.block<3, 3>(3, 9) = x * axial + ex * (d4 * perp * slope_of_theta);
  return n;
}

/// Phi_b (6 k x n) of the host points on a reduced body. Fails, naming the point, for a node
/// that does not exist, a node without rotational DOFs (the rotation of an attachment point must
/// be known), coincident nodes or xi outside [0, 1].
FLEXSTRESS_PRECOMPUTE
Result<MatrixXd> boundary_modes(const reduction::ModalBodyData& host,
                                const std::vector<HostPoint>& points)
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  const Index n = host.num_modes;
  MatrixXd phi = MatrixXd::Zero(6 * static_cast<Index>(points.size()), n);
  auto node_rows = [&](Index node, std::size_t a) -> Result<Eigen::Matrix<double, 6, -1>> {
    if (node < 0 || node >= host.num_nodes())
      return make_error(ErrorCode::invalid_argument, "sub-model attachment ", a, ": host node ",
                        node, " does not exist (the host has ", host.num_nodes(), " nodes)");
    if (!host.node_has_rotation[static_cast<std::size_t>(node)])
      return make_error(ErrorCode::invalid_argument, "sub-model attachment ", a, ": host node ",
                        node, " has no rotational DOFs, so the rotation there is unknown");
    Eigen::Matrix<double, 6, -1> r(6, n);
    r.topRows<3>() = host.phi_r(node);
    r.bottomRows<3>() = host.phi_theta(node);
    return r;
  };
  for (std::size_t a = 0; a < points.size(); ++a) {
    const HostPoint& p = points[a];
    auto ra = node_rows(p.node_a, a);
    if (!ra) return ra.error();
    const auto row = 6 * static_cast<Index>(a);
    if (p.node_b < 0) {
      phi.middleRows<6>(row) = *ra;
      continue;
    }
    auto rb = node_rows(p.node_b, a);
    if (!rb) return rb.error();
    if (!(p.xi >= 0.0 && p.xi <= 1.0))
      return make_error(ErrorCode::invalid_argument, "sub-model attachment ", a, ": xi = ", p.xi,
                        " is outside [0, 1]");
    const Vector3d& xa = host.node_positions[static_cast<std::size_t>(p.node_a)];
    const Vector3d& xb = host.node_positions[static_cast<std::size_t>(p.node_b)];
    if (!((xb - xa).norm() > 0.0))
      return make_error(ErrorCode::invalid_argument, "sub-model attachment ", a, ": host nodes ",
                        p.node_a, " and ", p.node_b, " coincide");
    const Eigen::Matrix<double, 6, 12> interp =
        beam_point_interpolation(xa, xb, p.xi, p.interpolation);
    phi.middleRows<6>(row) = interp.leftCols<6>() * *ra + interp.rightCols<6>() * *rb;
  }
  return phi;
}
#else
    ;
#endif

/// Position of a host point in the body frame (undeformed).
inline Vector3d host_point_position(const reduction::ModalBodyData& host, const HostPoint& p) {
  const Vector3d& xa = host.node_positions[static_cast<std::size_t>(p.node_a)];
  if (p.node_b < 0) return xa;
  return (1 - p.xi) * xa + p.xi * host.node_positions[static_cast<std::size_t>(p.node_b)];
}

}  // namespace flexstress::stress

// This header's precompute entry points (core/precompute.hpp).
#define FLEXSTRESS_PRECOMPUTE_STRESS_HOST_POINT(X) \
  X(10, Result<MatrixXd>, stress::boundary_modes,  \
    (const reduction::ModalBodyData&, const std::vector<stress::HostPoint>&))
namespace flexstress {
FLEXSTRESS_PRECOMPUTE_EXTERN(FLEXSTRESS_PRECOMPUTE_STRESS_HOST_POINT)
}  // namespace flexstress
