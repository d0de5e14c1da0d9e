// Andrews' squeezing mechanism, built on the runtime model: a test case of the stress suite and of
// the pieces' Newton (tests/model/test_stress_suite.cpp, test_andrews_squeezer.cpp).
#pragma once

#include <cmath>
#include <utility>

#include <Eigen/Geometry>

#include <flexstress/model/all.hpp>

// Andrews' squeezing mechanism (Hairer & Wanner, Solving ODEs II, sec. VII.7; problem "andrews"
// of the IVP Test Set, F. Mazzia, C. Magherini, F. Iavernaro, andrews.f): seven rigid bodies in a
// plane (no gravity), three closed loops through the point E, a stiff spring (c0 = 4530 N/m)
// from the ground to body 3 and a constant torque of 0.033 N m on the crank; the crank spins up to
// 1140 rad/s in 0.03 s. The Test Set's parameters and start, with its coordinates: beta, the
// crank's angle; theta, the rod's from the crank; gamma, delta and epsilon, the angles of bodies
// 3, 5 and 7 about their ground pivots B and A; phi and Omega, those of bodies 4 and 6 from
// bodies 5 and 7. Each body's frame is at a pivot and turns by its absolute angle about z; the
// ten hinges are 3D revolutes about z (a planar model: redundant). A centre of mass off the line
// of a body pivoted on the ground enters the Test Set's equations only through its distance
// from the pivot, which is what is kept here. Out of the plane each body has the inertia it has
// about z (nothing moves it there).
namespace flexstress::testing::andrews {
constexpr double m1 = .04325, m2 = .00365, m3 = .02373, m4 = .00706, m5 = .07050, m6 = .00706,
                 m7 = .05498;
constexpr double i1 = 2.194e-6, i2 = 4.410e-7, i3 = 5.255e-6, i4 = 5.667e-7, i5 = 1.169e-5,
                 i6 = 5.667e-7, i7 = 1.912e-5;
constexpr double xa = -.06934, ya = -.00227, xb = -0.03635, yb = .03273, xc = .014, yc = .072;
constexpr double d = 28e-3, da = 115e-4, e = 2e-2, ea = 1421e-5, rr = 7e-3, ra = 92e-5;
constexpr double ss = 35e-3, sa = 1874e-5, sb = 1043e-5, sc = 18e-3, sd = 2e-2;
constexpr double ta = 2308e-5, tb = 916e-5, u = 4e-2, ua = 1228e-5, ub = 449e-5;
constexpr double zf = 2e-2, zt = 4e-2, fa = 1421e-5, mom = 33e-3, c0 = 4530, l0 = 7785e-5;
// The Test Set's consistent start (andrews.f, INITIAL), at rest.
constexpr double beta = -0.0617138900142764496358948458001, theta = 0,
                 gamma = 0.455279819163070380255912382449, phi = 0.222668390165885884674473185609,
                 delta = 0.487364979543842550225598953530,
                 omega = -0.222668390165885884674473185609,
                 epsilon = 1.23054744454982119249735015568;
// The Test Set's reference at t = 0.03 s (andrews.f, SOLN: PSIDE at tolerances 1e-14).
constexpr double beta_end = 0.1581077119629904e+2;

inline void torque(double /*t*/, const double* /*position*/, const double* /*velocity*/,
                   double* /*force*/, double* moment, void* /*user*/) {
  moment[2] = mom;
}

inline EulerParameters<double> turned(double angle) {
  return from_rotation_matrix<double>(Eigen::AngleAxisd(angle, Vector3d::UnitZ()).matrix());
}

struct Squeezer {
  Model<double> model;
  BodyId crank;
};

inline Result<Squeezer> make_squeezer() {
  ModelBuilder<double> b;
  const auto body = [&](const char* name, double mass, double inertia, Vector3d com, Vector3d at,
                        double angle) {
    const BodyId id =
        b.add_rigid_body(name, mass, com, Vector3d(inertia, inertia, inertia).asDiagonal());
    b.set_initial_pose(id, at, turned(angle));
    return id;
  };
  const Vector3d o(0, 0, 0), a(xa, ya, 0), bb(xb, yb, 0);
  const Vector3d f(rr * std::cos(beta), rr * std::sin(beta), 0);
  const Vector3d g = a + zt * Vector3d(std::cos(delta), std::sin(delta), 0);
  const Vector3d h = a + u * Vector3d(std::sin(epsilon), -std::cos(epsilon), 0);
  // Frames: 1 at O along OF; 2 at F (E at -d on its x); 3 at B (E at -ss on its y); 4 at G (E at
  // -e on its y); 5 at A (G at zt on its x); 6 at H (E at zf on its x); 7 at A (H at -u on y).
  Squeezer s;
  s.crank = body("1 crank", m1, i1, Vector3d(ra, 0, 0), o, beta);
  const BodyId rod = body("2 rod", m2, i2, Vector3d(-da, 0, 0), f, beta + theta);
  const BodyId b3 = body("3", m3, i3, Vector3d(sa, sb, 0), bb, gamma);
  const BodyId b4 = body("4", m4, i4, Vector3d(0, -(e - ea), 0), g, phi + delta);
  const BodyId b5 = body("5", m5, i5, Vector3d(ta, tb, 0), a, delta);
  const BodyId b6 = body("6", m6, i6, Vector3d(zf - fa, 0, 0), h, omega + epsilon);
  const BodyId b7 = body("7", m7, i7, Vector3d(ua, ub, 0), a, epsilon);
  const auto at = [&](BodyId on, double x, double y) {
    return b.add_marker("pin", on, -1, Vector3d(x, y, 0));
  };
  const auto ground = [&](const Vector3d& p) { return b.add_marker("pivot", b.ground(), -1, p); };
  const MarkerId crank_root = at(s.crank, 0, 0), rod_e = at(rod, -d, 0);
  b.add_joint("O", JointKind::revolute, ground(o), crank_root);
  b.add_joint("F", JointKind::revolute, at(s.crank, rr, 0), at(rod, 0, 0));
  b.add_joint("E 2-3", JointKind::revolute, rod_e, at(b3, 0, -ss));
  b.add_joint("E 2-4", JointKind::revolute, rod_e, at(b4, 0, -e));
  b.add_joint("E 2-6", JointKind::revolute, rod_e, at(b6, zf, 0));
  b.add_joint("B", JointKind::revolute, ground(bb), at(b3, 0, 0));
  b.add_joint("A 5", JointKind::revolute, ground(a), at(b5, 0, 0));
  b.add_joint("A 7", JointKind::revolute, ground(a), at(b7, 0, 0));
  b.add_joint("G", JointKind::revolute, at(b5, zt, 0), at(b4, 0, 0));
  b.add_joint("H", JointKind::revolute, at(b7, 0, -u), at(b6, 0, 0));
  SpringDamperParams<double> spring;
  spring.stiffness = c0;
  spring.rest_length = l0;
  b.add_spring_damper("spring", ground(Vector3d(xc, yc, 0)), at(b3, sd, -sc), spring);
  b.add_point_load("drive", crank_root, &torque);
  auto m = b.finalize();
  if (!m) return m.error();
  s.model = std::move(*m);
  return s;
}

/// Planar angle of a body's x axis.
inline double heading(const Model<double>& m, const Data<double>& data, BodyId body) {
  const Matrix3d r = rotation_matrix(body_orientation(m, data, body));
  return std::atan2(r(1, 0), r(0, 0));
}
}  // namespace flexstress::testing::andrews
