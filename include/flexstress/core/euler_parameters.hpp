// Euler parameters (unit quaternions, scalar first) and the matrices of the FFRF kinematics.
//
// Conventions (see docs/notation.md and the reference sheet on FFRF equations):
//   theta = (e0, e1, e2, e3), |theta| = 1, e0 the scalar part.
//   A(theta) rotates body-frame vectors into the global frame: x_global = A x_body.
//   G(theta), G_bar(theta) (3x4): w_global = 2 G theta_dot, w_body = 2 G_bar theta_dot,
//   theta_dot = 1/2 G_bar^T w_body. (The paper's eq. 4 misses the factor 2; its eq. 2 misses
//   an overall factor 2 and is only valid for unit theta.)
//   Composition: A(a (x) b) = A(a) A(b), so a body-frame rotation increment multiplies on the
//   right: theta_new = theta (x) exp(phi_body).
#pragma once

#include <cmath>
#include <limits>

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products

#include "flexstress/core/assert.hpp"
#include "flexstress/core/scalar_traits.hpp"
#include "flexstress/core/skew.hpp"
#include "flexstress/core/types.hpp"

namespace flexstress {

template <class Scalar>
using EulerParameters = Vec4<Scalar>;

/// The identity rotation (1, 0, 0, 0).
template <class Scalar>
EulerParameters<Scalar> identity_euler_parameters() {
  return EulerParameters<Scalar>(Scalar(1), Scalar(0), Scalar(0), Scalar(0));
}

/// Rotation matrix A(theta) (Nikravesh; Shabana eq. 2.60). Orthogonal only for |theta| = 1;
/// this form keeps A linear-quadratic in theta so its derivatives stay simple.
template <class Scalar>
Mat3<Scalar> rotation_matrix(const EulerParameters<Scalar>& t) {
  const Scalar e0 = t(0), e1 = t(1), e2 = t(2), e3 = t(3);
  Mat3<Scalar> a;
  a << e0 * e0 + e1 * e1 - e2 * e2 - e3 * e3, Scalar(2) * (e1 * e2 - e0 * e3),
      Scalar(2) * (e1 * e3 + e0 * e2),  //
      Scalar(2) * (e1 * e2 + e0 * e3), e0 * e0 - e1 * e1 + e2 * e2 - e3 * e3,
      Scalar(2) * (e2 * e3 - e0 * e1),  //
      Scalar(2) * (e1 * e3 - e0 * e2), Scalar(2) * (e2 * e3 + e0 * e1),
      e0 * e0 - e1 * e1 - e2 * e2 + e3 * e3;
  return a;
}

/// G_bar(theta) (paper eq. 5): w_body = 2 G_bar theta_dot, and G_bar theta = 0.
template <class Scalar>
Mat34<Scalar> g_bar_matrix(const EulerParameters<Scalar>& t) {
  const Scalar e0 = t(0), e1 = t(1), e2 = t(2), e3 = t(3);
  Mat34<Scalar> g;
  g << -e1, e0, e3, -e2,  //
      -e2, -e3, e0, e1,   //
      -e3, e2, -e1, e0;
  return g;
}

/// G(theta): w_global = 2 G theta_dot, G theta = 0, and A = G G_bar^T for unit theta.
template <class Scalar>
Mat34<Scalar> g_matrix(const EulerParameters<Scalar>& t) {
  const Scalar e0 = t(0), e1 = t(1), e2 = t(2), e3 = t(3);
  Mat34<Scalar> g;
  g << -e1, e0, -e3, e2,  //
      -e2, e3, e0, -e1,   //
      -e3, -e2, e1, e0;
  return g;
}

/// Body-frame angular velocity from Euler parameter rates: w = 2 G_bar theta_dot.
template <class Scalar>
Vec3<Scalar> body_angular_velocity(const EulerParameters<Scalar>& theta,
                                   const EulerParameters<Scalar>& theta_dot) {
  return Scalar(2) * g_bar_matrix(theta) * theta_dot;
}

/// Euler parameter rates from body-frame angular velocity: theta_dot = 1/2 G_bar^T w
/// (needs |theta| = 1).
template <class Scalar>
EulerParameters<Scalar> euler_parameter_rates(const EulerParameters<Scalar>& theta,
                                              const Vec3<Scalar>& w_body) {
  return Scalar(0.5) * g_bar_matrix(theta).transpose() * w_body;
}

/// Quaternion product a (x) b, scalar first; A(a (x) b) = A(a) A(b).
template <class Scalar>
EulerParameters<Scalar> compose(const EulerParameters<Scalar>& a,
                                const EulerParameters<Scalar>& b) {
  EulerParameters<Scalar> c;
  c(0) = a(0) * b(0) - a.template tail<3>().dot(b.template tail<3>());
  c.template tail<3>() = a(0) * b.template tail<3>() + b(0) * a.template tail<3>() +
                         a.template tail<3>().cross(b.template tail<3>());
  return c;
}

/// The inverse rotation (conjugate) of a unit theta.
template <class Scalar>
EulerParameters<Scalar> conjugate(const EulerParameters<Scalar>& t) {
  return EulerParameters<Scalar>(t(0), -t(1), -t(2), -t(3));
}

/// theta / |theta|. A zero or non-finite theta (a diverging time step, not a programming error)
/// gives NaN, which the integrators report as a failed step instead of aborting.
template <class Scalar>
EulerParameters<Scalar> normalized(const EulerParameters<Scalar>& t) {
  const Scalar n = t.norm();
  if (!(n > Scalar(0)) || !std::isfinite(n))
    return EulerParameters<Scalar>::Constant(std::numeric_limits<Scalar>::quiet_NaN());
  return t / n;
}

/// Exponential map: the unit theta of the rotation vector phi (axis * angle). Uses a series
/// near zero so that it is smooth and exact to rounding for small increments.
template <class Scalar>
EulerParameters<Scalar> exp_rotation(const Vec3<Scalar>& phi) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  const Scalar angle2 = phi.squaredNorm();
  Scalar c, s_over_angle;  // cos(angle/2), sin(angle/2)/angle
  if (angle2 < ScalarTraits<Scalar>::small_angle * ScalarTraits<Scalar>::small_angle) {
    c = Scalar(1) - angle2 / Scalar(8) + angle2 * angle2 / Scalar(384);
    s_over_angle = Scalar(0.5) - angle2 / Scalar(48) + angle2 * angle2 / Scalar(3840);
  } else {
    const Scalar angle = sqrt(angle2);
    c = cos(angle / Scalar(2));
    s_over_angle = sin(angle / Scalar(2)) / angle;
  }
  EulerParameters<Scalar> t;
  t(0) = c;
  t.template tail<3>() = s_over_angle * phi;
  return t;
}

