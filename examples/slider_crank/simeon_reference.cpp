// Independent reference for examples/slider_crank: Simeon's flexible slider crank exactly as
// the IVP Test Set defines it (crank.f, RESMBS: B. Simeon, "Modelling a flexible slider crank
// mechanism by a mixed system of DAEs and PDEs", Math. Modelling of Systems 2 (1996) 1-18;
// F. Mazzia, C. Magherini, F. Iavernaro, Test Set for IVP Solvers, release 2.3, 2006): the
// rod's lateral deflection is q1 sin(pi xi) + q2 sin(2 pi xi) in the frame through its two
// pins, its axial one quadratic (q3 mid node, q4 end node); linear stiffness, no damping, no
// gravity, the crank angle 150 t. q1 is the midpoint deflection relative to the pin line.
//
// Integrated here with coordinate partitioning: q and q_dot are the states, phi2, x3 and their
// rates follow from the closed loop, the accelerations and multipliers from the 10 x 10 KKT
// system of crank.f's mass matrix, forces and acceleration constraints; classical RK4 at a
// fixed step (1e-6 s; the highest frequency, an axial one, is about 2.7e4 rad/s).
//
//   simeon_reference [--ini 1|2] [--step H] [--duration S] [--every N]
// prints t,q1,q2,q3,q4 every N steps (CSV) and, on stderr, q at the end and max |q1|.
// --ini 1: the Test Set's smooth consistent start (its init1); --ini 2: the rod undeformed and
// its elastic velocities zero (the Test Set's second start).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <Eigen/Dense>

