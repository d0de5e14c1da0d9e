// Joint equations on evaluated markers, independent of the bodies' mode counts.
//
// A constraint row's Jacobian on one body is b^T J summed over the marker vectors it reads
// (dynamics/body_vector.hpp): b^T J = [b^T (points) | (u x A^T b)^T | (A^T b)^T Psi]. The first
// six columns need only the evaluated marker (u, A); the modal columns are the weights
// g = A^T b times the vector's mode shapes Psi. So a joint kernel writes, per row and body,
// the six rigid columns and one weight per marker vector (RowSide), and the body's own
// fixed-size kernel expands the weights into its modal columns. Joint kernels then compile once
// for all mode counts, and body kernels once per count.
//
// Equations (Nikravesh, Computer-Aided Analysis of Mechanical Systems, ch. 7; Shabana, ch. 3):
//   spherical 3, revolute 5, universal 4, cylindrical 4, prismatic 5, fixed 6, distance 1,
//   prismatic driver 1 ((r_j - r_i) . z_i = s(t)), revolute driver 1 (angle x_i -> x_j about
//   z_i = phi(t)). Each row carries phi, phi_t (explicit time derivative) and conv (the second
//   time derivative without its B v_dot part).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <type_traits>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "flexstress/core/types.hpp"
#include "flexstress/dynamics/marker.hpp"
#include "flexstress/dynamics/motion_laws.hpp"

namespace flexstress {

enum class JointKind : std::uint8_t {
  spherical,
  revolute,
  universal,
  cylindrical,
  prismatic,
  fixed,
  distance,
  prismatic_driver,
  revolute_driver,
};

inline const char* to_string(JointKind k) {
  switch (k) {
    case JointKind::spherical: return "spherical";
    case JointKind::revolute: return "revolute";
    case JointKind::universal: return "universal";
    case JointKind::cylindrical: return "cylindrical";
    case JointKind::prismatic: return "prismatic";
    case JointKind::fixed: return "fixed";
    case JointKind::distance: return "distance";
    case JointKind::prismatic_driver: return "prismatic driver";
    case JointKind::revolute_driver: return "revolute driver";
  }
  return "unknown";
}

/// Equations of a joint kind.
constexpr int joint_equations(JointKind k) {
  switch (k) {
    case JointKind::spherical: return 3;
    case JointKind::revolute: return 5;
    case JointKind::universal: return 4;
    case JointKind::cylindrical: return 4;
    case JointKind::prismatic: return 5;
    case JointKind::fixed: return 6;
    case JointKind::distance: return 1;
    case JointKind::prismatic_driver: return 1;
    case JointKind::revolute_driver: return 1;
  }
  return 0;
}
inline constexpr int max_joint_equations = 6;

/// Whether the kind has a motion law (a driver).
constexpr bool is_driver(JointKind k) {
  return k == JointKind::prismatic_driver || k == JointKind::revolute_driver;
}

/// Marker parts (MarkerParts bits) a kind reads on marker i and on marker j: only those are
/// evaluated.
constexpr unsigned joint_parts_i(JointKind k) {
  using P = MarkerParts;
  switch (k) {
    case JointKind::spherical: return P::origin;
    case JointKind::revolute: return P::origin | P::z;
    case JointKind::universal: return P::origin | P::z;
    case JointKind::cylindrical: return P::all;
    case JointKind::prismatic: return P::all;
    case JointKind::fixed: return P::origin | P::x | P::z;
    case JointKind::distance: return P::origin;
    case JointKind::prismatic_driver: return P::origin | P::z;
    case JointKind::revolute_driver: return P::x | P::y;
  }
  return P::all;
}
constexpr unsigned joint_parts_j(JointKind k) {
  using P = MarkerParts;
  switch (k) {
    case JointKind::spherical: return P::origin;
    case JointKind::revolute: return P::origin | P::x | P::y;
    case JointKind::universal: return P::origin | P::z;
    case JointKind::cylindrical: return P::origin | P::x | P::y;
    case JointKind::prismatic: return P::origin | P::x | P::y;
    case JointKind::fixed: return P::origin | P::x | P::y;
    case JointKind::distance: return P::origin;
    case JointKind::prismatic_driver: return P::origin;
    case JointKind::revolute_driver: return P::x;
  }
  return P::all;
}

/// A marker evaluated on its body: its four vectors and the body's rotation A.
template <class Scalar>
struct MarkerState {
  VectorEval<Scalar> origin, x, y, z;
  Mat3<Scalar> rotation = Mat3<Scalar>::Identity();
  const VectorEval<Scalar>& axis(int a) const { return a == 0 ? x : a == 1 ? y : z; }
  /// Axis A (0 x, 1 y, 2 z) chosen at compile time: the joint kernels' rows name theirs.
  template <int A>
  const VectorEval<Scalar>& axis() const {
    static_assert(A >= 0 && A < 3, "a marker has axes 0 (x), 1 (y) and 2 (z)");
    if constexpr (A == 0) return x;
    if constexpr (A == 1) return y;
    if constexpr (A == 2) return z;
  }
};

/// One row's Jacobian on one body: six rigid columns and the weights of the modal columns,
/// g_v per marker vector v (origin, x, y, z), in the body frame. Only the weights named in
/// `parts` hold values: a row starts with none, and the first addition to a weight sets it, so
/// a row never writes the twelve weights it mostly leaves unused. A joint's rows start with a
/// set_ call (which writes all six rigid columns) and go on with add_ calls: nothing is cleared.
template <class Scalar>
struct RowSide {
  Eigen::Matrix<Scalar, 1, 6> rigid = Eigen::Matrix<Scalar, 1, 6>::Zero();
  std::array<Vec3<Scalar>, 4> weight{Vec3<Scalar>::Zero(), Vec3<Scalar>::Zero(),
                                     Vec3<Scalar>::Zero(), Vec3<Scalar>::Zero()};
  /// The marker vectors (MarkerParts bits) this row weighs: its modal part sums Psi over
  /// these only (a revolute's coincidence rows read the origin, its perpendicularity rows one
  /// axis each, although the joint as a whole reads three vectors).
  unsigned parts = 0;

