// Sub-models tied to a host by rigid webs (Rantalainen et al. 2013). References: Euler-Bernoulli
// beam theory (far-field stress M c / I and N / A with the section force from the strain energy,
// exact Hermite interpolation of a beam loaded at its nodes), rigid-body kinematics (no strain
// from rigid boundary motion), and the full sub-model re-solve that the influence matrix and the
// fused modal rows replace.
#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include <doctest/doctest.h>

#include <flexstress/fe/beam_line.hpp>
#include <flexstress/fe/rhs_attachment_mesh.hpp>
#include <flexstress/fe/static_solver.hpp>
#include <flexstress/stress/fused_stress.hpp>
#include <flexstress/stress/host_point.hpp>
#include <flexstress/stress/section_force_modes.hpp>
#include <flexstress/stress/stress_outputs.hpp>
#include <flexstress/stress/sub_model.hpp>
#include <flexstress/stress/weld_toe_hot_spot.hpp>

#include "support/beam_fixtures.hpp"

namespace test_sub_model {

using namespace flexstress;
using namespace flexstress::stress;

namespace {

fe::RhsAttachmentMesh rhs(double density, double x0 = 0.5, double x1 = 0.8) {
  fe::RhsAttachmentSpec spec;
  spec.density = density;
  spec.x0 = x0;
  spec.x1 = x1;
  auto r = fe::make_rhs_attachment_mesh(spec);
  REQUIRE_MESSAGE(r.ok(), r.error().what());
  return std::move(r).value();
}

// The RHS segment at density 0.6 with bricks at most 20 mm long along x (long enough to carry a
// moment gradient) and sections at `stations`.
fe::RhsAttachmentMesh capped_rhs(double x0, double x1, std::vector<double> stations = {}) {
  fe::RhsAttachmentSpec spec;
  spec.density = 0.6;
  spec.x0 = x0;
  spec.x1 = x1;
  spec.max_element_length = 0.02;
  spec.extra_x_stations = std::move(stations);
  auto r = fe::make_rhs_attachment_mesh(spec);
  REQUIRE_MESSAGE(r.ok(), r.error().what());
  return std::move(r).value();
}

SubModel tie(const fe::RhsAttachmentMesh& r) {
  std::vector<SubModelAttachment> att = {{Vector3d(r.spec.x0, 0, 0), r.end_section_x0},
                                         {Vector3d(r.spec.x1, 0, 0), r.end_section_x1}};
  auto s = SubModel::build(r.mesh, att);
  REQUIRE_MESSAGE(s.ok(), s.error().what());
  return std::move(s).value();
}

// u_b of a rigid motion (translation a, small rotation b about the origin) of all masters.
VectorXd rigid_boundary(const SubModel& s, const Vector3d& a, const Vector3d& b) {
  VectorXd u(s.num_boundary_dofs());
  for (Index k = 0; k < s.num_attachments(); ++k) {
    u.segment<3>(6 * k) = a + b.cross(s.mesh().node(s.master_node(k)));
    u.segment<3>(6 * k + 3) = b;
  }
  return u;
}

}  // namespace

TEST_CASE("sub-model: rigid boundary motion gives no stress, unit translation moves every node") {
  const auto r = rhs(0.6);
  const SubModel s = tie(r);
  CHECK(s.num_boundary_dofs() == 12);
  const std::vector<Vector3d> pts = {
      {r.weld_toe_x + 0.0016, 0.075, 0.0}, {0.56, -0.075, 0.02}, {0.7, 0.05, 0.05}};
  auto h = s.stress_influence(pts);
  REQUIRE(h.ok());
  // Scale: the stress of a unit relative rotation, |H| over the rotation columns.
  const double scale = h->cwiseAbs().maxCoeff();
  const Vector3d axes[6] = {Vector3d::UnitX(), Vector3d::UnitY(), Vector3d::UnitZ(),
                            Vector3d::UnitX(), Vector3d::UnitY(), Vector3d::UnitZ()};
  for (int k = 0; k < 6; ++k) {
    CAPTURE(k);
    const VectorXd ub = k < 3 ? rigid_boundary(s, axes[k], Vector3d::Zero())
                              : rigid_boundary(s, Vector3d::Zero(), axes[k]);
    CHECK((*h * ub).cwiseAbs().maxCoeff() < 1e-10 * scale);
  }
  // A unit x translation of both masters moves every node by exactly (1, 0, 0).
  const VectorXd u = s.solve(rigid_boundary(s, Vector3d::UnitX(), Vector3d::Zero()));
  const auto& dofs = s.model().dofs;
  double worst = 0;
  for (Index n = 0; n < s.mesh().num_nodes(); ++n)
    worst = std::max(worst, std::abs(u(dofs.dof(n, 0)) - 1.0) + std::abs(u(dofs.dof(n, 1))));
  CHECK(worst < 1e-9);
}

TEST_CASE("sub-model: far from the detail, bending and axial stress match beam theory") {
  // A longer segment (0.2 to 1.1 m) so that the read-out is a section height from the rib and
  // from the rigid end sections (St.-Venant). The section force comes from the strain energy:
  // u^T K u = M theta (pure bending by a relative end rotation theta) or N delta.
  const auto r = rhs(0.6, 0.2, 1.1);
  const SubModel s = tie(r);
  const fe::BeamSection sec = fe::rectangular_hollow_section(0.150, 0.100, 0.004);
  const double c = 0.075;
  for (int load = 0; load < 2; ++load) {
    CAPTURE(load);
    // Pure bending: end rotations -theta/2 and +theta/2 about z with the ends held, which bends
    // a prismatic beam into a circular arc (uniform curvature theta / L, no shear). Axial:
    // the far end pulled by delta.
    VectorXd ub = VectorXd::Zero(12);
    const double amount = 1e-3;
    if (load == 0) {
      ub(5) = -amount / 2;
      ub(11) = amount / 2;
    } else {
      ub(6) = amount;
    }
    const VectorXd u = s.solve(ub);
    const double work = u.dot(s.model().stiffness_all * u);  // = M theta or N delta
    const double force = work / amount;
    for (double x : {0.35, 0.95})
      for (const Vector3d& p : {Vector3d(x, c, 0), Vector3d(x, -c, 0), Vector3d(x, 0.05, 0.05),
                                Vector3d(x, -c, 0.03)}) {
        CAPTURE(p.transpose());
        auto sigma = s.stresses_by_resolve({p}, ub);
        REQUIRE(sigma.ok());
        const double beam = load == 0 ? -force * p.y() / sec.iz : force / sec.area;
        CHECK((*sigma)(0) == doctest::Approx(beam).epsilon(0.02));
      }
  }
}

TEST_CASE("a whole boom of bricks clamped at one end: tip load gives beam theory's bending") {
  // A 1.2 m cantilever of the RHS (the detail at 0.65 m included) clamped through a rigid web at
  // x = 0, a 1 kN load hung below a section at x = 1.0 through another (SubModel::load_response
  // with the clamp as the only attachment). Euler-Bernoulli: M(x) = P (1.0 - x) about z (the
  // hook's offset below the axis adds no moment to a vertical load), sigma_xx = -M y / I on the
  // flanges, read at least a section height from the clamp, the rib and the hook.
  const auto r = capped_rhs(0.0, 1.2, {1.0});
  fe::Mesh mesh = r.mesh;
  const Index hook = mesh.add_node(Vector3d(1.0, -0.125, 0.0));
  mesh.add_rigid_link(hook, r.section_nodes(1.0));
  auto s = SubModel::build(std::move(mesh), {{Vector3d::Zero(), r.end_section_x0}});
  REQUIRE_MESSAGE(s.ok(), s.error().what());
  const auto& dofs = s->model().dofs;
  const double p = -1000.0;
  VectorXd load = VectorXd::Zero(dofs.size());
  load(dofs.dof(hook, 1)) = p;
  const VectorXd u = s->load_response(load);
  const fe::BeamSection sec = fe::rectangular_hollow_section(0.150, 0.100, 0.004);
  const double c = 0.075;
  for (double x : {0.2, 0.4, 0.85})
    for (double y : {c, -c}) {
      const Vector3d point(x, y, 0.0);
      CAPTURE(point.transpose());
      auto h = s->stress_influence({point}, u);
      REQUIRE(h.ok());
      const double moment = p * (1.0 - x);  // about z, from the load to the left of it
      CHECK((*h)(0, 0) == doctest::Approx(-moment * y / sec.iz).epsilon(0.02));
    }
}

TEST_CASE("influence, fused modal rows and the full re-solve agree") {
  // Host: a 1.2 m RHS beam reduced by Craig-Bampton (interfaces at both ends), with nodes at
  // the sub-model's ends 0.5 and 0.8 m. The sub-model reads a tensor, a hot spot and a gauge.
  constexpr int N = 8;
  const fe::BeamSection sec = fe::rectangular_hollow_section(0.150, 0.100, 0.004);
  auto host = testing::make_beam_body(1.2, sec, 12, {0.0, 1.2}, N);
  const auto r = rhs(0.6);
  const SubModel s = tie(r);
  const std::vector<HostPoint> hosts = {HostPoint::at_node(host.line.node_at(0.5)),
                                        HostPoint::at_node(host.line.node_at(0.8))};
  auto phi_b = boundary_modes(host.data, hosts);
  REQUIRE(phi_b.ok());
  StressOutputs out;
  const Vector3d toe(r.weld_toe_x, 0.075, 0.0);
  const Index tensor = out.add_tensor(toe + Vector3d(0.002, 0, 0), "near toe");
  HotSpotLocation hs;
  hs.toe = toe;
  hs.away = Vector3d::UnitX();
  hs.thickness = 0.004;
  auto hot = out.add_hot_spot(hs, "hot spot a");
  REQUIRE(hot.ok());
  auto gauge = out.add_strain_gauge(Vector3d(0.56, 0.075, 0.0), Vector3d::UnitX(), 0.006, "SG1");
  REQUIRE(gauge.ok());
  auto rows = out.rows(s);
  REQUIRE(rows.ok());
  auto fused = FusedStress<N>::build(*rows, *phi_b);
  REQUIRE(fused.ok());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uni(-1e-3, 1e-3);
  for (int trial = 0; trial < 3; ++trial) {
    Eigen::Matrix<double, N, 1> p;
    for (int k = 0; k < N; ++k) p(k) = uni(rng);
    VectorXd y_fused(out.num_outputs()), y_influence(out.num_outputs());
    fused->evaluate(p, y_fused);
    fused->evaluate_by_influence(p, y_influence);
    // Re-solve with u_b = Phi_b p, then recover the same outputs by hand.
    const VectorXd ub = phi_b->leftCols(N) * p;  // the host has 14 modes; the scene keeps 8
    auto ref = s.stresses_by_resolve(out.stress_points(), ub);
    REQUIRE(ref.ok());
    const double scale = y_fused.cwiseAbs().maxCoeff();
    REQUIRE(scale > 0);
    for (int c = 0; c < 6; ++c) CHECK(std::abs(y_fused(tensor + c) - (*ref)(c)) < 1e-9 * scale);
    auto rule = hot_spot_rule(hs.rule, hs.thickness);
    double hot_ref = 0;
    for (std::size_t i = 0; i < rule->weights.size(); ++i)
      hot_ref += rule->weights[i] * (*ref)(6 * static_cast<Index>(i + 1));  // sigma_xx
    CHECK(std::abs(y_fused(*hot) - hot_ref) < 1e-9 * scale);
    CHECK((y_fused - y_influence).cwiseAbs().maxCoeff() < 1e-9 * scale);
    CHECK(fused->evaluate(*hot, p) == doctest::Approx(y_fused(*hot)).epsilon(1e-12));
    // The gauge against the strain at its centre: uniform along x there, so the average equals
    // the point strain eps_xx = (sigma_xx - nu (sigma_yy + sigma_zz)) / E on the surface.
    auto centre = s.stresses_by_resolve({Vector3d(0.56, 0.075, 0.0)}, ub);
    REQUIRE(centre.ok());
    const double eps = ((*centre)(0) - 0.3 * ((*centre)(1) + (*centre)(2))) / 210e9;
    CHECK(y_fused(*gauge) == doctest::Approx(eps).epsilon(0.02));
  }
}

TEST_CASE("Hermite boundary interpolation is exact for a beam loaded at its nodes; linear is not") {
  // A cantilever (Euler-Bernoulli: no shear areas) of 4 elements under a tip force P:
  // v(x) = P x^2 (3 L - x) / (6 E I), theta_z = P x (2 L - x) / (2 E I) (any mechanics text).
  fe::BeamSection sec = fe::rectangular_hollow_section(0.150, 0.100, 0.004);
  sec.shear_area_y = sec.shear_area_z = 0.0;
  fe::Mesh mesh;
  fe::BeamLineSpec spec;
  const double len = 2.0, force = 1e3, ei = 210e9 * sec.iz;
  spec.end = Vector3d(len, 0, 0);
  spec.num_elements = 4;
  spec.material = mesh.add_material(fe::steel());
  spec.section = mesh.add_section(sec);
  const auto line = fe::add_beam_line(mesh, spec);
  fe::BoundaryConditions bc;
  bc.clamp(line.nodes.front());
  auto model = fe::assemble(mesh, bc);
  REQUIRE(model.ok());
  auto solver = fe::StaticSolver::factorize(mesh, *model);
  REQUIRE(solver.ok());
  auto f = fe::load_vector(model->dofs, {{line.nodes.back(), 1, force}});
  REQUIRE(f.ok());
  const VectorXd u = solver->solve(*f);
  auto nodal = [&](Index n) {
    Eigen::Matrix<double, 6, 1> d;
    for (int c = 0; c < 6; ++c) d(c) = u(model->dofs.dof(n, c));
    return d;
  };
  double err_linear = 0, err_hermite = 0, err_hermite_rot = 0;
  const double v_tip = force * len * len * len / (3 * ei);
  for (int e = 0; e < 4; ++e)
    for (double xi : {0.25, 0.5, 0.8}) {
      const Index a = line.nodes[static_cast<std::size_t>(e)],
                  b = line.nodes[static_cast<std::size_t>(e + 1)];
      Eigen::Matrix<double, 12, 1> ab;
      ab << nodal(a), nodal(b);
      const double x = (e + xi) * len / 4;
      const double v = force * x * x * (3 * len - x) / (6 * ei);
      const double th = force * x * (2 * len - x) / (2 * ei);
      const Eigen::Matrix<double, 6, 1> lin =
          beam_point_interpolation(mesh.node(a), mesh.node(b), xi, BoundaryInterpolation::linear) *
          ab;
      const Eigen::Matrix<double, 6, 1> her =
          beam_point_interpolation(mesh.node(a), mesh.node(b), xi, BoundaryInterpolation::hermite) *
          ab;
      err_linear = std::max(err_linear, std::abs(lin(1) - v));
      err_hermite = std::max(err_hermite, std::abs(her(1) - v));
      err_hermite_rot = std::max(err_hermite_rot, std::abs(her(5) - th));
    }
  MESSAGE("tip load: max deflection error linear " << err_linear / v_tip << ", Hermite "
                                                   << err_hermite / v_tip << " of the tip value");
  CHECK(err_hermite < 1e-10 * v_tip);
  CHECK(err_hermite_rot < 1e-10 * force * len * len / (2 * ei));
  CHECK(err_linear > 1e-3 * v_tip);
  // Under a distributed load q the FE nodal values are still exact (consistent loads), but the
  // deflection between nodes is a quartic: both interpolations approximate it.
  // v(x) = q x^2 (6 L^2 - 4 L x + x^2) / (24 E I).
  {
    const double q = 500.0;
    std::vector<fe::NodalLoad> loads;
    const double h = len / 4;
    for (std::size_t k = 0; k < line.nodes.size(); ++k) {
      const bool end = k == 0 || k + 1 == line.nodes.size();
      loads.push_back({line.nodes[k], 1, q * h * (end ? 0.5 : 1.0)});
      const double m = q * h * h / 12;  // consistent end moments of each element
      if (k == 0) loads.push_back({line.nodes[k], 5, m});
      if (k + 1 == line.nodes.size()) loads.push_back({line.nodes[k], 5, -m});
    }
    auto fq = fe::load_vector(model->dofs, loads);
    REQUIRE(fq.ok());
    const VectorXd uq = solver->solve(*fq);
    double lin_err = 0, her_err = 0;
    const double v_end = q * std::pow(len, 4) / (8 * ei);
    for (int e = 0; e < 4; ++e) {
      Eigen::Matrix<double, 12, 1> ab;
      for (int c = 0; c < 6; ++c) {
        ab(c) = uq(model->dofs.dof(line.nodes[static_cast<std::size_t>(e)], c));
        ab(6 + c) = uq(model->dofs.dof(line.nodes[static_cast<std::size_t>(e + 1)], c));
      }
      const Vector3d xa = mesh.node(line.nodes[static_cast<std::size_t>(e)]),
                     xb = mesh.node(line.nodes[static_cast<std::size_t>(e + 1)]);
      const double x = (e + 0.5) * h;
      const double v = q * x * x * (6 * len * len - 4 * len * x + x * x) / (24 * ei);
      const Eigen::Matrix<double, 6, 1> l =
          beam_point_interpolation(xa, xb, 0.5, BoundaryInterpolation::linear) * ab;
      const Eigen::Matrix<double, 6, 1> hm =
          beam_point_interpolation(xa, xb, 0.5, BoundaryInterpolation::hermite) * ab;
      lin_err = std::max(lin_err, std::abs(l(1) - v));
      her_err = std::max(her_err, std::abs(hm(1) - v));
    }
    MESSAGE("distributed load, mid-element deflection error: linear "
            << lin_err / v_end << ", Hermite " << her_err / v_end << " of the tip value");
    CHECK(her_err < 0.1 * lin_err);
    CHECK(her_err > 0.0);
    CHECK(her_err < 1e-3 * v_end);
  }
  // Out of plane (x-z) the same with theta_y = -dw/dx.
  auto fz = fe::load_vector(model->dofs, {{line.nodes.back(), 2, force}});
  REQUIRE(fz.ok());
  const VectorXd uz = solver->solve(*fz);
  Eigen::Matrix<double, 12, 1> ab;
  for (int c = 0; c < 6; ++c) {
    ab(c) = uz(model->dofs.dof(line.nodes[1], c));
    ab(6 + c) = uz(model->dofs.dof(line.nodes[2], c));
  }
  const double eiy = 210e9 * sec.iy, x = 0.75;
  const Eigen::Matrix<double, 6, 1> her =
      beam_point_interpolation(mesh.node(line.nodes[1]), mesh.node(line.nodes[2]), 0.5,
                               BoundaryInterpolation::hermite) *
      ab;
  CHECK(her(2) == doctest::Approx(force * x * x * (3 * len - x) / (6 * eiy)).epsilon(1e-9));
  CHECK(her(4) == doctest::Approx(-force * x * (2 * len - x) / (2 * eiy)).epsilon(1e-9));
}

TEST_CASE("sub-model bad input names the attachment, node or point") {
  const auto r = rhs(0.6);
  auto empty = SubModel::build(r.mesh, {{Vector3d(0.5, 0, 0), {}}});
  REQUIRE_FALSE(empty.ok());
  CHECK(empty.error().message.find("attachment 0") != std::string::npos);
  auto overlap = SubModel::build(
      r.mesh, {{Vector3d(0.5, 0, 0), r.end_section_x0}, {Vector3d(0.8, 0, 0), r.end_section_x0}});
  REQUIRE_FALSE(overlap.ok());
  CHECK(overlap.error().message.find("also belongs to attachment 0") != std::string::npos);
  auto missing = SubModel::build(r.mesh, {{Vector3d(0.5, 0, 0), {Index(1) << 40}}});
  REQUIRE_FALSE(missing.ok());
  CHECK(missing.error().message.find("does not exist") != std::string::npos);
  // A brick connected to nothing the attachments hold: the solver explains the free motion.
  fe::Mesh loose = r.mesh;
  std::array<Index, 8> ids{};
  const Vector3d corner(2.0, 0, 0);
  for (int k = 0; k < 8; ++k)
    ids[static_cast<std::size_t>(k)] =
        loose.add_node(corner + Vector3d((k == 1 || k == 2 || k == 5 || k == 6) ? 0.01 : 0.0,
                                         (k == 2 || k == 3 || k == 6 || k == 7) ? 0.01 : 0.0,
                                         k >= 4 ? 0.01 : 0.0));
  loose.add_hex8(ids, 0);
  auto free_brick = SubModel::build(
      loose, {{Vector3d(0.5, 0, 0), r.end_section_x0}, {Vector3d(0.8, 0, 0), r.end_section_x1}});
  REQUIRE_FALSE(free_brick.ok());
  CHECK(free_brick.error().code == ErrorCode::singular_matrix);
  MESSAGE(free_brick.error().what());
  // Read-out points off the mesh (a weld-toe line that leaves the surface) are named.
  const SubModel s = tie(r);
  StressOutputs out;
  out.add_normal_stress(Vector3d(0.65, 0.2, 0.0), Vector3d::UnitX(), "off the surface");
  auto rows = out.rows(s);
  REQUIRE_FALSE(rows.ok());
  CHECK(rows.error().message.find("stress read-out") != std::string::npos);
  MESSAGE(rows.error().what());
  // A host node without rotations cannot carry an attachment; a host node that does not exist.
  const fe::BeamSection sec = fe::rectangular_hollow_section(0.150, 0.100, 0.004);
  auto host = testing::make_beam_body(1.2, sec, 6, {0.0}, 4);
  auto bad = boundary_modes(host.data, {HostPoint::at_node(999)});
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error().message.find("host node 999") != std::string::npos);
  auto bad_xi = boundary_modes(host.data, {HostPoint::between(0, 1, 1.5)});
  CHECK_FALSE(bad_xi.ok());
}

