// The deformed shape of a flexible body at points of the user's choice: render vertices, a
// camera or sensor mount, the tip a game shows. Each point is carried by a host point of the
// body (a node, or a place between two nodes of a beam, host_point.hpp) and a rigid offset from
// it, so its elastic displacement per modal coordinate is
//   Phi_i = Phi_u(host) - skew(offset) Phi_theta(host)      (small rotation of the offset)
// and its global position x_i = R + A(theta) (x0_i + Phi_i p) (the FFRF kinematics of the paper's
// eq. 9-11). Built once (allocates); evaluate() is a 3 x n by n x modes product per call and
// never allocates, so a renderer can call it every frame.
#pragma once

#include <algorithm>
#include <limits>
#include <vector>

#include <Eigen/Core>

#include "flexstress/core/euler_parameters.hpp"
#include "flexstress/core/skew.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/reduction/modal_body.hpp"
#include "flexstress/stress/host_point.hpp"

namespace flexstress::stress {

/// A point that follows the body: its host point and its offset from it (body frame).
struct ShapePoint {
  HostPoint host;
  Vector3d offset = Vector3d::Zero();
};

/// Positions of points on a flexible body with NModes modal coordinates (Eigen::Dynamic: all of
/// the body data's modes, a count chosen at run time).
template <int NModes, class Scalar = double>
class DeformedShape {
 public:
  using Points = Eigen::Matrix<Scalar, 3, Eigen::Dynamic>;

  /// Errors: those of boundary_modes (a missing node, a node without rotations, xi outside
  /// [0, 1]), a non-finite offset, and a body with fewer than NModes modes.
  static Result<DeformedShape> build(const reduction::ModalBodyData& body,
                                     const std::vector<ShapePoint>& points) {
    if (body.num_modes < NModes)
      return make_error(ErrorCode::size_mismatch, "deformed shape: the body has ", body.num_modes,
                        " modes, the shape was compiled for ", NModes);
    std::vector<HostPoint> hosts;
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (!points[i].offset.allFinite())
        return make_error(ErrorCode::invalid_argument, "deformed shape: point ", i,
                          " has a non-finite offset");
      hosts.push_back(points[i].host);
    }
    auto phi_b = boundary_modes(body, hosts);
    if (!phi_b) return phi_b.error();
    DeformedShape shape;
    const Index n = static_cast<Index>(points.size());
    const Index modes = NModes == Eigen::Dynamic ? body.num_modes : NModes;
    shape.rest_.resize(3, n);
    shape.phi_.resize(3 * n, modes);
    for (Index i = 0; i < n; ++i) {
      const ShapePoint& pt = points[static_cast<std::size_t>(i)];
      const Vector3d xa = body.node_positions[static_cast<std::size_t>(pt.host.node_a)];
      const Vector3d host =
          pt.host.node_b < 0
              ? xa
              : xa + pt.host.xi *
                         (body.node_positions[static_cast<std::size_t>(pt.host.node_b)] - xa);
      shape.rest_.col(i) = (host + pt.offset).cast<Scalar>();
      const auto rows = phi_b->middleRows(6 * i, 6).leftCols(modes);
      shape.phi_.middleRows(3 * i, 3) =
          (rows.topRows(3) - skew(pt.offset) * rows.bottomRows(3)).template cast<Scalar>();
    }
    return shape;
  }

  /// Points given by their undeformed body-frame positions near a beam line (consecutive body
  /// nodes `line`): each is hosted at the nearest point of the line and offset from it rigidly.
  static Result<DeformedShape> along_beam(
      const reduction::ModalBodyData& body, const std::vector<Index>& line,
      const std::vector<Vector3d>& positions,
      BoundaryInterpolation interpolation = BoundaryInterpolation::hermite) {
    if (line.size() < 2)
      return make_error(ErrorCode::invalid_argument,
                        "deformed shape: a beam line needs at least two nodes, got ", line.size());
    for (Index node : line)
      if (node < 0 || node >= body.num_nodes())
        return make_error(ErrorCode::invalid_argument, "deformed shape: line node ", node,
                          " does not exist (the body has ", body.num_nodes(), " nodes)");
    std::vector<ShapePoint> points;
    for (std::size_t v = 0; v < positions.size(); ++v) {
      if (!positions[v].allFinite())
        return make_error(ErrorCode::invalid_argument, "deformed shape: vertex ", v,
                          " has a non-finite position");
      double best = std::numeric_limits<double>::infinity();
      ShapePoint chosen;
      for (std::size_t k = 0; k + 1 < line.size(); ++k) {
        const Vector3d& a = body.node_positions[static_cast<std::size_t>(line[k])];
        const Vector3d& b = body.node_positions[static_cast<std::size_t>(line[k + 1])];
        const Vector3d d = b - a;
        const double len2 = d.squaredNorm();
        const double xi = len2 > 0.0 ? std::clamp((positions[v] - a).dot(d) / len2, 0.0, 1.0) : 0.0;
        const Vector3d foot = a + xi * d;
        const double dist = (positions[v] - foot).norm();
        if (dist < best) {
          best = dist;
          chosen.host = HostPoint::between(line[k], line[k + 1], xi, interpolation);
          chosen.offset = positions[v] - foot;
        }
      }
      points.push_back(chosen);
    }
    return build(body, points);
  }

  Index size() const { return rest_.cols(); }
  /// Undeformed body-frame positions (3 x size).
  const Points& rest() const { return rest_; }
  /// Elastic displacement per modal coordinate (3 size x NModes), body frame.
  const Eigen::Matrix<Scalar, Eigen::Dynamic, NModes>& modes() const { return phi_; }

  /// Global positions x_i = R + A(theta) (x0_i + Phi_i p) into out (3 x size, sized by the
  /// caller). Never allocates.
  template <class P, class Out>
  void evaluate(const Vec3<Scalar>& r, const EulerParameters<Scalar>& theta,
                const Eigen::MatrixBase<P>& p, Out& out) const {
    const Mat3<Scalar> a = rotation_matrix<Scalar>(theta);
    for (Index i = 0; i < size(); ++i)
      out.col(i).noalias() = r + a * (rest_.col(i) + phi_.template middleRows<3>(3 * i) * p);
  }

 private:
  Points rest_;
  Eigen::Matrix<Scalar, Eigen::Dynamic, NModes> phi_;
};

}  // namespace flexstress::stress