  // Written out in scalars: these run for every row of every joint at every Newton iterate,
  // and as Eigen expressions GCC left their 3-vector products to out-of-line calls.

  /// += s b^T J_origin (the origin is a point): [s b^T | (u x bb)^T | bb^T Psi], bb = s A^T b.
  FLEXSTRESS_ALWAYS_INLINE void add_origin(const MarkerState<Scalar>& m, const Vec3<Scalar>& b,
                                           Scalar s = Scalar(1)) {
    const Vec3<Scalar> bb = turned(m.rotation, b, s);
    for (int c = 0; c < 3; ++c) rigid(c) += s * b(c);
    add_moment_and_weight(m.origin.local, bb, 0);
  }
  /// = s b^T J_origin: the row from scratch.
  FLEXSTRESS_ALWAYS_INLINE void set_origin(const MarkerState<Scalar>& m, const Vec3<Scalar>& b,
                                           Scalar s = Scalar(1)) {
    for (int c = 0; c < 3; ++c) rigid(c) = s * b(c);
    set_moment_and_weight(m.origin.local, turned(m.rotation, b, s), 0);
  }
  /// = s e_c^T J_origin: one coordinate of the origin (A^T e_c is row c of A).
  template <int C>
  FLEXSTRESS_ALWAYS_INLINE void set_origin_component(const MarkerState<Scalar>& m, Scalar s) {
    const Mat3<Scalar>& a = m.rotation;
    for (int k = 0; k < 3; ++k) rigid(k) = k == C ? s : Scalar(0);
    set_moment_and_weight(m.origin.local, Vec3<Scalar>(s * a(C, 0), s * a(C, 1), s * a(C, 2)), 0);
  }
  /// += s b^T J_axis(a) (a direction: no translation column).
  FLEXSTRESS_ALWAYS_INLINE void add_axis(const MarkerState<Scalar>& m, int a, const Vec3<Scalar>& b,
                                         Scalar s = Scalar(1)) {
    add_moment_and_weight(m.axis(a).local, turned(m.rotation, b, s), 1 + a);
  }
  /// = s b^T J_axis(A): the row from scratch.
  template <int A>
  FLEXSTRESS_ALWAYS_INLINE void set_axis(const MarkerState<Scalar>& m, const Vec3<Scalar>& b,
                                         Scalar s = Scalar(1)) {
    for (int c = 0; c < 3; ++c) rigid(c) = Scalar(0);
    set_moment_and_weight(m.template axis<A>().local, turned(m.rotation, b, s), 1 + A);
  }
  /// The row of a s + b t (for combining rows).
  static RowSide combine(Scalar s, const RowSide& a, Scalar t, const RowSide& b) {
    RowSide r;
    r.rigid = s * a.rigid + t * b.rigid;
    for (std::size_t k = 0; k < 4; ++k) {
      const unsigned bit = 1u << k;
      if (a.parts & bit) r.weight[k] += s * a.weight[k];
      if (b.parts & bit) r.weight[k] += t * b.weight[k];
    }
    r.parts = a.parts | b.parts;
    return r;
  }

