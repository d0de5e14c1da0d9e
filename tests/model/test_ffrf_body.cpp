// FFRF body: the mass matrix and the quadratic velocity vector built from inertia integrals
// must equal their definitions as sums over material points (FFRF reference sheet:
// M = sum m_i L_i^T L_i, Q_v = sum m_i L_i^T (dL_i/dt) v, with dL_i/dt by finite differences
// along the motion), for orthonormal modes and for a general mode set (not mass-orthogonal to
// rigid motion, not orthonormal), where no term vanishes (the body model alone). Then
// conservation laws, on the runtime model (one free body): a free spinning flexible body keeps
// its energy and angular momentum.
#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

#include <doctest/doctest.h>

#include <flexstress/dynamics/body_model.hpp>
#include <flexstress/fe/rigid_body_modes.hpp>
#include <flexstress/model/all.hpp>
#include <flexstress/reduction/component_modes.hpp>
#include <flexstress/reduction/inertia_integrals.hpp>
#include <flexstress/reduction/orthonormalize.hpp>

#include "support/beam_fixtures.hpp"

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

// finalize(), failing with its message.
Model<double> finalized(const ModelBuilder<double>& b) {
  auto m = b.finalize();
  if (!m.ok()) FAIL(m.error().what());
  return std::move(*m);
}

// A free flexible body (no gravity, no joints; the quadratic velocity terms are always on) with
// `modes` modes and integrator settings `set`.
struct FreeBody {
  Model<double> model;
  BodyId body;
};
FreeBody free_body(const reduction::ModalBodyData& data, int modes,
                   const ImplicitSettings<double>& set) {
  ModelBuilder<double> b;
  const BodyId body = b.add_flexible_body("body", data, modes);
  b.settings() = set;
  return {finalized(b), body};
}

// Sets a body's velocities [R_dot (global); w (body); p_dot] at rest shape (p = 0).
void set_velocities(const Model<double>& m, Data<double>& d, BodyId body, const VectorXd& v) {
  set_body_velocity(m, d, body, Vector3d(v.head<3>()), Vector3d(v.segment<3>(3)));
  const Index modes = v.size() - 6;
  REQUIRE(set_modal_state(m, d, body, VectorXd::Zero(modes), v.tail(modes)).ok());
}

// A thin steel strip (1 m, 20 x 5 mm) free in space: first bending mode about 27 Hz, so a spin
// of a few rad/s couples rigid rotation and deformation visibly.
struct SpinningStrip {
  const reduction::ModalBodyData& data;
  VectorXd initial_v;
  explicit SpinningStrip(const reduction::ModalBodyData& d) : data(d), initial_v(12) {
    initial_v << 0.1, -0.2, 0.05, 2.0, 6.0, 1.0, 0.3, -0.2, 0.1, 0.05, 0.0, 0.02;
  }
  struct Drift {
    double energy = 0, momentum = 0;
  };
  Drift run(double h, int steps, double rho = 1.0) const {
    ImplicitSettings<double> set;
    set.step = h;
    set.spectral_radius = rho;
    const FreeBody f = free_body(data, 6, set);
    const Model<double>& m = f.model;
    Data<double> d(m);
    set_velocities(m, d, f.body, initial_v);
    REQUIRE(initialize(m, d).ok());
    const double e0 = energy(m, d).total();
    const Vector3d h0 = momentum(m, d, f.body).angular;
    Drift dr;
    for (int i = 0; i < steps; ++i) {
      REQUIRE(step(m, d) == StepStatus::ok);
      dr.energy = std::max(dr.energy, std::abs(energy(m, d).total() - e0) / e0);
      dr.momentum = std::max(dr.momentum, (momentum(m, d, f.body).angular - h0).norm() / h0.norm());
    }
    // The Euler parameters stay unit length.
    CHECK(std::abs(body_orientation(m, d, f.body).norm() - 1.0) < 1e-12);
    return dr;
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
  ImplicitSettings<double> set;
  set.step = 2e-5;
  set.spectral_radius = 1.0;
  const FreeBody f = free_body(bar.general, kModes, set);
  const Model<double>& m = f.model;
  Data<double> d(m);
  VectorXd v(6 + kModes);
  v << 0.2, 0.1, -0.3, 3.0, -1.0, 8.0, 0.01, -0.02, 0.015, 0.01;
  set_velocities(m, d, f.body, v);
  REQUIRE(initialize(m, d).ok());
  const double e0 = energy(m, d).total();
  const Vector3d h0 = momentum(m, d, f.body).angular;
  double de = 0, dh = 0;
  for (int i = 0; i < 20000; ++i) {
    REQUIRE(step(m, d) == StepStatus::ok);
    de = std::max(de, std::abs(energy(m, d).total() - e0) / e0);
    dh = std::max(dh, (momentum(m, d, f.body).angular - h0).norm() / h0.norm());
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
  auto unit = Body::from_modal_data(bar.unit_modes);
  auto tenfold = Body::from_modal_data(bar.tenfold_modes);
  REQUIRE(unit.ok());
  REQUIRE(tenfold.ok());
  CHECK(tenfold->modal_displacement_scale().isApprox(10.0 * unit->modal_displacement_scale()));
  ImplicitSettings<double> set;
  set.acceleration_tolerance = 1e-7;  // several iterations per step
  set.relative_acceleration_tolerance = 0;
  const FreeBody a = free_body(bar.unit_modes, kModes, set);
  const FreeBody b = free_body(bar.tenfold_modes, kModes, set);
  Data<double> da(a.model), db(b.model);
  VectorXd va(6 + kModes);
  va << 0, 0, 0, 0.5, -0.2, 1.0, 2.0, -3.0, 2.5, 1.5;
  VectorXd vb = va;
  vb.tail<kModes>() /= 10.0;
  set_velocities(a.model, da, a.body, va);
  set_velocities(b.model, db, b.body, vb);
  REQUIRE(initialize(a.model, da).ok());
  REQUIRE(initialize(b.model, db).ok());
  double dp = 0, dr = 0, p_range = 0;
  for (int i = 0; i < 2000; ++i) {
    REQUIRE(step(a.model, da) == StepStatus::ok);
    REQUIRE(step(b.model, db) == StepStatus::ok);
    const VectorXd pa = modal_coordinates(a.model, da, a.body);
    const VectorXd pb = modal_coordinates(b.model, db, b.body);
    dp = std::max(dp, (pa - 10.0 * pb).cwiseAbs().maxCoeff());
    dr = std::max(dr, (body_position(a.model, da, a.body) - body_position(b.model, db, b.body))
                          .cwiseAbs()
                          .maxCoeff());
    p_range = std::max(p_range, pa.cwiseAbs().maxCoeff());
  }
  const long ita = da.statistics.iterations, itb = db.statistics.iterations;
  MESSAGE("iterations " << ita << " and " << itb << " in 2000 steps; largest differences: " << dr
                        << " m (frame), " << dp << " of " << p_range << " (modes)");
  CHECK(std::abs(ita - itb) <= ita / 100);
  CHECK(dr < 1e-9);
  CHECK(dp < 1e-6 * p_range);
}

}  // namespace test_ffrf_body