TEST_CASE("a force-driven end: the segment's stress follows statics, not its stiffness") {
  // The segment 0.2 to 1.1 m held at x0 and loaded at the x1 master by a moment M_z, then by a
  // force F_y. Statics: M_z(x) = M, then F_y (x1 - x) (the load's moment about the section at
  // x); Euler-Bernoulli sigma_xx = -M_z y / I, read a section height from the ends and the rib.
  // Bricks at most 20 mm long: the generator's graded zones alone put a single 0.25 m brick
  // between the end and the rib, which cannot carry a moment gradient (it reads 9 % low at
  // 0.3 m and 12 % high at 0.45 m).
  const auto r = capped_rhs(0.2, 1.1);
  auto s =
      SubModel::build(r.mesh, {{Vector3d(0.2, 0, 0), r.end_section_x0},
                               {Vector3d(1.1, 0, 0), r.end_section_x1, AttachmentDrive::force}});
  REQUIRE_MESSAGE(s.ok(), s.error().what());
  CHECK(s->drive(0) == AttachmentDrive::displacement);
  CHECK(s->drive(1) == AttachmentDrive::force);
  const fe::BeamSection sec = fe::rectangular_hollow_section(0.150, 0.100, 0.004);
  const double c = 0.075;
  std::vector<Vector3d> points;
  for (double x : {0.35, 0.85})
    for (double y : {c, -c}) points.emplace_back(x, y, 0.0);
  auto h = s->stress_influence(points);
  REQUIRE(h.ok());
  for (int load = 0; load < 2; ++load) {
    VectorXd b = VectorXd::Zero(12);
    b(load == 0 ? 11 : 7) = load == 0 ? 2000.0 : 5000.0;  // N m about z, or N along y
    const VectorXd sigma = *h * b;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Vector3d& p = points[i];
      CAPTURE(load);
      CAPTURE(p.transpose());
      const double moment = load == 0 ? 2000.0 : 5000.0 * (1.1 - p.x());
      CHECK(sigma(6 * static_cast<Index>(i)) ==
            doctest::Approx(-moment * p.y() / sec.iz).epsilon(0.02));
    }
  }
  // The held end's rigid motion still gives no stress; the fused form equals the re-solve.
  VectorXd b = rigid_boundary(*s, Vector3d(1, 2, 3), Vector3d(0.1, 0.2, 0.3));
  b.tail<6>().setZero();                                  // no load at the force-driven end
  CHECK((*h * b).cwiseAbs().maxCoeff() < 1e-10 * 210e9);  // strain at round-off level
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  for (Index k = 0; k < 12; ++k) b(k) = uni(rng) * (k < 6 ? 1e-3 : 1e3);
  auto ref = s->stresses_by_resolve(points, b);
  REQUIRE(ref.ok());
  const VectorXd y = *h * b;
  CHECK((y - *ref).cwiseAbs().maxCoeff() < 1e-9 * y.cwiseAbs().maxCoeff());
  // Every end force-driven: nothing holds it.
  auto loose =
      SubModel::build(r.mesh, {{Vector3d(0.2, 0, 0), r.end_section_x0, AttachmentDrive::force},
                               {Vector3d(1.1, 0, 0), r.end_section_x1, AttachmentDrive::force}});
  REQUIRE_FALSE(loose.ok());
  CHECK(loose.error().message.find("all 2 attachments are force-driven") != std::string::npos);
}

