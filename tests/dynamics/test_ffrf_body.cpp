// FFRF body: the mass matrix and the quadratic velocity vector built from inertia integrals
// must equal their definitions as sums over material points (FFRF reference sheet:
// M = sum m_i L_i^T L_i, Q_v = sum m_i L_i^T (dL_i/dt) v, with dL_i/dt by finite differences
// along the motion), for orthonormal modes and for a general mode set (not mass-orthogonal to
// rigid motion, not orthonormal), where no term vanishes. Then conservation laws: a free
// spinning flexible body keeps its energy and angular momentum.
#include <cmath>
#include <random>

#include <doctest/doctest.h>

#include <flexstress/dynamics/implicit_integrator.hpp>
#include <flexstress/fe/rigid_body_modes.hpp>

#include "fixtures.hpp"

namespace test_ffrf_body {

using namespace flexstress;

namespace {

constexpr int kModes = 4;
using Body = FFRFBody<kModes>;

// A lumped-mass brick bar (1.0 x 0.1 x 0.08 m, 6 x 2 x 2 bricks): its inertia integrals are sums
// over nodes, so the definitions can be evaluated directly.
struct LumpedBar {
  fe::Mesh mesh;
  fe::MassOptions mass;
  reduction::ModalBodyData orthonormal, general;
  // The orthonormal modes as they are and multiplied by 10 (built the same way, so that they
  // differ only in normalization): the same body, its modal coordinates 10 times smaller.
  reduction::ModalBodyData unit_modes, tenfold_modes;
  VectorXd nodal_mass;
  LumpedBar() {
    const Index mat = mesh.add_material(fe::steel());
    const int nx = 6, ny = 2, nz = 2;
    auto id = [&](int i, int j, int k) {
      return static_cast<Index>((i * (ny + 1) + j) * (nz + 1) + k);
    };
    for (int i = 0; i <= nx; ++i)
      for (int j = 0; j <= ny; ++j)
        for (int k = 0; k <= nz; ++k)
          mesh.add_node(Vector3d(1.0 * i / nx, 0.1 * j / ny - 0.03, 0.08 * k / nz + 0.01));
    for (int i = 0; i < nx; ++i)
      for (int j = 0; j < ny; ++j)
        for (int k = 0; k < nz; ++k)
          mesh.add_hex8(
              {id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k), id(i, j, k + 1),
               id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)},
              mat);
    mass.lumping = fe::MassLumping::lumped;
    auto cm = reduction::craig_chang(mesh, {}, reduction::ModeSelection{kModes, -1, 0}, mass);
    REQUIRE(cm.ok());
    reduction::ReductionSpec spec;
    spec.mass = mass;
    auto d = reduction::make_modal_body(mesh, *cm, spec);
    REQUIRE(d.ok());
    orthonormal = *d;
    auto def = reduction::orthonormalize(mesh, *cm);
    REQUIRE(def.ok());
    const auto& dofs = cm->model.dofs;
    nodal_mass = VectorXd(cm->model.mass_all.diagonal());
    // General modes: mixed (T) and polluted with rigid motion (C) -- S_Phi, the antisymmetric
    // part of Lambda_0k and the off-diagonal M_ff and K entries no longer vanish.
    std::mt19937 rng(9);
    std::normal_distribution<double> n;
    MatrixXd t(kModes, kModes), c(6, kModes);
    for (Index i = 0; i < t.size(); ++i) t.data()[i] = n(rng) * 0.4;
    t += MatrixXd::Identity(kModes, kModes);
    for (Index i = 0; i < c.size(); ++i) c.data()[i] = n(rng) * 0.05;
    const MatrixXd rigid = fe::rigid_body_modes(mesh, dofs, Vector3d(0.3, 0.1, -0.2));
    const MatrixXd modes = def->modes.leftCols(kModes) * t + rigid * c;
    general = orthonormal;
    auto in = reduction::inertia_integrals(mesh, dofs, modes, mass);
    REQUIRE(in.ok());
    general.inertia = *in;
    const MatrixXd k = def->eigenvalues.head(kModes).asDiagonal();
    general.modal_stiffness = t.transpose() * k * t;
    for (Index nd = 0; nd < mesh.num_nodes(); ++nd)
      for (int cc = 0; cc < 3; ++cc)
        general.phi_translation.row(3 * nd + cc) = modes.row(dofs.dof(nd, cc));
    const auto scaled = [&](double factor) {
      reduction::ModalBodyData d = orthonormal;
      const MatrixXd phi = factor * def->modes.leftCols(kModes);
      auto integrals = reduction::inertia_integrals(mesh, dofs, phi, mass);
      REQUIRE(integrals.ok());
      d.inertia = *integrals;
      d.modal_stiffness = factor * factor * k;
      for (Index nd = 0; nd < mesh.num_nodes(); ++nd)
        for (int cc = 0; cc < 3; ++cc)
          d.phi_translation.row(3 * nd + cc) = phi.row(dofs.dof(nd, cc));
      return d;
    };
    unit_modes = scaled(1.0);
    tenfold_modes = scaled(10.0);
  }
};

