// The few scalar constraint equations every joint is built from (Nikravesh, Computer-Aided
// Analysis of Mechanical Systems, ch. 7; Shabana, ch. 3), written on evaluated markers.
//
// For each equation phi(q, t) = 0 a row carries: phi; its Jacobian rows for the two bodies
// (d phi/dt = b_i v_i + b_j v_j + phi_t); phi_t (explicit time derivative); and `conv`, every
// part of the second time derivative except b v_dot (so the acceleration constraint reads
// b_i v_dot_i + b_j v_dot_j = -conv).
#pragma once

#include <Eigen/Core>

#include "flexstress/core/types.hpp"
#include "flexstress/dynamics/marker.hpp"

namespace flexstress {

template <class Scalar, int NVI, int NVJ>
struct ConstraintRow {
  Scalar phi = Scalar(0);
  Scalar phi_t = Scalar(0);
  Scalar conv = Scalar(0);
  Eigen::Matrix<Scalar, 1, NVI> bi;
  Eigen::Matrix<Scalar, 1, NVJ> bj;
};

namespace constraint {

/// a_i . b_j = 0: two axes stay perpendicular (dot-1 constraint).
template <class Scalar, int NI, int NJ>
ConstraintRow<Scalar, 6 + NI, 6 + NJ> perpendicular(const MarkerEval<Scalar, NI>& mi, int axis_i,
                                                    const MarkerEval<Scalar, NJ>& mj, int axis_j) {
  const auto& a = mi.axis(axis_i);
  const auto& b = mj.axis(axis_j);
  ConstraintRow<Scalar, 6 + NI, 6 + NJ> r;
  r.phi = a.value.dot(b.value);
  r.bi = mi.row_axis(axis_i, b.value);
  r.bj = mj.row_axis(axis_j, a.value);
  r.conv = a.convective.dot(b.value) + Scalar(2) * a.velocity.dot(b.velocity) +
           a.value.dot(b.convective);
  return r;
}

/// a_i . (r_j - r_i) = 0: the origin of marker j stays in the plane of marker i normal to a_i
/// (dot-2 constraint).
template <class Scalar, int NI, int NJ>
ConstraintRow<Scalar, 6 + NI, 6 + NJ> in_plane(const MarkerEval<Scalar, NI>& mi, int axis_i,
                                               const MarkerEval<Scalar, NJ>& mj) {
  const auto& a = mi.axis(axis_i);
  const Vec3<Scalar> d = mj.origin.value - mi.origin.value;
  const Vec3<Scalar> d_dot = mj.origin.velocity - mi.origin.velocity;
  ConstraintRow<Scalar, 6 + NI, 6 + NJ> r;
  r.phi = a.value.dot(d);
  r.bi = mi.row_axis(axis_i, d) - mi.row_origin(a.value);
  r.bj = mj.row_origin(a.value);
  r.conv = a.convective.dot(d) + Scalar(2) * a.velocity.dot(d_dot) +
           a.value.dot(Vec3<Scalar>(mj.origin.convective - mi.origin.convective));
  return r;
}

/// Component k of r_j - r_i = 0 (spherical joint rows).
template <class Scalar, int NI, int NJ>
ConstraintRow<Scalar, 6 + NI, 6 + NJ> coincident(const MarkerEval<Scalar, NI>& mi,
                                                 const MarkerEval<Scalar, NJ>& mj, int k) {
  const Vec3<Scalar> e = Vec3<Scalar>::Unit(k);
  ConstraintRow<Scalar, 6 + NI, 6 + NJ> r;
  r.phi = mj.origin.value(k) - mi.origin.value(k);
  r.bi = -mi.row_origin(e);
  r.bj = mj.row_origin(e);
  r.conv = mj.origin.convective(k) - mi.origin.convective(k);
  return r;
}

/// (r_j - r_i) . (r_j - r_i) - L^2 = 0.
template <class Scalar, int NI, int NJ>
ConstraintRow<Scalar, 6 + NI, 6 + NJ> distance(const MarkerEval<Scalar, NI>& mi,
                                               const MarkerEval<Scalar, NJ>& mj, Scalar length) {
  const Vec3<Scalar> d = mj.origin.value - mi.origin.value;
  const Vec3<Scalar> d_dot = mj.origin.velocity - mi.origin.velocity;
  ConstraintRow<Scalar, 6 + NI, 6 + NJ> r;
  r.phi = d.squaredNorm() - length * length;
  r.bi = -Scalar(2) * mi.row_origin(d);
  r.bj = Scalar(2) * mj.row_origin(d);
  r.conv = Scalar(2) * d_dot.squaredNorm() +
           Scalar(2) * d.dot(Vec3<Scalar>(mj.origin.convective - mi.origin.convective));
  return r;
}

/// Velocity of a_i . b_j (needed by rheonomic drivers that combine two dot products).
template <class Scalar, int NI, int NJ>
Scalar perpendicular_rate(const MarkerEval<Scalar, NI>& mi, int axis_i,
                          const MarkerEval<Scalar, NJ>& mj, int axis_j) {
  return mi.axis(axis_i).velocity.dot(mj.axis(axis_j).value) +
         mi.axis(axis_i).value.dot(mj.axis(axis_j).velocity);
}

}  // namespace constraint
}  // namespace flexstress
