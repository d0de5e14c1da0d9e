// Joints and drivers between two bodies (compile-time body indices I and J; `ground` = -1),
// each a fixed number of scalar equations built from constraint_primitives.hpp on the two
// joint markers (marker i on body I, marker j on body J). Equation counts are compile-time
// constants, so a scene knows its constraint count at compile time, and so are the parts of
// each marker a joint reads (parts_i, parts_j: MarkerParts), so a scene evaluates only those.
//
//   Spherical    3  origins coincide
//   Revolute     5  + z_i perpendicular to x_j and y_j (rotation about the common z axis)
//   Universal    4  + z_i perpendicular to z_j (cross axes z_i, z_j)
//   Cylindrical  4  origin j on the z_i line, z_i parallel to z_j
//   Prismatic    5  + x_i perpendicular to y_j (no rotation about z)
//   Fixed        6  spherical + three perpendicularities
//   Distance     1  |r_j - r_i| = L
//   PrismaticDriver  1  (r_j - r_i) . z_i = s(t)
//   RevoluteDriver   1  angle from x_i to x_j about z_i = phi(t)
#pragma once

#include <cmath>

#include "flexstress/core/types.hpp"
#include "flexstress/dynamics/constraint_primitives.hpp"
#include "flexstress/dynamics/marker.hpp"
#include "flexstress/dynamics/motion_laws.hpp"