TEST_CASE("section-force modes of a reduced cantilever give the section's shear and moment") {
  // A 2 m RHS cantilever in 20 beam elements, reduced (Craig-Bampton, interfaces at the root and
  // the tip, so its static modes span the tip-load solution exactly). The full model's static
  // deflection under a tip force P_y, written in the body's modes (plus its rigid motions, which
  // carry no force), gives section forces K_e Phi_e p that statics knows: at the node x the
  // element on its root side receives from the tip side F_y = P and M_z = P (L - x).
  const double length = 2.0, load = 3000.0;
  const fe::BeamSection sec = fe::rectangular_hollow_section(0.150, 0.100, 0.004);
  auto beam = testing::make_beam_body(length, sec, 20, {0.0, length}, 4);
  const Index root = beam.interface_nodes[0], tip = beam.interface_nodes[1];
  fe::BoundaryConditions bc;
  bc.clamp(root);
  auto model = fe::assemble(beam.mesh, bc);
  REQUIRE(model.ok());
  auto solver = fe::StaticSolver::factorize(beam.mesh, *model);
  REQUIRE(solver.ok());
  VectorXd f = VectorXd::Zero(model->dofs.size());
  f(model->dofs.dof(tip, 1)) = load;
  const VectorXd u = solver->solve(f);
  // u in the modes and the six rigid motions of the body frame, by least squares over all nodes.
  const Index nn = beam.mesh.num_nodes(), n = beam.data.num_modes;
  std::vector<HostPoint> all;
  for (Index k = 0; k < nn; ++k) all.push_back(HostPoint::at_node(k));
  auto phi = boundary_modes(beam.data, all);
  REQUIRE(phi.ok());
  MatrixXd basis = MatrixXd::Zero(6 * nn, n + 6);
  basis.leftCols(n) = *phi;
  VectorXd target(6 * nn);
  for (Index k = 0; k < nn; ++k) {
    for (int c = 0; c < 6; ++c) target(6 * k + c) = u(model->dofs.dof(k, c));
    for (int c = 0; c < 3; ++c) {
      basis(6 * k + c, n + c) = 1.0;
      const Vector3d rot = Vector3d::Unit(c).cross(beam.mesh.node(k));
      basis.block<3, 1>(6 * k, n + 3 + c) = rot;
      basis(6 * k + 3 + c, n + 3 + c) = 1.0;
    }
  }
  const VectorXd coeffs = basis.colPivHouseholderQr().solve(target);
  REQUIRE((basis * coeffs - target).norm() < 1e-9 * target.norm());
  const VectorXd p = coeffs.head(n);
  for (std::size_t e = 0; e < beam.mesh.beams().size(); e += 6) {
    const auto& el = beam.mesh.beams()[e];
    const Index outer = beam.mesh.node(el.nodes[1]).x() > beam.mesh.node(el.nodes[0]).x()
                            ? el.nodes[1]
                            : el.nodes[0];
    auto modes = section_force_modes(beam.mesh, beam.data, static_cast<Index>(e), outer);
    REQUIRE(modes.ok());
    const VectorXd section = *modes * p;
    const double x = beam.mesh.node(outer).x();
    CAPTURE(x);
    CHECK(section(1) == doctest::Approx(load).epsilon(1e-6));
    CHECK(section(5) == doctest::Approx(load * (length - x)).epsilon(1e-6));
    CHECK(std::abs(section(0)) + std::abs(section(2)) + std::abs(section(3)) +
              std::abs(section(4)) <
          1e-6 * load);
  }
  // Bad input names what is wrong.
  auto no_element = section_force_modes(beam.mesh, beam.data, 99, tip);
  REQUIRE_FALSE(no_element.ok());
  CHECK(no_element.error().message.find("beam element 99 does not exist") != std::string::npos);
  auto not_its_node = section_force_modes(beam.mesh, beam.data, 0, tip);
  REQUIRE_FALSE(not_its_node.ok());
  CHECK(not_its_node.error().message.find("is not a node of beam element 0") != std::string::npos);
}