namespace {

constexpr double M1 = 0.36, M2 = 0.151104, M3 = 0.075552, L1 = 0.15, L2 = 0.30;
constexpr double J1 = 0.002727, J2 = 0.0045339259, PI = 3.1415927, EE = 0.20e12;
constexpr double BB = 0.0080, HH = 0.0080, RHO = 7870.0, GRAV = 0.0, OMEGA = 150.0;
constexpr int NQ = 4, NP = 7;

struct Fe {
  Eigen::Matrix4d MQ = Eigen::Matrix4d::Zero(), KQ = Eigen::Matrix4d::Zero(),
                  BQ = Eigen::Matrix4d::Zero();
  Eigen::Vector4d c1 = Eigen::Vector4d::Zero(), c2 = Eigen::Vector4d::Zero(),
                  c12 = Eigen::Vector4d::Zero(), c21 = Eigen::Vector4d::Zero();
  Fe() {
    const double FACM = RHO * BB * HH * L2, FACK = EE * BB * HH / L2, FACB = BB * HH * L2;
    MQ(0, 0) = FACM * .5;
    MQ(1, 1) = FACM * .5;
    MQ(2, 2) = FACM * 8.;
    MQ(2, 3) = MQ(3, 2) = FACM;
    MQ(3, 3) = FACM * 2.;
    KQ(0, 0) = FACK * std::pow(PI, 4) / 24. * std::pow(HH / L2, 2);
    KQ(1, 1) = FACK * std::pow(PI, 4) * 2. / 3. * std::pow(HH / L2, 2);
    KQ(2, 2) = FACK * 16. / 3.;
    KQ(2, 3) = KQ(3, 2) = -FACK * 8. / 3.;
    KQ(3, 3) = FACK * 7. / 3.;
    BQ(0, 2) = -FACB * 16. / std::pow(PI, 3);
    BQ(0, 3) = FACB * (8. / std::pow(PI, 3) - 1. / PI);
    BQ(1, 3) = FACB * .5 / PI;
    BQ(2, 0) = FACB * 16. / std::pow(PI, 3);
    BQ(3, 0) = -FACB * (8. / std::pow(PI, 3) - 1. / PI);
    BQ(3, 1) = -FACB * .5 / PI;
    c1(2) = FACB * 2. / 3.;
    c1(3) = FACB / 6.;
    c2(0) = FACB * 2. / PI;
    c12(2) = L2 * FACB / 3.;
    c12(3) = L2 * FACB / 6.;
    c21(0) = L2 * FACB / PI;
    c21(1) = -L2 * FACB * .5 / PI;
  }
};

struct Full {
  double p[3], v[3];  // phi1, phi2, x3 and rates
};

// The rigid coordinates and rates from the loop closure (KU = 4: the axial end node q4).
Full close_loop(double t, const Eigen::Vector4d& q, const Eigen::Vector4d& qd) {
  Full f;
  f.p[0] = OMEGA * t;
  f.v[0] = OMEGA;
  const double l = L2 + q(3);
  f.p[1] = std::asin(-L1 * std::sin(f.p[0]) / l);
  f.p[2] = L1 * std::cos(f.p[0]) + l * std::cos(f.p[1]);
  const double c1 = std::cos(f.p[0]), s1 = std::sin(f.p[0]), c2 = std::cos(f.p[1]),
               s2 = std::sin(f.p[1]);
  // VLC1: L1 c1 v1 + l c2 v2 + s2 qd4 = 0; VLC2: L1 s1 v1 + l s2 v2 + v3 - c2 qd4 = 0
  f.v[1] = -(L1 * c1 * OMEGA + s2 * qd(3)) / (l * c2);
  f.v[2] = -(L1 * s1 * OMEGA + l * s2 * f.v[1] - c2 * qd(3));
  return f;
}

// Modal accelerations from crank.f's equations (index-1 form).
Eigen::Vector4d accel(const Fe& fe, double t, const Eigen::Vector4d& q, const Eigen::Vector4d& qd,
                      Eigen::Matrix<double, 10, 1>* all = nullptr) {
  const Full f = close_loop(t, q, qd);
  const double cosp1 = std::cos(f.p[0]), sinp1 = std::sin(f.p[0]), cosp2 = std::cos(f.p[1]),
               sinp2 = std::sin(f.p[1]);
  const double cosp12 = std::cos(f.p[0] - f.p[1]), sinp12 = std::sin(f.p[0] - f.p[1]);
  const double V1 = f.v[0], V2 = f.v[1];
  const double c1TQ = fe.c1.dot(q), c1TQD = fe.c1.dot(qd), c2TQ = fe.c2.dot(q),
               c2TQD = fe.c2.dot(qd), c12TQ = fe.c12.dot(q), c12TQD = fe.c12.dot(qd);
  const Eigen::Vector4d MQQ = fe.MQ * q, KQQ = fe.KQ * q;
  const Eigen::Vector4d QTBQ = fe.BQ.transpose() * q;  // QTBQ(I) = q . BQ(:,I)
  const Eigen::Vector4d BQQD = fe.BQ * qd;             // BQQD(I) = BQ(I,:) . qd
  const double QTMQQ = q.dot(MQQ), QDTMQQ = qd.dot(MQQ), QDTBQQD = qd.dot(BQQD);
  Eigen::Matrix<double, 7, 7> AM = Eigen::Matrix<double, 7, 7>::Zero();
  AM(0, 0) = J1 + M2 * L1 * L1;
  AM(0, 1) = .5 * L1 * L2 * M2 * cosp12 + RHO * L1 * (sinp12 * c2TQ + cosp12 * c1TQ);
  AM(1, 1) = J2 + QTMQQ + 2.0 * RHO * c12TQ;
  AM(2, 2) = M3;
  for (int i = 0; i < NQ; ++i) {
    AM(0, 3 + i) = RHO * L1 * (-sinp12 * fe.c1(i) + cosp12 * fe.c2(i));
    AM(1, 3 + i) = RHO * fe.c21(i) + RHO * QTBQ(i);
  }
  AM.block<4, 4>(3, 3) = fe.MQ;
  for (int i = 0; i < NP; ++i)
    for (int j = i + 1; j < NP; ++j) AM(j, i) = AM(i, j);
  const double QKU = q(3), QDKU = qd(3);
  Eigen::Matrix<double, 3, 7> GP = Eigen::Matrix<double, 3, 7>::Zero();
  GP(0, 0) = L1 * cosp1;
  GP(0, 1) = L2 * cosp2 + QKU * cosp2;
  GP(1, 0) = L1 * sinp1;
  GP(1, 1) = L2 * sinp2 + QKU * sinp2;
  GP(1, 2) = 1.;
  GP(2, 0) = 1.;
  GP(0, 6) = sinp2;
  GP(1, 6) = -cosp2;
  Eigen::Matrix<double, 7, 1> F;
  F(0) = -.5 * L1 * GRAV * (M1 + 2.0 * M2) * cosp1 - .5 * L1 * L2 * M2 * V2 * V2 * sinp12;
  F(1) = -.5 * L2 * GRAV * M2 * cosp2 + .5 * L1 * L2 * M2 * V1 * V1 * sinp12;
  F(2) = 0.;
  F(0) += RHO * L1 * V2 * V2 * (-sinp12 * c1TQ + cosp12 * c2TQ) -
          2.0 * RHO * L1 * V2 * (cosp12 * c1TQD + sinp12 * c2TQD);
  F(1) += RHO * L1 * V1 * V1 * (sinp12 * c1TQ - cosp12 * c2TQ) - 2.0 * RHO * V2 * c12TQD -
          2.0 * V2 * QDTMQQ - RHO * QDTBQQD - RHO * GRAV * (cosp2 * c1TQ - sinp2 * c2TQ);
  for (int i = 0; i < NQ; ++i)
    F(3 + i) = V2 * V2 * MQQ(i) +
               RHO * (V2 * V2 * fe.c12(i) + L1 * V1 * V1 * (cosp12 * fe.c1(i) + sinp12 * fe.c2(i)) +
                      2.0 * V2 * BQQD(i)) -
               RHO * GRAV * (sinp2 * fe.c1(i) + cosp2 * fe.c2(i)) - KQQ(i);
  // ALC with w = 0 (the convective part gamma): G w + gamma = 0
  Eigen::Vector3d gamma;
  gamma(0) = -L1 * sinp1 * V1 * V1 - (L2 + QKU) * sinp2 * V2 * V2 + 2.0 * V2 * cosp2 * QDKU;
  gamma(1) = L1 * cosp1 * V1 * V1 + (L2 + QKU) * cosp2 * V2 * V2 + 2.0 * V2 * sinp2 * QDKU;
  gamma(2) = 0.;
  Eigen::Matrix<double, 10, 10> K = Eigen::Matrix<double, 10, 10>::Zero();
  K.topLeftCorner<7, 7>() = AM;
  K.topRightCorner<7, 3>() = GP.transpose();
  K.bottomLeftCorner<3, 7>() = GP;
  Eigen::Matrix<double, 10, 1> rhs;
  rhs << F, -gamma;
  const Eigen::Matrix<double, 10, 1> x = K.partialPivLu().solve(rhs);
  if (all) *all = x;
  return x.segment<4>(3);
}

}  // namespace