// L_i = [I, -A skew(u_i), A Phi_i] of node i.
Eigen::Matrix<double, 3, 6 + kModes> l_matrix(const reduction::ModalBodyData& d, Index node,
                                              const Matrix3d& a, const Vec<double, kModes>& p) {
  const Mat<double, 3, kModes> phi = d.phi_r(node).leftCols(kModes);
  const Vector3d u = d.node_positions[static_cast<std::size_t>(node)] + phi * p;
  Eigen::Matrix<double, 3, 6 + kModes> l;
  l << Matrix3d::Identity(), -a * skew(u), a * phi;
  return l;
}

void check_against_point_sums(const LumpedBar& bar, const reduction::ModalBodyData& data) {
  auto body = Body::from_modal_data(data);
  REQUIRE(body.ok());
  std::mt19937 rng(3);
  std::normal_distribution<double> n;
  for (int trial = 0; trial < 3; ++trial) {
    const EulerParameters<double> theta =
        normalized<double>(Vec4<double>(n(rng), n(rng), n(rng), n(rng)));
    Body::Kinematics k;
    k.rotation = rotation_matrix(theta);
    for (int i = 0; i < kModes; ++i) {
      k.p(i) = 0.02 * n(rng);
      k.p_dot(i) = 0.5 * n(rng);
    }
    k.velocity = Vector3d(n(rng), n(rng), n(rng));
    k.omega = Vector3d(n(rng), n(rng), n(rng)) * 3.0;
    Body::Terms terms;
    body->compute_terms(k, terms);
    Body::MatV m;
    body->mass_matrix(k, terms, m);
    Body::VecV qv;
    body->quadratic_velocity(k, terms, qv);
    Body::VecV v;
    v << k.velocity, k.omega, k.p_dot;
    // Point sums; dL/dt along theta(t) = theta o exp(t w), p(t) = p + t p_dot.
    Body::MatV m_sum = Body::MatV::Zero();
    Body::VecV q_sum = Body::VecV::Zero();
    const double eps = 1e-6;
    const Matrix3d ap = rotation_matrix<double>(
        compose<double>(theta, exp_rotation<double>(Vector3d(eps * k.omega))));
    const Matrix3d am = rotation_matrix<double>(
        compose<double>(theta, exp_rotation<double>(Vector3d(-eps * k.omega))));
    for (Index node = 0; node < bar.mesh.num_nodes(); ++node) {
      const double mi = bar.nodal_mass(3 * node);
      const Eigen::Matrix<double, 3, 6 + kModes> l = l_matrix(data, node, k.rotation, k.p);
      const Eigen::Matrix<double, 3, 6 + kModes> ldot =
          (l_matrix(data, node, ap, k.p + eps * k.p_dot) -
           l_matrix(data, node, am, k.p - eps * k.p_dot)) /
          (2 * eps);
      m_sum.noalias() += mi * l.transpose() * l;
      q_sum.noalias() += mi * l.transpose() * (ldot * v);
    }
    CHECK((m - m_sum).norm() <= 1e-12 * m_sum.norm());
    CHECK((qv - q_sum).norm() <= 1e-6 * q_sum.norm());
  }
}

}  // namespace