namespace flexstress {

/// Joint parameters for joints that have none.
template <class Scalar>
struct NoParams {};

template <int I, int J>
struct Spherical {
  static constexpr int body_i = I, body_j = J, equations = 3;
  static constexpr unsigned parts_i = MarkerParts::origin;
  static constexpr unsigned parts_j = MarkerParts::origin;
  static constexpr const char* name = "spherical";
  template <class Scalar>
  using Params = NoParams<Scalar>;
  template <class Scalar, int NI, int NJ, class Sink>
  static void evaluate(const Params<Scalar>&, const MarkerEval<Scalar, NI>& i,
                       const MarkerEval<Scalar, NJ>& j, Scalar, Sink&& out) {
    for (int k = 0; k < 3; ++k) out(k, constraint::coincident(i, j, k));
  }
};

template <int I, int J>
struct Revolute {
  static constexpr int body_i = I, body_j = J, equations = 5;
  static constexpr unsigned parts_i = MarkerParts::origin | MarkerParts::z;
  static constexpr unsigned parts_j = MarkerParts::origin | MarkerParts::x | MarkerParts::y;
  static constexpr const char* name = "revolute";
  template <class Scalar>
  using Params = NoParams<Scalar>;
  template <class Scalar, int NI, int NJ, class Sink>
  static void evaluate(const Params<Scalar>&, const MarkerEval<Scalar, NI>& i,
                       const MarkerEval<Scalar, NJ>& j, Scalar, Sink&& out) {
    for (int k = 0; k < 3; ++k) out(k, constraint::coincident(i, j, k));
    out(3, constraint::perpendicular(i, 2, j, 0));
    out(4, constraint::perpendicular(i, 2, j, 1));
  }
};

template <int I, int J>
struct Universal {
  static constexpr int body_i = I, body_j = J, equations = 4;
  static constexpr unsigned parts_i = MarkerParts::origin | MarkerParts::z;
  static constexpr unsigned parts_j = MarkerParts::origin | MarkerParts::z;
  static constexpr const char* name = "universal";
  template <class Scalar>
  using Params = NoParams<Scalar>;
  template <class Scalar, int NI, int NJ, class Sink>
  static void evaluate(const Params<Scalar>&, const MarkerEval<Scalar, NI>& i,
                       const MarkerEval<Scalar, NJ>& j, Scalar, Sink&& out) {
    for (int k = 0; k < 3; ++k) out(k, constraint::coincident(i, j, k));
    out(3, constraint::perpendicular(i, 2, j, 2));
  }
};

template <int I, int J>
struct Cylindrical {
  static constexpr int body_i = I, body_j = J, equations = 4;
  static constexpr unsigned parts_i = MarkerParts::all;
  static constexpr unsigned parts_j = MarkerParts::origin | MarkerParts::x | MarkerParts::y;
  static constexpr const char* name = "cylindrical";
  template <class Scalar>
  using Params = NoParams<Scalar>;
  template <class Scalar, int NI, int NJ, class Sink>
  static void evaluate(const Params<Scalar>&, const MarkerEval<Scalar, NI>& i,
                       const MarkerEval<Scalar, NJ>& j, Scalar, Sink&& out) {
    out(0, constraint::in_plane(i, 0, j));
    out(1, constraint::in_plane(i, 1, j));
    out(2, constraint::perpendicular(i, 2, j, 0));
    out(3, constraint::perpendicular(i, 2, j, 1));
  }
};

template <int I, int J>
struct Prismatic {
  static constexpr int body_i = I, body_j = J, equations = 5;
  static constexpr unsigned parts_i = MarkerParts::all;
  static constexpr unsigned parts_j = MarkerParts::origin | MarkerParts::x | MarkerParts::y;
  static constexpr const char* name = "prismatic";
  template <class Scalar>
  using Params = NoParams<Scalar>;
  template <class Scalar, int NI, int NJ, class Sink>
  static void evaluate(const Params<Scalar>&, const MarkerEval<Scalar, NI>& i,
                       const MarkerEval<Scalar, NJ>& j, Scalar, Sink&& out) {
    out(0, constraint::in_plane(i, 0, j));
    out(1, constraint::in_plane(i, 1, j));
    out(2, constraint::perpendicular(i, 2, j, 0));
    out(3, constraint::perpendicular(i, 2, j, 1));
    out(4, constraint::perpendicular(i, 0, j, 1));
  }
};

template <int I, int J>
struct Fixed {
  static constexpr int body_i = I, body_j = J, equations = 6;
  static constexpr unsigned parts_i = MarkerParts::origin | MarkerParts::x | MarkerParts::z;
  static constexpr unsigned parts_j = MarkerParts::origin | MarkerParts::x | MarkerParts::y;
  static constexpr const char* name = "fixed";
  template <class Scalar>
  using Params = NoParams<Scalar>;
  template <class Scalar, int NI, int NJ, class Sink>
  static void evaluate(const Params<Scalar>&, const MarkerEval<Scalar, NI>& i,
                       const MarkerEval<Scalar, NJ>& j, Scalar, Sink&& out) {
    for (int k = 0; k < 3; ++k) out(k, constraint::coincident(i, j, k));
    out(3, constraint::perpendicular(i, 2, j, 0));
    out(4, constraint::perpendicular(i, 2, j, 1));
    out(5, constraint::perpendicular(i, 0, j, 1));
  }
};

template <int I, int J>
struct Distance {
  static constexpr int body_i = I, body_j = J, equations = 1;
  static constexpr unsigned parts_i = MarkerParts::origin;
  static constexpr unsigned parts_j = MarkerParts::origin;
  static constexpr const char* name = "distance";
  template <class Scalar>
  struct Params {
    Scalar length = Scalar(1);
  };
  template <class Scalar, int NI, int NJ, class Sink>
  static void evaluate(const Params<Scalar>& p, const MarkerEval<Scalar, NI>& i,
                       const MarkerEval<Scalar, NJ>& j, Scalar, Sink&& out) {
    out(0, constraint::distance(i, j, p.length));
  }
};

/// Prescribes the slide s(t) of marker j along z_i: (r_j - r_i) . z_i = s(t). Use with a
/// Prismatic or Cylindrical joint between the same markers (the cylinder stroke of a crane).
template <int I, int J, template <class> class Law>
struct PrismaticDriver {
  static constexpr int body_i = I, body_j = J, equations = 1;
  static constexpr unsigned parts_i = MarkerParts::origin | MarkerParts::z;
  static constexpr unsigned parts_j = MarkerParts::origin;
  static constexpr const char* name = "prismatic driver";
  template <class Scalar>
  struct Params {
    Law<Scalar> law{};
  };
  template <class Scalar, int NI, int NJ, class Sink>
  static void evaluate(const Params<Scalar>& p, const MarkerEval<Scalar, NI>& i,
                       const MarkerEval<Scalar, NJ>& j, Scalar t, Sink&& out) {
    auto r = constraint::in_plane(i, 2, j);
    const MotionValue<Scalar> s = p.law(t);
    r.phi -= s.value;
    r.phi_t = -s.rate;
    r.conv -= s.acceleration;
    out(0, r);
  }
};

/// Prescribes the rotation phi(t) of x_j from x_i about z_i (with a Revolute joint):
/// sin(phi) (x_i . x_j) - cos(phi) (y_i . x_j) = 0.
template <int I, int J, template <class> class Law>
struct RevoluteDriver {
  static constexpr int body_i = I, body_j = J, equations = 1;
  static constexpr unsigned parts_i = MarkerParts::x | MarkerParts::y;
  static constexpr unsigned parts_j = MarkerParts::x;
  static constexpr const char* name = "revolute driver";
  template <class Scalar>
  struct Params {
    Law<Scalar> law{};
  };
  template <class Scalar, int NI, int NJ, class Sink>
  static void evaluate(const Params<Scalar>& p, const MarkerEval<Scalar, NI>& i,
                       const MarkerEval<Scalar, NJ>& j, Scalar t, Sink&& out) {
    using std::cos;
    using std::sin;
    const MotionValue<Scalar> phi = p.law(t);
    const Scalar s = sin(phi.value), c = cos(phi.value);
    const Scalar sd = c * phi.rate, cd = -s * phi.rate;
    const Scalar sdd = -s * phi.rate * phi.rate + c * phi.acceleration;
    const Scalar cdd = -c * phi.rate * phi.rate - s * phi.acceleration;
    const auto a = constraint::perpendicular(i, 0, j, 0);  // x_i . x_j = cos(phi) when met
    const auto b = constraint::perpendicular(i, 1, j, 0);  // y_i . x_j = sin(phi)
    const Scalar a_dot = constraint::perpendicular_rate(i, 0, j, 0);
    const Scalar b_dot = constraint::perpendicular_rate(i, 1, j, 0);
    ConstraintRow<Scalar, 6 + NI, 6 + NJ> r;
    r.phi = s * a.phi - c * b.phi;
    r.bi = s * a.bi - c * b.bi;
    r.bj = s * a.bj - c * b.bj;
    r.phi_t = sd * a.phi - cd * b.phi;
    r.conv = sdd * a.phi + Scalar(2) * sd * a_dot + s * a.conv - cdd * b.phi -
             Scalar(2) * cd * b_dot - c * b.conv;
    out(0, r);
  }
};

}  // namespace flexstress
