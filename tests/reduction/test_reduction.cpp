// Craig-Bampton and Craig-Chang reduction with orthonormalized modes. References: the Rayleigh-
// Ritz property of Craig-Bampton (Craig & Bampton, AIAA J. 6 (1968)); static exactness of the
// full CB basis for interface loads (ibid.); Euler-Bernoulli free-free frequencies (validation
// sheet); inertia of a uniform beam and of a cuboid from geometry.
#include <cmath>

#include <doctest/doctest.h>

#include <flexstress/fe/beam_line.hpp>
#include <flexstress/fe/static_solver.hpp>
#include <flexstress/reduction/body_stress_modes.hpp>
#include <flexstress/reduction/modal_body_data.hpp>

namespace test_reduction {

using namespace flexstress;
using namespace flexstress::fe;
using namespace flexstress::reduction;

namespace {

constexpr double kPi = 3.14159265358979323846;

// The paper's boom: RHS 150x100x4, L = 4.5 m, 20 elements, nodes at A (x = 0) and B (x = 0.32).
struct Boom {
  Mesh mesh;
  BeamLine line;
  BeamSection section = rectangular_hollow_section(0.15, 0.10, 0.004);
  Index node_a = 0, node_b = 0;
  explicit Boom(int elements = 19) {
    BeamLineSpec spec;
    spec.end = Vector3d(4.5, 0, 0);
    spec.num_elements = elements;
    spec.extra_positions = {0.32};
    spec.material = mesh.add_material(steel());
    spec.section = mesh.add_section(section);
    line = add_beam_line(mesh, spec);
    node_a = line.node_at(0.0);
    node_b = line.node_at(0.32);
  }
  std::vector<InterfaceNode> interface() const { return {{node_a}, {node_b}}; }
};

enum class Spiders { rigid, averaging, none };

// A brick bar 1.0 x 0.1 x 0.1 (nx x 2 x 2 bricks) with spiders on both end faces (rigid by
// default).
struct BrickBar {
  Mesh mesh;
  Index spider0 = 0, spider1 = 0;
  explicit BrickBar(int nx = 12, Spiders spiders = Spiders::rigid) {
    const Index mat = mesh.add_material(steel());
    const int ny = 2, nz = 2;
    const double lx = 1.0, ly = 0.1, lz = 0.1;
    auto id = [&](int i, int j, int k) {
      return static_cast<Index>((i * (ny + 1) + j) * (nz + 1) + k);
    };
    for (int i = 0; i <= nx; ++i)
      for (int j = 0; j <= ny; ++j)
        for (int k = 0; k <= nz; ++k)
          mesh.add_node(Vector3d(lx * i / nx, ly * j / ny - ly / 2, lz * k / nz - lz / 2));
    for (int i = 0; i < nx; ++i)
      for (int j = 0; j < ny; ++j)
        for (int k = 0; k < nz; ++k)
          mesh.add_hex8(
              {id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k), id(i, j, k + 1),
               id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)},
              mat);
    std::vector<Index> f0, f1;
    for (int j = 0; j <= ny; ++j)
      for (int k = 0; k <= nz; ++k) {
        f0.push_back(id(0, j, k));
        f1.push_back(id(nx, j, k));
      }
    if (spiders == Spiders::rigid) {
      spider0 = add_rigid_spider(mesh, f0);
      spider1 = add_rigid_spider(mesh, f1);
    } else if (spiders == Spiders::averaging) {
      spider0 = add_averaging_spider(mesh, f0);
      spider1 = add_averaging_spider(mesh, f1);
    }
  }
};

VectorXd full_free_free_eigenvalues(const Mesh& mesh, int n) {
  auto model = assemble(mesh);
  REQUIRE(model.ok());
  EigenOptions eo;
  eo.num_modes = 6 + n;
  eo.method = EigenMethod::dense;
  auto s = solve_eigen(model->stiffness, model->mass, eo);
  REQUIRE(s.ok());
  return s->eigenvalues.tail(n);
}