TEST_CASE("mass matrix and quadratic velocity vector equal their point-sum definitions") {
  const LumpedBar bar;
  SUBCASE("orthonormal modes") {
    check_against_point_sums(bar, bar.orthonormal);
  }
  SUBCASE("general modes (nothing vanishes)") {
    // The general set really exercises the coupling terms.
    CHECK(bar.general.inertia.first[1].norm() > 1e-3);
    check_against_point_sums(bar, bar.general);
  }
}

namespace {

using FreeBody = Scene<double, Bodies<FFRFBody<6>>, Joints<>, Effects<QuadraticVelocity>>;

// A thin steel strip (1 m, 20 x 5 mm) free in space: first bending mode about 27 Hz, so a spin
// of a few rad/s couples rigid rotation and deformation visibly.
struct SpinningStrip {
  FreeBody scene;
  FreeBody::State initial;
  explicit SpinningStrip(const reduction::ModalBodyData& data) {
    auto body = FFRFBody<6>::from_modal_data(data);
    REQUIRE(body.ok());
    scene.body<0>() = *body;
    initial.v << 0.1, -0.2, 0.05, 2.0, 6.0, 1.0, 0.3, -0.2, 0.1, 0.05, 0.0, 0.02;
  }
  struct Drift {
    double energy = 0, momentum = 0;
  };
  Drift run(double h, int steps, double rho = 1.0) const {
    ImplicitIntegrator<FreeBody>::Settings set;
    set.step = h;
    set.spectral_radius = rho;
    ImplicitIntegrator<FreeBody> integ(scene, set);
    FreeBody::State s = initial;
    REQUIRE(integ.initialize(s).ok());
    auto& w = integ.workspace();
    scene.update_kinematics(s, w);
    const double e0 = scene.energy(w).total();
    const Vector3d h0 = scene.body<0>().angular_momentum(std::get<0>(w.kin));
    Drift d;
    for (int i = 0; i < steps; ++i) {
      REQUIRE(integ.step(s) == StepStatus::ok);
      scene.update_kinematics(s, w);
      d.energy = std::max(d.energy, std::abs(scene.energy(w).total() - e0) / e0);
      d.momentum =
          std::max(d.momentum,
                   (scene.body<0>().angular_momentum(std::get<0>(w.kin)) - h0).norm() / h0.norm());
    }
    // The Euler parameters stay unit length.
    CHECK(std::abs(s.coordinates<0>().theta.norm() - 1.0) < 1e-12);
    return d;
  }
};

}  // namespace

TEST_CASE("free spinning flexible body conserves energy and angular momentum") {
  auto strip =
      testing::make_beam_body(1.0, fe::rectangular_section(0.005, 0.02), 16, {0.0, 1.0}, 2);
  const SpinningStrip sim(strip.data);
  // 1e5 steps without numerical dissipation (rho = 1).
  const auto long_run = sim.run(5e-5, 100000);
  MESSAGE("1e5 steps at h = 5e-5: energy drift " << long_run.energy << ", momentum drift "
                                                 << long_run.momentum);
  CHECK(long_run.energy < 1e-6);
  CHECK(long_run.momentum < 1e-6);
  // The drift falls with h at second order: halving h divides it by about four.
  const auto coarse = sim.run(4e-4, 2500);
  const auto fine = sim.run(2e-4, 5000);
  MESSAGE("over 1 s: energy drift " << coarse.energy << " (h = 4e-4) -> " << fine.energy
                                    << " (h = 2e-4)");
  CHECK(coarse.energy / fine.energy > 3.0);
  CHECK(coarse.energy / fine.energy < 5.5);
}

