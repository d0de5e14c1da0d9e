// A vector attached to a (flexible) body: the primitive of joints, markers and forces.
//
// In the body frame a point or a direction of a deformable body is affine in the modal
// coordinates: u = c + Psi p. A node: c = u0, Psi = Phi_R. A point at a rigid offset d from a
// node, carried by the node's small rotation I + skew(Phi_theta p) (paper eq. 9-11):
// c = u0 + d, Psi = Phi_R - skew(d) Phi_theta. A direction e0 at a node:
// c = e0, Psi = -skew(e0) Phi_theta. A rigid body is the case Psi = 0 (zero modes).
//
// Globally x = [R] + A u (R only for points). With body velocities v = [R_dot; w; p_dot]
// (w in the body frame) everything a constraint needs follows exactly:
//   x_dot  = J v,  J = [I (points) | -A skew(u) | A Psi],
//   x_ddot = J v_dot + A (w x (w x u) + 2 w x Psi p_dot)   (the convective part),
//   b^T J  = [b^T (points) | (u x A^T b)^T | (A^T b)^T Psi].
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "flexstress/core/skew.hpp"
#include "flexstress/core/types.hpp"

namespace flexstress {

/// The kinematic state of one body needed to evaluate body vectors: orientation A, modal
/// coordinates p, body angular velocity w and modal velocities p_dot.
/// NModes may be Eigen::Dynamic (a mode count chosen at run time): then p and p_dot are
/// sized by the caller, in storage bounded by max_runtime_modes.
template <class Scalar, int NModes>
struct BodyKinematics {
  using VecN = typename ModalSizes<Scalar, NModes>::VecN;
  Vec3<Scalar> position = Vec3<Scalar>::Zero();      ///< R
  Vec3<Scalar> velocity = Vec3<Scalar>::Zero();      ///< R_dot
  Mat3<Scalar> rotation = Mat3<Scalar>::Identity();  ///< A
  VecN p = VecN::Zero(NModes == Eigen::Dynamic ? 0 : NModes);
  Vec3<Scalar> omega = Vec3<Scalar>::Zero();  ///< w, body frame
  VecN p_dot = VecN::Zero(NModes == Eigen::Dynamic ? 0 : NModes);
  Index modes() const { return p.size(); }
};

template <class Scalar, int NModes>
struct BodyVector {
  using Sizes = ModalSizes<Scalar, NModes>;
  static constexpr int nv = Sizes::nv;
  using RowV = typename Sizes::RowV;

  Vec3<Scalar> c = Vec3<Scalar>::Zero();
  typename Sizes::Mat3NRows psi = Sizes::Mat3NRows::Zero(3, NModes == Eigen::Dynamic ? 0 : NModes);
  bool is_point = false;

  /// Body-frame value u = c + Psi p.
  Vec3<Scalar> local(const BodyKinematics<Scalar, NModes>& k) const {
    if constexpr (NModes == 0) {
      return c;
    } else {
      return c + psi * k.p;
    }
  }
  /// Global value x = [R] + A u.
  Vec3<Scalar> global(const BodyKinematics<Scalar, NModes>& k) const {
    return global_from_local(k, local(k));
  }
  /// Global time derivative J v.
  Vec3<Scalar> velocity(const BodyKinematics<Scalar, NModes>& k) const {
    Vec3<Scalar> v, c;
    rates_from_local(k, local(k), v, c);
    return v;
  }
  /// Convective acceleration A (w x (w x u) + 2 w x Psi p_dot): x_ddot = J v_dot + this.
  Vec3<Scalar> convective(const BodyKinematics<Scalar, NModes>& k) const {
    Vec3<Scalar> v, c;
    rates_from_local(k, local(k), v, c);
    return c;
  }
  /// Row vector b^T J (1 x nv) for a global vector b.
  RowV row(const BodyKinematics<Scalar, NModes>& k, const Vec3<Scalar>& b) const {
    return row(k, local(k), b);
  }

  // The same with the body-frame value u = local(k) already known: a marker evaluates it once
  // and every row and rate of the vector reuses it (with ten modes it is 30 of a row's 75
  // multiply-adds).
  Vec3<Scalar> global_from_local(const BodyKinematics<Scalar, NModes>& k,
                                 const Vec3<Scalar>& u) const {
    const Vec3<Scalar> g = k.rotation * u;
    return is_point ? Vec3<Scalar>(k.position + g) : g;
  }
  /// Velocity and convective acceleration together: both need w x u and Psi p_dot.
  void rates_from_local(const BodyKinematics<Scalar, NModes>& k, const Vec3<Scalar>& u,
                        Vec3<Scalar>& velocity, Vec3<Scalar>& convective) const {
    const Vec3<Scalar> w_u = k.omega.cross(u);
    Vec3<Scalar> body_velocity = w_u;
    Vec3<Scalar> body_convective = k.omega.cross(w_u);
    if constexpr (NModes != 0) {
      const Vec3<Scalar> u_dot = psi * k.p_dot;  // deformation rate
      body_velocity += u_dot;
      body_convective += Scalar(2) * k.omega.cross(u_dot);
    }
    velocity = k.rotation * body_velocity;
    if (is_point) velocity += k.velocity;
    convective = k.rotation * body_convective;
  }
  RowV row(const BodyKinematics<Scalar, NModes>& k, const Vec3<Scalar>& u,
           const Vec3<Scalar>& b) const {
    RowV r(1, 6 + psi.cols());
    const Vec3<Scalar> bb = k.rotation.transpose() * b;
    if (is_point)
      r.template head<3>() = b.transpose();
    else
      r.template head<3>().setZero();
    r.template segment<3>(3) = u.cross(bb).transpose();
    if constexpr (NModes != 0) r.template segment<NModes>(6, psi.cols()) = bb.transpose() * psi;
    return r;
  }
  /// Full Jacobian J (3 x nv), global rows.
  typename Sizes::Mat3V jacobian(const BodyKinematics<Scalar, NModes>& k) const {
    typename Sizes::Mat3V j(3, 6 + psi.cols());
    j.template leftCols<3>() = is_point ? Mat3<Scalar>::Identity() : Mat3<Scalar>::Zero();
    j.template middleCols<3>(3) = -k.rotation * skew(local(k));
    if constexpr (NModes != 0) j.template rightCols<NModes>(psi.cols()) = k.rotation * psi;
    return j;
  }
};

/// A point fixed in a rigid body (or the undeformed position of a flexible one).
template <class Scalar, int NModes = 0>
BodyVector<Scalar, NModes> body_point(const Vec3<Scalar>& c) {
  BodyVector<Scalar, NModes> v;
  v.c = c;
  v.is_point = true;
  return v;
}

/// A direction fixed in a rigid body.
template <class Scalar, int NModes = 0>
BodyVector<Scalar, NModes> body_direction(const Vec3<Scalar>& e) {
  BodyVector<Scalar, NModes> v;
  v.c = e;
  v.is_point = false;
  return v;
}

}  // namespace flexstress