ReductionSpec cb_spec(std::vector<InterfaceNode> interface, int fixed_modes) {
  ReductionSpec spec;
  spec.interface = std::move(interface);
  spec.dynamic_modes.count = fixed_modes;
  return spec;
}

}  // namespace

TEST_CASE("orthonormalized modes: Phi^T M Phi = I and Phi^T K Phi = diag to round-off") {
  Boom boom;
  auto body = reduce(boom.mesh, cb_spec(boom.interface(), 4));
  REQUIRE(body.ok());
  // The paper's "10 modes": 6 static (2 interface nodes: 12 - 6) + 4 fixed-interface.
  CHECK(body->num_modes == 10);
  CHECK(body->mass_residual < 1e-12);
  CHECK(body->stiffness_residual < 1e-12);
  BrickBar bar;
  auto brick_body = reduce(bar.mesh, cb_spec({{bar.spider0}, {bar.spider1}}, 5));
  REQUIRE(brick_body.ok());
  CHECK(brick_body->num_modes == 11);
  CHECK(brick_body->mass_residual < 1e-12);
  CHECK(brick_body->stiffness_residual < 1e-12);
}

TEST_CASE(
    "Craig-Bampton is Rayleigh-Ritz: frequencies at or above the full model's, errors "
    "non-increasing as fixed-interface modes are added (beam and bricks; n = 0 is Guyan)") {
  auto check_model = [](const Mesh& mesh, std::vector<InterfaceNode> interface, int compare) {
    const VectorXd exact = full_free_free_eigenvalues(mesh, compare);
    VectorXd previous_error = VectorXd::Constant(compare, 1e300);
    for (int n : {0, 2, 4, 8, 16}) {
      auto body = reduce(mesh, cb_spec(interface, n));
      REQUIRE(body.ok());
      const Index m = std::min<Index>(compare, body->num_modes);
      for (Index i = 0; i < m; ++i) {
        CAPTURE(n);
        CAPTURE(i);
        CHECK(body->eigenvalues(i) >= exact(i) * (1 - 1e-10));
        const double error = body->eigenvalues(i) / exact(i) - 1;
        CHECK(error <= previous_error(i) * (1 + 1e-9) + 1e-13);
        previous_error(i) = error;
      }
    }
    return previous_error;
  };
  Boom boom;
  const VectorXd beam_err = check_model(boom.mesh, boom.interface(), 6);
  MESSAGE("beam: largest relative eigenvalue error of the lowest six with 16 modes: "
          << beam_err.maxCoeff());
  CHECK(beam_err.maxCoeff() < 1e-3);
  BrickBar bar(8);
  check_model(bar.mesh, {{bar.spider0}, {bar.spider1}}, 6);
  BrickBar averaged(8, Spiders::averaging);
  check_model(averaged.mesh, {{averaged.spider0}, {averaged.spider1}}, 6);
}

TEST_CASE("averaging (RBE3) spiders: interfaces on bricks that add no stiffness") {
  // The full free-free model: averaging spiders (massless, no stiffness of their own) leave the
  // bar's frequencies as they are; rigid spiders stiffen its end faces.
  const VectorXd bare = full_free_free_eigenvalues(BrickBar(8, Spiders::none).mesh, 6);
  const VectorXd averaged = full_free_free_eigenvalues(BrickBar(8, Spiders::averaging).mesh, 6);
  const VectorXd rigid = full_free_free_eigenvalues(BrickBar(8, Spiders::rigid).mesh, 6);
  const double averaged_change = (averaged.array() / bare.array() - 1).abs().maxCoeff();
  const double rigid_change = (rigid.array() / bare.array() - 1).abs().maxCoeff();
  MESSAGE("lowest six elastic eigenvalues against the bare bar: averaging spiders "
          << averaged_change << ", rigid spiders " << rigid_change);
  CHECK(averaged_change < 1e-9);
  CHECK(rigid_change > 1e-4);  // 7e-4: far above the averaging spiders' round-off

  // Reduced over averaging spiders: orthonormal modes, rotational mode shapes at the spiders.
  BrickBar bar(12, Spiders::averaging);
  auto body = reduce(bar.mesh, cb_spec({{bar.spider0}, {bar.spider1}}, 5));
  REQUIRE(body.ok());
  CHECK(body->num_modes == 11);
  CHECK(body->mass_residual < 1e-12);
  CHECK(body->stiffness_residual < 1e-12);
  CHECK(body->node_has_rotation[static_cast<std::size_t>(bar.spider1)] == 1);
  CHECK(body->phi_theta(bar.spider1).norm() > 0.0);
}