 private:
  /// s A^T b.
  static FLEXSTRESS_ALWAYS_INLINE Vec3<Scalar> turned(const Mat3<Scalar>& a, const Vec3<Scalar>& b,
                                                      Scalar s) {
    const Scalar b0 = s * b(0), b1 = s * b(1), b2 = s * b(2);
    return Vec3<Scalar>(a(0, 0) * b0 + a(1, 0) * b1 + a(2, 0) * b2,
                        a(0, 1) * b0 + a(1, 1) * b1 + a(2, 1) * b2,
                        a(0, 2) * b0 + a(1, 2) * b1 + a(2, 2) * b2);
  }
  /// rigid's rotation columns = (u x bb)^T, weight[v] = bb, and only v in parts.
  FLEXSTRESS_ALWAYS_INLINE void set_moment_and_weight(const Vec3<Scalar>& u, const Vec3<Scalar>& bb,
                                                      int v) {
    rigid(3) = u(1) * bb(2) - u(2) * bb(1);
    rigid(4) = u(2) * bb(0) - u(0) * bb(2);
    rigid(5) = u(0) * bb(1) - u(1) * bb(0);
    weight[static_cast<std::size_t>(v)] = bb;
    parts = 1u << v;
  }
  /// rigid's rotation columns += (u x bb)^T, weight[v] += bb (= bb if not yet in parts).
  FLEXSTRESS_ALWAYS_INLINE void add_moment_and_weight(const Vec3<Scalar>& u, const Vec3<Scalar>& bb,
                                                      int v) {
    rigid(3) += u(1) * bb(2) - u(2) * bb(1);
    rigid(4) += u(2) * bb(0) - u(0) * bb(2);
    rigid(5) += u(0) * bb(1) - u(1) * bb(0);
    Vec3<Scalar>& w = weight[static_cast<std::size_t>(v)];
    const unsigned bit = 1u << v;
    if (parts & bit)
      for (int c = 0; c < 3; ++c) w(c) += bb(c);
    else
      w = bb;
    parts |= bit;
  }
};

/// The rows of one joint. Each row helper below writes every field of its rows, so the rows
/// are not cleared between joints.
template <class Scalar>
struct JointRows {
  int count = 0;
  std::array<Scalar, max_joint_equations> phi{}, phi_t{}, conv{};
  std::array<RowSide<Scalar>, max_joint_equations> i{}, j{};
};

namespace joint_rows {

template <class Scalar>
using Rows = JointRows<Scalar>;

// Each helper writes row r whole: phi, phi_t (0: the joints hold without time), conv (0 without
// rates: a Newton iterate needs Phi and B alone, and its markers carry no velocities) and both
// sides. Out of line, one copy shared by the joint kinds: inlined
// into every case of the switch below they made it too large for the instruction cache
// (measured on the crane's step).

/// a_i . b_j = 0 (dot-1), axis AI of marker i and AJ of marker j (compile-time: a row's axes
/// are fixed by its joint kind).
template <int AI, int AJ, class Scalar>
FLEXSTRESS_NOINLINE_FLATTEN void perpendicular(const MarkerState<Scalar>& mi,
                                               const MarkerState<Scalar>& mj, Rows<Scalar>& out,
                                               int r, bool rates) {
  const auto k = static_cast<std::size_t>(r);
  const auto& a = mi.template axis<AI>();
  const auto& b = mj.template axis<AJ>();
  out.phi[k] = a.value.dot(b.value);
  out.phi_t[k] = Scalar(0);
  out.i[k].template set_axis<AI>(mi, b.value);
  out.j[k].template set_axis<AJ>(mj, a.value);
  out.conv[k] = rates ? a.convective.dot(b.value) + Scalar(2) * a.velocity.dot(b.velocity) +
                            a.value.dot(b.convective)
                      : Scalar(0);
}

/// a_i . (r_j - r_i) = 0 (dot-2), axis AI of marker i.
template <int AI, class Scalar>
FLEXSTRESS_NOINLINE_FLATTEN void in_plane(const MarkerState<Scalar>& mi,
                                          const MarkerState<Scalar>& mj, Rows<Scalar>& out, int r,
                                          bool rates) {
  const auto k = static_cast<std::size_t>(r);
  const auto& a = mi.template axis<AI>();
  const Vec3<Scalar> d = mj.origin.value - mi.origin.value;
  out.phi[k] = a.value.dot(d);
  out.phi_t[k] = Scalar(0);
  out.i[k].template set_axis<AI>(mi, d);
  out.i[k].add_origin(mi, a.value, Scalar(-1));
  out.j[k].set_origin(mj, a.value);
  out.conv[k] = Scalar(0);
  if (rates) {
    const Vec3<Scalar> d_dot = mj.origin.velocity - mi.origin.velocity;
    out.conv[k] = a.convective.dot(d) + Scalar(2) * a.velocity.dot(d_dot) +
                  a.value.dot(Vec3<Scalar>(mj.origin.convective - mi.origin.convective));
  }
}

/// r_j - r_i = 0, rows r to r + 2.
template <class Scalar>
FLEXSTRESS_NOINLINE_FLATTEN void coincident(const MarkerState<Scalar>& mi,
                                            const MarkerState<Scalar>& mj, Rows<Scalar>& out, int r,
                                            bool rates) {
  const auto row = [&](auto component) {
    constexpr int c = decltype(component)::value;
    const auto k = static_cast<std::size_t>(r + c);
    out.phi[k] = mj.origin.value(c) - mi.origin.value(c);
    out.phi_t[k] = Scalar(0);
    out.i[k].template set_origin_component<c>(mi, Scalar(-1));
    out.j[k].template set_origin_component<c>(mj, Scalar(1));
    out.conv[k] = rates ? mj.origin.convective(c) - mi.origin.convective(c) : Scalar(0);
  };
  row(std::integral_constant<int, 0>{});
  row(std::integral_constant<int, 1>{});
  row(std::integral_constant<int, 2>{});
}

/// |r_j - r_i|^2 - L^2 = 0.
template <class Scalar>
FLEXSTRESS_NOINLINE_FLATTEN void distance(const MarkerState<Scalar>& mi,
                                          const MarkerState<Scalar>& mj, Scalar length,
                                          Rows<Scalar>& out, int r, bool rates) {
  const auto k = static_cast<std::size_t>(r);
  const Vec3<Scalar> d = mj.origin.value - mi.origin.value;
  out.phi[k] = d.squaredNorm() - length * length;
  out.phi_t[k] = Scalar(0);
  out.i[k].set_origin(mi, d, Scalar(-2));
  out.j[k].set_origin(mj, d, Scalar(2));
  out.conv[k] = Scalar(0);
  if (rates) {
    const Vec3<Scalar> d_dot = mj.origin.velocity - mi.origin.velocity;
    out.conv[k] = Scalar(2) * d_dot.squaredNorm() +
                  Scalar(2) * d.dot(Vec3<Scalar>(mj.origin.convective - mi.origin.convective));
  }
}

/// Rate of a_i . b_j.
template <class Scalar>
Scalar perpendicular_rate(const MarkerState<Scalar>& mi, int ai, const MarkerState<Scalar>& mj,
                          int aj) {
  return mi.axis(ai).velocity.dot(mj.axis(aj).value) + mi.axis(ai).value.dot(mj.axis(aj).velocity);
}

}  // namespace joint_rows

/// The rows of a joint of kind `kind` between evaluated markers i and j at time t. `length` is
/// a distance joint's; `law` a driver's prescribed motion at t. Without rates, conv is left at
/// zero (the markers were evaluated without velocities).
template <class Scalar>
void evaluate_joint_rows(JointKind kind, const MarkerState<Scalar>& i, const MarkerState<Scalar>& j,
                         Scalar length, const MotionValue<Scalar>& law, JointRows<Scalar>& out,
                         bool rates = true) {
  namespace jr = joint_rows;
  out.count = joint_equations(kind);
  switch (kind) {
    case JointKind::spherical: jr::coincident(i, j, out, 0, rates); return;
    case JointKind::revolute:
      jr::coincident(i, j, out, 0, rates);
      jr::perpendicular<2, 0>(i, j, out, 3, rates);
      jr::perpendicular<2, 1>(i, j, out, 4, rates);
      return;
    case JointKind::universal:
      jr::coincident(i, j, out, 0, rates);
      jr::perpendicular<2, 2>(i, j, out, 3, rates);
      return;
    case JointKind::cylindrical:
      jr::in_plane<0>(i, j, out, 0, rates);
      jr::in_plane<1>(i, j, out, 1, rates);
      jr::perpendicular<2, 0>(i, j, out, 2, rates);
      jr::perpendicular<2, 1>(i, j, out, 3, rates);
      return;
    case JointKind::prismatic:
      jr::in_plane<0>(i, j, out, 0, rates);
      jr::in_plane<1>(i, j, out, 1, rates);
      jr::perpendicular<2, 0>(i, j, out, 2, rates);
      jr::perpendicular<2, 1>(i, j, out, 3, rates);
      jr::perpendicular<0, 1>(i, j, out, 4, rates);
      return;
    case JointKind::fixed:
      jr::coincident(i, j, out, 0, rates);
      jr::perpendicular<2, 0>(i, j, out, 3, rates);
      jr::perpendicular<2, 1>(i, j, out, 4, rates);
      jr::perpendicular<0, 1>(i, j, out, 5, rates);
      return;
    case JointKind::distance: jr::distance(i, j, length, out, 0, rates); return;
    case JointKind::prismatic_driver:
      jr::in_plane<2>(i, j, out, 0, rates);
      out.phi[0] -= law.value;
      out.phi_t[0] = -law.rate;
      out.conv[0] -= law.acceleration;
      return;
    case JointKind::revolute_driver: {
      // cos(phi) (y_i . x_j) - sin(phi) (x_i . x_j) = sin(theta - phi) = 0 for the angle theta
      // from x_i to x_j about z_i: it grows with theta, as the prismatic driver's with the
      // stroke, so that both drivers' efforts are -lambda (readouts.hpp, driver_effort).
      using std::cos;
      using std::sin;
      const Scalar s = sin(law.value), c = cos(law.value);
      const Scalar sd = c * law.rate, cd = -s * law.rate;
      const Scalar sdd = -s * law.rate * law.rate + c * law.acceleration;
      const Scalar cdd = -c * law.rate * law.rate - s * law.acceleration;
      JointRows<Scalar> ab;
      ab.count = 2;
      jr::perpendicular<0, 0>(i, j, ab, 0, true);  // x_i . x_j = cos(theta)
      jr::perpendicular<1, 0>(i, j, ab, 1, true);  // y_i . x_j = sin(theta)
      const Scalar a_dot = jr::perpendicular_rate(i, 0, j, 0);
      const Scalar b_dot = jr::perpendicular_rate(i, 1, j, 0);
      out.phi[0] = -(s * ab.phi[0] - c * ab.phi[1]);
      out.i[0] = RowSide<Scalar>::combine(-s, ab.i[0], c, ab.i[1]);
      out.j[0] = RowSide<Scalar>::combine(-s, ab.j[0], c, ab.j[1]);
      out.phi_t[0] = -(sd * ab.phi[0] - cd * ab.phi[1]);
      out.conv[0] = -(sdd * ab.phi[0] + Scalar(2) * sd * a_dot + s * ab.conv[0] - cdd * ab.phi[1] -
                      Scalar(2) * cd * b_dot - c * ab.conv[1]);
      return;
    }
  }
}

}  // namespace flexstress