TEST_CASE("under a uniform moment the rib's two toes read one hot spot, each away from its weld") {
  // The rib and its welds are symmetric about the rib's mid-plane (x = 0.65, halfway between the
  // segment's ends), and pure bending by opposite end rotations makes the moment uniform: the
  // two toes see the same stress field mirrored, and the generator mirrors its mesh too.
  // Read towards the weld, the -x toe's points fall under the weld's foot (measured: 0.53 of
  // the toe's hot spot).
  const auto r = rhs(0.6);
  const SubModel s = tie(r);
  StressOutputs out;
  const auto plus = out.add_hot_spot(weld_toe_hot_spot(r, WeldToe::plus_x));
  const auto minus = out.add_hot_spot(weld_toe_hot_spot(r, WeldToe::minus_x));
  HotSpotLocation into_weld = weld_toe_hot_spot(r, WeldToe::minus_x);
  into_weld.away = Vector3d::UnitX();
  const auto wrong = out.add_hot_spot(into_weld);
  REQUIRE((plus.ok() && minus.ok() && wrong.ok()));
  auto rows = out.rows(s);
  REQUIRE(rows.ok());
  VectorXd ub = VectorXd::Zero(12);  // the top flange, where the rib is, in tension
  ub(5) = 5e-4;
  ub(11) = -5e-4;
  const VectorXd y = *rows * ub;
  MESSAGE("hot spots: +x toe " << y(*plus) << " Pa, -x toe " << y(*minus)
                               << " Pa, -x toe read into the weld " << y(*wrong) << " Pa");
  CHECK(y(*plus) > 0);
  CHECK(y(*minus) == doctest::Approx(y(*plus)).epsilon(1e-4));  // the generator's mesh is mirrored
  CHECK(y(*wrong) < 0.9 * y(*minus));
}