TEST_CASE(
    "static exactness: the full CB basis reproduces interface-load statics exactly; "
    "truncation changes it by a measured amount") {
  Boom boom;
  // Full model: clamp A, tip-like load at the interface node B (force and moment).
  BoundaryConditions bc;
  bc.clamp(boom.node_a);
  auto full = assemble(boom.mesh, bc);
  REQUIRE(full.ok());
  auto solver = StaticSolver::factorize(boom.mesh, *full);
  REQUIRE(solver.ok());
  auto f = load_vector(full->dofs, {{boom.node_b, 1, -1000.0},
                                    {boom.node_b, 2, 300.0},
                                    {boom.node_b, 5, 250.0},
                                    {boom.node_b, 0, 50.0}});
  REQUIRE(f.ok());
  const VectorXd u_full = solver->solve(*f);
  // Reduced: span of rigid motions and the kept deformation modes, clamped at A.
  auto reduced_solution = [&](Index keep) {
    ReductionSpec spec = cb_spec(boom.interface(), 4);
    spec.keep_modes = keep;
    auto body = reduce(boom.mesh, spec);
    REQUIRE(body.ok());
    auto cm = craig_bampton(boom.mesh, boom.interface(), spec.dynamic_modes);
    REQUIRE(cm.ok());
    auto def = orthonormalize(boom.mesh, *cm);
    REQUIRE(def.ok());
    const MatrixXd rigid = rigid_body_modes(boom.mesh, full->dofs, Vector3d::Zero());
    MatrixXd v(full->dofs.size(), 6 + keep);
    v << rigid, def->modes.leftCols(keep);
    MatrixXd va(6, v.cols());
    for (int c = 0; c < 6; ++c) va.row(c) = v.row(full->dofs.dof(boom.node_a, c));
    Eigen::FullPivLU<MatrixXd> lu(va);
    const MatrixXd n = lu.kernel();
    const MatrixXd vn = v * n;
    const MatrixXd kr = vn.transpose() * (full->stiffness_all * vn);
    const VectorXd y = kr.ldlt().solve(vn.transpose() * *f);
    return VectorXd(vn * y);
  };
  const VectorXd u10 = reduced_solution(10);
  CHECK((u10 - u_full).norm() < 1e-10 * u_full.norm());
  // Truncating to the lowest 4 deformation modes loses static exactness.
  const VectorXd u4 = reduced_solution(4);
  const double err4 = (u4 - u_full).norm() / u_full.norm();
  MESSAGE("static error with 4 of 10 modes: " << err4);
  CHECK(err4 > 1e-6);
}