/// Logarithm: the rotation vector phi (|phi| <= pi) of a unit theta. Robust at 0 and at pi
/// (uses atan2 of the vector and scalar parts, and picks the representative with e0 >= 0).
template <class Scalar>
Vec3<Scalar> log_rotation(const EulerParameters<Scalar>& theta) {
  using std::atan2;
  EulerParameters<Scalar> t = theta(0) < Scalar(0) ? EulerParameters<Scalar>(-theta) : theta;
  const Vec3<Scalar> v = t.template tail<3>();
  const Scalar vn = v.norm();
  if (vn < ScalarTraits<Scalar>::small_angle) {
    // angle = 2 atan(vn / e0) = 2 vn / e0 (1 - vn^2 / (3 e0^2) + ...)
    const Scalar r = vn / t(0);
    return (Scalar(2) / t(0)) * (Scalar(1) - r * r / Scalar(3)) * v;
  }
  return (Scalar(2) * atan2(vn, t(0)) / vn) * v;
}

/// theta from a rotation vector given as unit axis and angle (radians).
template <class Scalar>
EulerParameters<Scalar> from_axis_angle(const Vec3<Scalar>& axis, Scalar angle) {
  return exp_rotation<Scalar>(axis.normalized() * angle);
}

/// Unit theta of a rotation matrix (Shepperd's method: picks the largest of the four
/// squared components, so it stays accurate near 180 degrees). Returns e0 >= 0.
template <class Scalar>
EulerParameters<Scalar> from_rotation_matrix(const Mat3<Scalar>& a) {
  using std::sqrt;
  const Scalar tr = a.trace();
  // 4 e_i^2 for i = 0..3
  const Scalar d[4] = {Scalar(1) + tr, Scalar(1) + Scalar(2) * a(0, 0) - tr,
                       Scalar(1) + Scalar(2) * a(1, 1) - tr, Scalar(1) + Scalar(2) * a(2, 2) - tr};
  int k = 0;
  for (int i = 1; i < 4; ++i)
    if (d[i] > d[k]) k = i;
  const Scalar s = sqrt(d[k]) * Scalar(0.5);  // |e_k|
  const Scalar f = Scalar(0.25) / s;          // 1 / (4 e_k)
  EulerParameters<Scalar> t;
  switch (k) {
    case 0:
      t << s, (a(2, 1) - a(1, 2)) * f, (a(0, 2) - a(2, 0)) * f, (a(1, 0) - a(0, 1)) * f;
      break;
    case 1:
      t << (a(2, 1) - a(1, 2)) * f, s, (a(0, 1) + a(1, 0)) * f, (a(0, 2) + a(2, 0)) * f;
      break;
    case 2:
      t << (a(0, 2) - a(2, 0)) * f, (a(0, 1) + a(1, 0)) * f, s, (a(1, 2) + a(2, 1)) * f;
      break;
    default:
      t << (a(1, 0) - a(0, 1)) * f, (a(0, 2) + a(2, 0)) * f, (a(1, 2) + a(2, 1)) * f, s;
      break;
  }
  if (t(0) < Scalar(0)) t = -t;
  return t / t.norm();
}

