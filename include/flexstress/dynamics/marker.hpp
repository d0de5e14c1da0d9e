// Markers: frames attached to bodies (a point and three axes), where joints and force elements
// act. On a flexible body a marker sits at a node (or at a rigid offset from it) and follows the
// node's translation and small rotation (paper eq. 9-11); on a rigid body anywhere.
#pragma once

#include <cmath>
#include <limits>

#include <Eigen/Core>

#include "flexstress/core/types.hpp"
#include "flexstress/dynamics/body_vector.hpp"

namespace flexstress {

/// Compile-time index of the ground in joint and force definitions.
inline constexpr int ground = -1;

template <class Scalar, int NModes>
struct Marker {
  BodyVector<Scalar, NModes> origin;
  BodyVector<Scalar, NModes> x, y, z;
};

/// Builds a marker on `body` at `node` (flexible bodies; -1 for rigid bodies: then `offset` is
/// the position) with a rigid offset and an orientation (columns: marker axes, body frame).
template <class Body, class Scalar = typename Body::scalar_type>
Marker<Scalar, Body::num_modes> make_marker(
    const Body& body, Index node, const Vec3<typename Body::scalar_type>& offset,
    const Mat3<typename Body::scalar_type>& axes = Mat3<typename Body::scalar_type>::Identity()) {
  Marker<Scalar, Body::num_modes> m;
  m.origin = body.point(node, offset);
  m.x = body.direction(node, axes.col(0));
  m.y = body.direction(node, axes.col(1));
  m.z = body.direction(node, axes.col(2));
  return m;
}

/// A marker fixed in the ground (or in a rigid body without nodes): position and axes.
template <class Scalar>
Marker<Scalar, 0> fixed_marker(const Vec3<Scalar>& position,
                               const Mat3<Scalar>& axes = Mat3<Scalar>::Identity()) {
  Marker<Scalar, 0> m;
  m.origin = body_point<Scalar, 0>(position);
  m.x = body_direction<Scalar, 0>(axes.col(0));
  m.y = body_direction<Scalar, 0>(axes.col(1));
  m.z = body_direction<Scalar, 0>(axes.col(2));
  return m;
}

/// An orthonormal frame whose z axis is `axis` (x and y completed deterministically).
template <class Scalar>
Mat3<Scalar> frame_with_z_axis(const Vec3<Scalar>& axis) {
  const Vec3<Scalar> z = axis.normalized();
  const Vec3<Scalar> helper =
      std::abs(z.x()) < Scalar(0.9) ? Vec3<Scalar>::UnitX() : Vec3<Scalar>::UnitY();
  const Vec3<Scalar> x = (helper - helper.dot(z) * z).normalized();
  Mat3<Scalar> f;
  f.col(0) = x;
  f.col(1) = z.cross(x);
  f.col(2) = z;
  return f;
}

/// The parts of a marker a joint reads (bit set). A joint evaluates only those: a spherical
/// joint reads the two origins and none of the six axes, a revolute joint one axis of marker i
/// and two of marker j.
struct MarkerParts {
  static constexpr unsigned origin = 1u, x = 2u, y = 4u, z = 8u, all = 15u;
};

/// One evaluated body vector: global value, velocity and convective acceleration, and the
/// body-frame value u = c + Psi p that its Jacobian rows reuse.
template <class Scalar>
struct VectorEval {
  Vec3<Scalar> value, velocity, convective, local;
};

/// Evaluates body vector v at k into e. Without rates, velocity and convective terms are zero;
/// a part not wanted is NaN (see MarkerEval::evaluate).
template <class Scalar, int NModes>
void evaluate_vector(const BodyVector<Scalar, NModes>& v, const BodyKinematics<Scalar, NModes>& k,
                     VectorEval<Scalar>& e, bool rates, bool wanted) {
  if (!wanted) {
    e.value.setConstant(std::numeric_limits<Scalar>::quiet_NaN());
    e.local = e.velocity = e.convective = e.value;
    return;
  }
  e.local = v.local(k);
  e.value = v.global_from_local(k, e.local);
  if (rates) {
    v.rates_from_local(k, e.local, e.velocity, e.convective);
  } else {
    e.velocity.setZero();
    e.convective.setZero();
  }
}

/// A marker evaluated at a body state: what joints and force elements read.
template <class Scalar, int NModes>
struct MarkerEval {
  static constexpr int nv = size_sum(NModes, 6);
  using RowV = typename BodyVector<Scalar, NModes>::RowV;
  const Marker<Scalar, NModes>* marker = nullptr;
  const BodyKinematics<Scalar, NModes>* kin = nullptr;
  VectorEval<Scalar> origin, x, y, z;

  /// Evaluates the marker at k. With rates == false only the values are computed (velocities
  /// and convective terms are set to zero): a Newton iteration needs Phi and B, not Phi_t or
  /// the convective terms, and skipping them saves two thirds of the work. Only the `parts`
  /// named are evaluated (MarkerParts); the others are set to NaN, so a joint that reads a
  /// part it did not declare produces NaN rows, which every Jacobian test catches.
  void evaluate(const Marker<Scalar, NModes>& m, const BodyKinematics<Scalar, NModes>& k,
                bool rates = true, unsigned parts = MarkerParts::all) {
    marker = &m;
    kin = &k;
    evaluate_vector(m.origin, k, origin, rates, parts & MarkerParts::origin);
    evaluate_vector(m.x, k, x, rates, parts & MarkerParts::x);
    evaluate_vector(m.y, k, y, rates, parts & MarkerParts::y);
    evaluate_vector(m.z, k, z, rates, parts & MarkerParts::z);
  }
  /// Row b^T J of the marker origin or of an axis (1 x nv).
  RowV row_origin(const Vec3<Scalar>& b) const { return marker->origin.row(*kin, origin.local, b); }
  RowV row_axis(int a, const Vec3<Scalar>& b) const {
    return (a == 0 ? marker->x : a == 1 ? marker->y : marker->z).row(*kin, axis(a).local, b);
  }
  const VectorEval<Scalar>& axis(int a) const { return a == 0 ? x : a == 1 ? y : z; }
  /// Jacobian of the origin (3 x nv).
  typename ModalSizes<Scalar, NModes>::Mat3V jacobian_origin() const {
    return marker->origin.jacobian(*kin);
  }
};

}  // namespace flexstress