TEST_CASE(
    "free-free beam: Craig-Chang frequencies match the analytic values; Craig-Bampton and "
    "Craig-Chang span the same low-frequency space") {
  Boom boom(40);
  ReductionSpec cc;
  cc.method = ReductionMethod::craig_chang;
  cc.interface = boom.interface();
  cc.dynamic_modes.count = 20;
  cc.mass.beam_rotary_inertia = false;  // the analytic values assume none
  auto body_cc = reduce(boom.mesh, cc);
  REQUIRE(body_cc.ok());
  CHECK(body_cc->num_modes == 20 + 12);  // free-free modes + 6k inertia-relief modes
  // Analytic free-free bending (validation sheet): the lowest in each plane.
  const double ea = 210e9, rho_a = 7850 * boom.section.area, l = 4.5;
  for (double i_plane : {boom.section.iz, boom.section.iy}) {
    for (double beta : {4.730041, 7.853205}) {
      const double exact = beta * beta / (l * l) * std::sqrt(ea * i_plane / rho_a);
      double best = 1e300;
      for (Index k = 0; k < body_cc->num_modes; ++k)
        best = std::min(best, std::abs(std::sqrt(body_cc->eigenvalues(k)) / exact - 1));
      CHECK(best < 1e-3);
    }
  }
  // Principal angles between the spans of the modes below a cut-off (M inner product).
  ReductionSpec cb = cb_spec(boom.interface(), 20);
  cb.mass.beam_rotary_inertia = false;
  auto body_cb = reduce(boom.mesh, cb);
  REQUIRE(body_cb.ok());
  auto cm_cb = craig_bampton(boom.mesh, cb.interface, cb.dynamic_modes, cb.mass);
  auto cm_cc = craig_chang(boom.mesh, cc.interface, cc.dynamic_modes, cc.mass);
  REQUIRE(cm_cb.ok());
  REQUIRE(cm_cc.ok());
  auto d_cb = orthonormalize(boom.mesh, *cm_cb);
  auto d_cc = orthonormalize(boom.mesh, *cm_cc);
  REQUIRE(d_cb.ok());
  REQUIRE(d_cc.ok());
  // Cut-off 200 Hz: the two lowest bending modes in each plane (37, 51, 103, 142 Hz). The
  // free-free torsion mode at 295 Hz is where 20 fixed-interface modes start to show (angle
  // about 0.014 rad up to 300 Hz, measured).
  const double cutoff = 2 * kPi * 200.0;
  auto below = [&](const DeformationModes& d) {
    Index n = 0;
    while (n < d.eigenvalues.size() && d.eigenvalues(n) < cutoff * cutoff) ++n;
    return MatrixXd(d.modes.leftCols(n));
  };
  const MatrixXd a = below(*d_cb), b = below(*d_cc);
  REQUIRE(a.cols() == b.cols());
  REQUIRE(a.cols() >= 4);
  const SparseMatrixd& m = cm_cb->model.mass_all;
  // Both sets are M-orthonormal, so the singular values of A^T M B are the cosines.
  Eigen::JacobiSVD<MatrixXd> svd(a.transpose() * (m * b));
  const double min_cos = std::min(1.0, svd.singularValues().minCoeff());
  const double max_angle = std::acos(min_cos);
  MESSAGE("largest principal angle below 200 Hz: " << max_angle << " rad over " << a.cols()
                                                   << " modes");
  CHECK(max_angle < 1e-3);
}

TEST_CASE("inertia integrals equal the geometric mass, first moment and inertia tensor") {
  SUBCASE("uniform beam with rotary inertia") {
    Boom boom;
    auto body = reduce(boom.mesh, cb_spec(boom.interface(), 4));
    REQUIRE(body.ok());
    const double rho = 7850, a = boom.section.area, l = 4.5;
    const double m = rho * a * l;
    CHECK(body->mass() == doctest::Approx(m).epsilon(1e-13));
    CHECK((body->center_of_mass() - Vector3d(l / 2, 0, 0)).norm() < 1e-13);
    const Matrix3d j = body->inertia_about_origin();
    // About the frame origin (end A): thin-beam terms plus the section's own inertia.
    CHECK(j(0, 0) == doctest::Approx(rho * l * (boom.section.iy + boom.section.iz)).epsilon(1e-12));
    CHECK(j(1, 1) == doctest::Approx(m * l * l / 3 + rho * l * boom.section.iy).epsilon(1e-12));
    CHECK(j(2, 2) == doctest::Approx(m * l * l / 3 + rho * l * boom.section.iz).epsilon(1e-12));
    CHECK(std::abs(j(0, 1)) + std::abs(j(0, 2)) + std::abs(j(1, 2)) < 1e-12 * j(1, 1));
  }
  SUBCASE("brick bar (cuboid) with spiders") {
    BrickBar bar;
    auto body = reduce(bar.mesh, cb_spec({{bar.spider0}, {bar.spider1}}, 3));
    REQUIRE(body.ok());
    const double m = 7850 * 1.0 * 0.1 * 0.1;
    CHECK(body->mass() == doctest::Approx(m).epsilon(1e-13));
    CHECK((body->center_of_mass() - Vector3d(0.5, 0, 0)).norm() < 1e-13);
    // Cuboid about its centroid: m (b^2 + c^2) / 12; shifted to the origin by m d^2.
    const Matrix3d j = body->inertia_about_origin();
    CHECK(j(0, 0) == doctest::Approx(m * (0.01 + 0.01) / 12).epsilon(1e-12));
    CHECK(j(1, 1) == doctest::Approx(m * (1.0 + 0.01) / 12 + m * 0.25).epsilon(1e-12));
  }
}