/// Rotation angle (radians, in [0, pi]) and unit axis of a unit theta. For a zero rotation the
/// axis is undefined and (1, 0, 0) is returned.
template <class Scalar>
void to_axis_angle(const EulerParameters<Scalar>& theta, Vec3<Scalar>& axis, Scalar& angle) {
  const Vec3<Scalar> phi = log_rotation(theta);
  angle = phi.norm();
  axis = angle > Scalar(0) ? Vec3<Scalar>(phi / angle) : Vec3<Scalar>::UnitX();
}

/// Right Jacobian of the exponential map of SO(3), T(phi): exp(phi + d) = exp(phi) exp(T d)
/// to first order. Body-frame angular velocity of exp(phi(t)) is T(phi) phi_dot. Used by the
/// Lie-group integrators (Bruls and Cardona 2010, eq. 15).
template <class Scalar>
Mat3<Scalar> right_jacobian_so3(const Vec3<Scalar>& phi) {
  using std::cos;
  using std::sin;
  const Scalar a2 = phi.squaredNorm();
  const Mat3<Scalar> k = skew(phi);
  Scalar c1, c2;  // (1 - cos a) / a^2, (a - sin a) / a^3
  if (a2 < ScalarTraits<Scalar>::small_angle * ScalarTraits<Scalar>::small_angle) {
    c1 = Scalar(0.5) - a2 / Scalar(24);
    c2 = Scalar(1) / Scalar(6) - a2 / Scalar(120);
  } else {
    using std::sqrt;
    const Scalar a = sqrt(a2);
    c1 = (Scalar(1) - cos(a)) / a2;
    c2 = (a - sin(a)) / (a2 * a);
  }
  return Mat3<Scalar>::Identity() - c1 * k + c2 * k * k;
}

}  // namespace flexstress