int main(int argc, char** argv) {
  int ini = 1, every = 100;
  double h = 1e-6, duration = 0.1;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--ini"))
      ini = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--step"))
      h = std::atof(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--duration"))
      duration = std::atof(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--every"))
      every = std::atoi(argv[i + 1]);
    else
      return std::fprintf(stderr, "unknown option %s\n", argv[i]), 2;
  }
  const Fe fe;
  Eigen::Vector4d q = Eigen::Vector4d::Zero(), qd = Eigen::Vector4d::Zero();
  if (ini == 1) {  // the Test Set's init1
    q << 0, 0, 0.103339863e-4, 0.169327969e-4;
    qd << 0.444896105, 0.463434311e-2, -0.178591076e-5, -0.268938672e-5;
  }
  const long steps = std::lround(duration / h);
  double t = 0, peak = 0, t_peak = 0;
  std::printf("t,q1,q2,q3,q4\n");
  std::printf("%.9g,%.10e,%.10e,%.10e,%.10e\n", t, q(0), q(1), q(2), q(3));
  for (long k = 0; k < steps; ++k) {
    const Eigen::Vector4d a1 = accel(fe, t, q, qd);
    const Eigen::Vector4d q2 = q + .5 * h * qd, v2 = qd + .5 * h * a1;
    const Eigen::Vector4d a2 = accel(fe, t + .5 * h, q2, v2);
    const Eigen::Vector4d q3 = q + .5 * h * v2, v3 = qd + .5 * h * a2;
    const Eigen::Vector4d a3 = accel(fe, t + .5 * h, q3, v3);
    const Eigen::Vector4d q4 = q + h * v3, v4 = qd + h * a3;
    const Eigen::Vector4d a4 = accel(fe, t + h, q4, v4);
    q += h / 6 * (qd + 2 * v2 + 2 * v3 + v4);
    qd += h / 6 * (a1 + 2 * a2 + 2 * a3 + a4);
    t = static_cast<double>(k + 1) * h;
    if (std::abs(q(0)) > peak) peak = std::abs(q(0)), t_peak = t;
    if ((k + 1) % every == 0)
      std::printf("%.9g,%.10e,%.10e,%.10e,%.10e\n", t, q(0), q(1), q(2), q(3));
  }
  Eigen::Matrix<double, 10, 1> all;
  accel(fe, t, q, qd, &all);
  const Full f = close_loop(t, q, qd);
  std::fprintf(stderr,
               "ini %d, h %g, t = %.6g: phi2 %.15g x3 %.15g q1 %.10e q2 %.10e q3 %.10e q4 %.10e\n"
               "  lambda %.10g %.10g %.10g; max |q1| %.6e at t = %.6g\n",
               ini, h, t, f.p[1], f.p[2], q(0), q(1), q(2), q(3), all(7), all(8), all(9), peak,
               t_peak);
  return 0;
}