TEST_CASE("deformation modes are mass-orthogonal to rigid motion; tr(Lambda_kl) = delta_kl") {
  for (auto lumping : {MassLumping::consistent, MassLumping::lumped}) {
    for (bool rotary : {true, false}) {
      Boom boom;
      ReductionSpec spec = cb_spec(boom.interface(), 4);
      spec.mass.lumping = lumping;
      spec.mass.beam_rotary_inertia = rotary;
      auto body = reduce(boom.mesh, spec);
      REQUIRE(body.ok());
      const auto& in = body->inertia;
      for (Index k = 1; k <= body->num_modes; ++k) {
        CAPTURE(k);
        // S_Phi = sum m phi_k = 0 and sum m u0 x phi_k = -2 unskew(Lambda_0k) = 0.
        CHECK(in.first[static_cast<std::size_t>(k)].norm() < 1e-10 * std::sqrt(body->mass()));
        CHECK(unskew(in.lambda(0, k)).norm() < 1e-10 * std::sqrt(body->mass()) * 4.5);
        for (Index l = 1; l <= body->num_modes; ++l)
          CHECK(std::abs(in.lambda(k, l).trace() - (k == l ? 1.0 : 0.0)) < 1e-11);
      }
    }
  }
}

TEST_CASE(
    "stress modes of a reduced brick body reproduce the FE stresses of an interface-loaded "
    "cantilever and beam theory") {
  // References: static exactness of the full Craig-Bampton basis (the FE stresses themselves,
  // to round-off) and Euler-Bernoulli bending, sigma_xx = M y / I (incompatible-mode bricks
  // recover beam theory on regular meshes, validation sheet).
  BrickBar bar;
  auto body = reduce(bar.mesh, cb_spec({{bar.spider0}, {bar.spider1}}, 4));  // full: 10 modes
  REQUIRE(body.ok());
  // Points at an element centre section, x = 13/24 m, a quarter of the height from the top and
  // bottom faces (inside the bricks, away from the spiders' local effects).
  const double x = 13.0 / 24.0, y = 0.025;
  const std::vector<Vector3d> points = {{x, y, 0.0}, {x, -y, 0.0}, {x, y, 0.025}};
  auto modes = body_stress_modes(bar.mesh, *body, points);
  REQUIRE(modes.ok());
  REQUIRE(modes->modes.rows() == 18);
  REQUIRE(modes->modes.cols() == 10);
  // The full model: clamped at x = 0, a 1 kN tip load along -y on the end spider.
  BoundaryConditions bc;
  bc.clamp(bar.spider0);
  auto full = assemble(bar.mesh, bc);
  REQUIRE(full.ok());
  auto solver = StaticSolver::factorize(bar.mesh, *full);
  REQUIRE(solver.ok());
  const double force = -1000.0;
  auto f = load_vector(full->dofs, {{bar.spider1, 1, force}});
  REQUIRE(f.ok());
  const VectorXd u = solver->solve(*f);
  auto locator = BrickLocator::build(bar.mesh);
  REQUIRE(locator.ok());
  auto op = point_stress_operator(bar.mesh, full->dofs, *locator, points);
  REQUIRE(op.ok());
  const VectorXd sigma_fe = *op * u;
  // The same displacement as rigid motion plus modal coordinates (least squares; it lies in
  // the span, so the fit is exact), then the stresses from the modes alone.
  auto shapes = all_dof_mode_shapes(bar.mesh, full->dofs, *body);
  REQUIRE(shapes.ok());
  MatrixXd basis(full->dofs.size(), 6 + body->num_modes);
  basis << rigid_body_modes(bar.mesh, full->dofs, Vector3d::Zero()), *shapes;
  const VectorXd c = basis.colPivHouseholderQr().solve(u);
  CHECK((basis * c - u).norm() < 1e-10 * u.norm());
  VectorXd sigma_modal(18);
  for (Index i = 0; i < 3; ++i) sigma_modal.segment<6>(6 * i) = modes->stress(i, c.tail(10));
  const double fit = (sigma_modal - sigma_fe).norm() / sigma_fe.norm();
  // Beam theory: M = F (L - x) about z; the top fibre (y > 0) is in tension under a downward load.
  const double i_z = 0.1 * std::pow(0.1, 3) / 12, beam = -force * (1.0 - x) * y / i_z;
  MESSAGE("stress modes vs FE stresses: " << fit << "; sigma_xx top " << sigma_modal(0)
                                          << " Pa, bottom " << sigma_modal(6) << " Pa, beam theory "
                                          << beam << " Pa");
  CHECK(fit < 1e-9);
  CHECK(std::abs(sigma_modal(0) / beam - 1) < 1e-3);
  CHECK(std::abs(sigma_modal(6) / -beam - 1) < 1e-3);
  // Off the neutral plane in z the bending stress about z is the same (no bending about y).
  CHECK(std::abs(sigma_modal(12) / sigma_modal(0) - 1) < 1e-3);
}