TEST_CASE("the hot-spot stress is insensitive to the sub-model mesh (three densities)" *
          doctest::test_suite("long")) {
  // The structural hot-spot method is built to be mesh-insensitive for meshes within its rules
  // (IIW type a: elements <= 0.4 t at the toe; Niemi, Fricke & Maddox, designer's guide), unlike
  // the notch stress at the toe itself, which grows without bound as the mesh is refined. The
  // RHS + rib under pure bending at densities 0.6, 1.0 and 1.6 (toe elements 0.4 t and finer):
  // the hot-spot / nominal ratio agrees within 3 %, and exceeds 1 (the rib concentrates stress).
  // Measured: 1.354, 1.359, 1.377 - it drifts up as the read-out points' elements shrink.
  std::vector<double> values;
  for (double density : {0.6, 1.0, 1.6}) {
    const auto r = rhs(density);
    const SubModel s = tie(r);
    StressOutputs out;
    HotSpotLocation hs;
    hs.toe = Vector3d(r.weld_toe_x, 0.075, 0);
    hs.thickness = 0.004;
    auto hot = out.add_hot_spot(hs);
    REQUIRE(hot.ok());
    const Index nominal = out.add_normal_stress(Vector3d(0.65, -0.075, 0), Vector3d::UnitX());
    auto rows = out.rows(s);
    REQUIRE(rows.ok());
    VectorXd ub = VectorXd::Zero(12);
    ub(5) = -5e-4;
    ub(11) = 5e-4;
    const VectorXd y = *rows * ub;
    const double ratio = y(*hot) / -y(nominal);
    MESSAGE("density " << density << " (" << r.mesh.hexes().size()
                       << " bricks): hot spot / nominal = " << ratio);
    CHECK(ratio > 1.1);
    values.push_back(ratio);
  }
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  CHECK(*hi - *lo < 0.03 * *lo);
}

}  // namespace test_sub_model