TEST_CASE("a general (non-orthonormal) mode set conserves too") {
  const LumpedBar bar;
  using GeneralScene =
      Scene<double, Bodies<FFRFBody<kModes>>, Joints<>, Effects<QuadraticVelocity>>;
  GeneralScene scene;
  auto body = FFRFBody<kModes>::from_modal_data(bar.general);
  REQUIRE(body.ok());
  scene.body<0>() = *body;
  ImplicitIntegrator<GeneralScene>::Settings set;
  set.step = 2e-5;
  set.spectral_radius = 1.0;
  ImplicitIntegrator<GeneralScene> integ(scene, set);
  GeneralScene::State s;
  s.v << 0.2, 0.1, -0.3, 3.0, -1.0, 8.0, 0.01, -0.02, 0.015, 0.01;
  REQUIRE(integ.initialize(s).ok());
  auto& w = integ.workspace();
  scene.update_kinematics(s, w);
  const double e0 = scene.energy(w).total();
  const Vector3d h0 = scene.body<0>().angular_momentum(std::get<0>(w.kin));
  double de = 0, dh = 0;
  for (int i = 0; i < 20000; ++i) {
    REQUIRE(integ.step(s) == StepStatus::ok);
    scene.update_kinematics(s, w);
    de = std::max(de, std::abs(scene.energy(w).total() - e0) / e0);
    dh = std::max(dh,
                  (scene.body<0>().angular_momentum(std::get<0>(w.kin)) - h0).norm() / h0.norm());
  }
  MESSAGE("general modes, 2e4 steps: energy drift " << de << ", momentum drift " << dh);
  CHECK(de < 1e-6);
  CHECK(dh < 1e-6);
}

TEST_CASE("the Newton tolerance does not depend on how the modes are normalized") {
  // Modes 10 times larger make the same body with modal coordinates 10 times smaller. The
  // tolerance counts a modal correction with its mode's largest nodal translation
  // (BodyModel::modal_displacement_scale), so both bodies converge at the same iterations and
  // move the same to the solver's tolerance. The bar vibrates more than it turns, so that the
  // modal corrections decide when Newton stops. (In modal units the tenfold body's corrections
  // look 10 times smaller and it stops earlier: 8813 against 9721 iterations, measured.)
  const LumpedBar bar;
  using FreeScene = Scene<double, Bodies<Body>, Joints<>, Effects<QuadraticVelocity>>;
  auto unit = Body::from_modal_data(bar.unit_modes);
  auto tenfold = Body::from_modal_data(bar.tenfold_modes);
  REQUIRE(unit.ok());
  REQUIRE(tenfold.ok());
  CHECK(tenfold->modal_displacement_scale().isApprox(10.0 * unit->modal_displacement_scale()));
  FreeScene a, b;
  a.body<0>() = *unit;
  b.body<0>() = *tenfold;
  ImplicitIntegrator<FreeScene>::Settings set;
  set.acceleration_tolerance = 1e-7;  // several iterations per step
  ImplicitIntegrator<FreeScene> ia(a, set), ib(b, set);
  FreeScene::State sa, sb;
  sa.v << 0, 0, 0, 0.5, -0.2, 1.0, 2.0, -3.0, 2.5, 1.5;
  sb.v = sa.v;
  sb.v.tail<kModes>() /= 10.0;
  REQUIRE(ia.initialize(sa).ok());
  REQUIRE(ib.initialize(sb).ok());
  double dp = 0, dr = 0, p_range = 0;
  for (int i = 0; i < 2000; ++i) {
    REQUIRE(ia.step(sa) == StepStatus::ok);
    REQUIRE(ib.step(sb) == StepStatus::ok);
    const auto& ca = sa.coordinates<0>();
    const auto& cb = sb.coordinates<0>();
    dp = std::max(dp, (ca.p - 10.0 * cb.p).cwiseAbs().maxCoeff());
    dr = std::max(dr, (ca.position - cb.position).cwiseAbs().maxCoeff());
    p_range = std::max(p_range, ca.p.cwiseAbs().maxCoeff());
  }
  const long ita = ia.statistics().iterations, itb = ib.statistics().iterations;
  MESSAGE("iterations " << ita << " and " << itb << " in 2000 steps; largest differences: " << dr
                        << " m (frame), " << dp << " of " << p_range << " (modes)");
  CHECK(std::abs(ita - itb) <= ita / 100);
  CHECK(dr < 1e-9);
  CHECK(dp < 1e-6 * p_range);
}

}  // namespace test_ffrf_body