TEST_CASE("stress modes: bad points and foreign data get a clear error") {
  BrickBar bar;
  auto body = reduce(bar.mesh, cb_spec({{bar.spider0}, {bar.spider1}}, 2));
  REQUIRE(body.ok());
  auto outside = body_stress_modes(bar.mesh, *body, {{0.5, 0.0, 0.0}, {2.0, 0.0, 0.0}});
  REQUIRE_FALSE(outside.ok());
  MESSAGE(outside.error().what());
  CHECK(outside.error().message.find("outside") != std::string::npos);
  BrickBar other(6);
  auto foreign = body_stress_modes(other.mesh, *body, {{0.5, 0.0, 0.0}});
  REQUIRE_FALSE(foreign.ok());
  MESSAGE(foreign.error().what());
  CHECK(foreign.error().message.find("the mesh the body was reduced from") != std::string::npos);
}

TEST_CASE("bad reduction input gets a clear error") {
  Boom boom;
  SUBCASE("interface node not in the mesh") {
    auto r = reduce(boom.mesh, cb_spec({{boom.node_a}, {999}}, 2));
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().message.find("interface node 999 does not exist") != std::string::npos);
  }
  SUBCASE("more modes than exist") {
    ReductionSpec spec = cb_spec(boom.interface(), 4);
    spec.keep_modes = 11;
    auto r = reduce(boom.mesh, spec);
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().code == ErrorCode::size_mismatch);
    CHECK(r.error().message.find("only 10") != std::string::npos);
  }
  SUBCASE("no interface and no free-free modes") {
    ReductionSpec spec;
    spec.method = ReductionMethod::craig_chang;
    spec.dynamic_modes.count = 0;
    auto r = reduce(boom.mesh, spec);
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().message.find("no interface and no free-free modes") != std::string::npos);
  }
  SUBCASE("interface that cannot carry rigid motion") {
    auto r = reduce(boom.mesh, cb_spec({InterfaceNode::translations_only(boom.node_a)}, 4));
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().message.find("cannot carry all six rigid-body motions") != std::string::npos);
    CHECK(r.error().message.find("rotation about x") != std::string::npos);
  }
  SUBCASE("singular interior block: a part the interface does not hold") {
    // A second, unconnected beam floats freely when the interface is fixed.
    const Index p = boom.mesh.add_node(Vector3d(0, 1, 0)),
                q = boom.mesh.add_node(Vector3d(1, 1, 0));
    boom.mesh.add_beam(p, q, 0, 0);
    auto r = reduce(boom.mesh, cb_spec(boom.interface(), 2));
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().code == ErrorCode::singular_matrix);
    CHECK(r.error().message.find("interior block") != std::string::npos);
  }
}

}  // namespace test_reduction
