// 3D beam element and the FE pipeline on beams, against Euler-Bernoulli beam theory
// (reference values: ../shared validation sheet; Blevins, Formulas for Natural Frequency and
// Mode Shape, table 8-1, for beta_n L).
#include <cmath>

#include <doctest/doctest.h>

#include <flexstress/fe/assembly.hpp>
#include <flexstress/fe/beam_line.hpp>
#include <flexstress/fe/eigen_solver.hpp>
#include <flexstress/fe/static_solver.hpp>

namespace test_beam {

using namespace flexstress;
using namespace flexstress::fe;

namespace {

// The crane boom's section and steel (paper, Table 2).
struct BeamFixture {
  Mesh mesh;
  BeamLine line;
  double length = 4.5;
  BeamSection section = rectangular_hollow_section(0.15, 0.10, 0.004);
  Material steel_ = steel();
  BeamFixture(int elements, BeamTheory theory = BeamTheory::euler_bernoulli) {
    BeamLineSpec spec;
    spec.end = Vector3d(length, 0, 0);
    spec.num_elements = elements;
    spec.material = mesh.add_material(steel_);
    spec.section = mesh.add_section(section);
    spec.theory = theory;
    line = add_beam_line(mesh, spec);
  }
  double analytic_omega(double beta_l, double i) const {
    return beta_l * beta_l / (length * length) *
           std::sqrt(steel_.youngs_modulus * i / (steel_.density * section.area));
  }
};

// Frequencies of bending in the x-y plane only (v, rz), by fixing the other DOFs: keeps the
// comparison one-to-one with the planar beam theory.
// The clamped first node is left out (it is fixed already).
void fix_out_of_plane(BoundaryConditions& bc, const BeamLine& line) {
  for (std::size_t i = 1; i < line.nodes.size(); ++i)
    bc.fix(line.nodes[i], 0).fix(line.nodes[i], 2).fix(line.nodes[i], 3).fix(line.nodes[i], 4);
}

}  // namespace

TEST_CASE("RHS 150x100x4 section matches the paper's Table 2") {
  const BeamSection s = rectangular_hollow_section(0.15, 0.10, 0.004);
  CHECK(s.area == doctest::Approx(1.936e-3).epsilon(1e-12));
  CHECK(s.iz == doctest::Approx(6.17e-6).epsilon(1e-3));  // Table 2: 6.17e-6 (strong axis)
  CHECK(s.iy == doctest::Approx(3.29e-6).epsilon(2e-3));  // Table 2: 3.29e-6
}

TEST_CASE("cantilever tip load and tip moment: exact at the nodes (Hermite beam)") {
  BeamFixture f(4);
  BoundaryConditions bc;
  bc.clamp(f.line.nodes.front());
  auto model = assemble(f.mesh, bc);
  REQUIRE(model.ok());
  auto solver = StaticSolver::factorize(f.mesh, *model);
  REQUIRE(solver.ok());
  const Index tip = f.line.nodes.back();
  const double p = 1000.0, moment = 500.0, e = f.steel_.youngs_modulus;
  auto load = load_vector(model->dofs, {{tip, 1, p}, {tip, 2, p}});
  REQUIRE(load.ok());
  const VectorXd u = solver->solve(*load);
  // Tip load: P L^3 / (3 E I) in each plane, with the plane's own second moment.
  const double l3 = std::pow(f.length, 3);
  CHECK(u(model->dofs.dof(tip, 1)) ==
        doctest::Approx(p * l3 / (3 * e * f.section.iz)).epsilon(1e-10));
  CHECK(u(model->dofs.dof(tip, 2)) ==
        doctest::Approx(p * l3 / (3 * e * f.section.iy)).epsilon(1e-10));
  // Tip slope P L^2 / (2 E I); rz = dv/dx, ry = -dw/dx.
  const double l2 = f.length * f.length;
  CHECK(u(model->dofs.dof(tip, 5)) ==
        doctest::Approx(p * l2 / (2 * e * f.section.iz)).epsilon(1e-10));
  CHECK(u(model->dofs.dof(tip, 4)) ==
        doctest::Approx(-p * l2 / (2 * e * f.section.iy)).epsilon(1e-10));
  // Tip moment M about z: deflection M L^2 / (2 E I).
  auto mload = load_vector(model->dofs, {{tip, 5, moment}});
  REQUIRE(mload.ok());
  const VectorXd um = solver->solve(*mload);
  CHECK(um(model->dofs.dof(tip, 1)) ==
        doctest::Approx(moment * l2 / (2 * e * f.section.iz)).epsilon(1e-10));
  // Bending stress at the clamp, top fibre: M c / I with M = P L (sigma = -M y / I, tension
  // on top for a downward... here the load is +y, so the top fibre y = +h/2 is compressed).
  const BeamElement& root = f.mesh.beams().front();
  Vector12d ue;
  for (int n = 0; n < 2; ++n)
    for (int c = 0; c < 6; ++c) ue(6 * n + c) = u(model->dofs.dof(root.nodes[n], c));
  const double sigma = beam_fibre_stress(f.mesh, root, ue, 0.0, 0.075, 0.0);
  CHECK(sigma == doctest::Approx(-p * f.length * 0.075 / f.section.iz - 0.0).epsilon(1e-9));
}

TEST_CASE("cantilever: first four bending frequencies within 0.1% (20 elements, EB, consistent)") {
  BeamFixture f(20);
  BoundaryConditions bc;
  bc.clamp(f.line.nodes.front());
  fix_out_of_plane(bc, f.line);
  MassOptions mo;
  mo.beam_rotary_inertia = false;  // the analytic values assume no rotary inertia
  auto model = assemble(f.mesh, bc, mo);
  REQUIRE(model.ok());
  EigenOptions eo;
  eo.num_modes = 4;
  auto sol = solve_eigen(model->stiffness, model->mass, eo);
  REQUIRE(sol.ok());
  const double beta[] = {1.875104, 4.694091, 7.854757, 10.995541};  // clamped-free
  for (int i = 0; i < 4; ++i) {
    const double exact = f.analytic_omega(beta[i], f.section.iz);
    CHECK(std::sqrt(sol->eigenvalues(i)) == doctest::Approx(exact).epsilon(1e-3));
  }
  // Mass normalization and orthogonality.
  const MatrixXd x = sol->vectors;
  CHECK((x.transpose() * (model->mass * x) - MatrixXd::Identity(4, 4)).norm() < 1e-10);
  const MatrixXd kx = x.transpose() * (model->stiffness * x);
  CHECK((kx - MatrixXd(sol->eigenvalues.asDiagonal())).norm() < 1e-9 * sol->eigenvalues(3));
}

TEST_CASE("rotary inertia, shear and lumping each lower the frequencies by a little") {
  // Measured against the EB consistent model (reported in docs/fe.md). For this stocky section
  // (L / h = 30) the validation sheet expects shifts of up to about 1% in the low modes.
  auto first_four = [](BeamTheory theory, MassOptions mo) {
    BeamFixture f(20, theory);
    BoundaryConditions bc;
    bc.clamp(f.line.nodes.front());
    fix_out_of_plane(bc, f.line);
    auto model = assemble(f.mesh, bc, mo);
    REQUIRE(model.ok());
    EigenOptions eo;
    eo.num_modes = 4;
    auto sol = solve_eigen(model->stiffness, model->mass, eo);
    REQUIRE(sol.ok());
    return VectorXd(sol->eigenvalues.cwiseSqrt());
  };
  MassOptions eb;
  eb.beam_rotary_inertia = false;
  MassOptions rotary;
  MassOptions lumped;
  lumped.lumping = MassLumping::lumped;
  lumped.beam_rotary_inertia = false;
  const VectorXd base = first_four(BeamTheory::euler_bernoulli, eb);
  const VectorXd with_rotary = first_four(BeamTheory::euler_bernoulli, rotary);
  const VectorXd with_shear = first_four(BeamTheory::timoshenko, eb);
  const VectorXd with_lumping = first_four(BeamTheory::euler_bernoulli, lumped);
  for (int i = 0; i < 4; ++i) {
    MESSAGE("mode " << i + 1 << ": rotary " << (with_rotary(i) / base(i) - 1) * 100 << "%, shear "
                    << (with_shear(i) / base(i) - 1) * 100 << "%, lumped "
                    << (with_lumping(i) / base(i) - 1) * 100 << "%");
    CHECK(with_rotary(i) < base(i));
    CHECK(with_shear(i) < base(i));
    CHECK(with_lumping(i) < base(i));
    CHECK(with_rotary(i) > 0.97 * base(i));
    CHECK(with_shear(i) > 0.95 * base(i));
  }
  // First mode: all three well under 1%.
  CHECK(with_rotary(0) > 0.999 * base(0));
  CHECK(with_shear(0) > 0.995 * base(0));
}

TEST_CASE("free-free beam: six rigid modes, then the analytic bending frequencies") {
  BeamFixture f(20);
  MassOptions mo;
  mo.beam_rotary_inertia = false;
  auto model = assemble(f.mesh, {}, mo);
  REQUIRE(model.ok());
  EigenOptions eo;
  eo.num_modes = 6 + 6;
  auto sol = solve_eigen(model->stiffness, model->mass, eo);
  REQUIRE(sol.ok());
  const double first_elastic = sol->eigenvalues(6);
  for (int i = 0; i < 6; ++i) CHECK(std::abs(sol->eigenvalues(i)) < 1e-8 * first_elastic);
  // In 3D the elastic modes interleave bending about y and z and torsion/axial; match the
  // free-free bending values for each plane among the elastic eigenvalues.
  const double beta[] = {4.730041, 7.853205, 10.995608};
  std::vector<double> omegas;
  for (Index i = 6; i < 12; ++i) omegas.push_back(std::sqrt(sol->eigenvalues(i)));
  for (double i_plane : {f.section.iz, f.section.iy}) {
    for (int n = 0; n < 2; ++n) {
      const double exact = f.analytic_omega(beta[n], i_plane);
      double best = 1e300;
      for (double w : omegas) best = std::min(best, std::abs(w / exact - 1));
      CHECK(best < 1e-3);
    }
  }
}

TEST_CASE("K and M are symmetric, M is positive definite") {
  BeamFixture f(7, BeamTheory::timoshenko);
  f.mesh.add_point_mass(f.line.nodes[3], 5.0, Matrix3d::Identity() * 0.2);
  for (auto lumping : {MassLumping::consistent, MassLumping::lumped}) {
    MassOptions mo;
    mo.lumping = lumping;
    auto model = assemble(f.mesh, {}, mo);
    REQUIRE(model.ok());
    const MatrixXd k(model->stiffness_all), m(model->mass_all);
    CHECK((k - k.transpose()).norm() <= 1e-14 * k.norm());
    CHECK((m - m.transpose()).norm() <= 1e-14 * m.norm());
    Eigen::SelfAdjointEigenSolver<MatrixXd> es(m);
    CHECK(es.eigenvalues().minCoeff() > 0.0);
    // Total translational mass: rho A L + point mass, seen by a rigid translation.
    const MatrixXd r = rigid_body_modes(f.mesh, model->dofs, Vector3d::Zero());
    const double mass = r.col(0).dot(m * r.col(0));
    CHECK(mass == doctest::Approx(7850 * f.section.area * f.length + 5.0).epsilon(1e-12));
  }
}

TEST_CASE("consistent beam mass equals the closed form (Przemieniecki) in the x-y plane") {
  Mesh mesh;
  const Index mat = mesh.add_material(steel());
  const Index sec = mesh.add_section(rectangular_hollow_section(0.15, 0.1, 0.004));
  const Index a = mesh.add_node(Vector3d::Zero()), b = mesh.add_node(Vector3d(0.7, 0, 0));
  const Index e = mesh.add_beam(a, b, mat, sec);
  MassOptions mo;
  mo.beam_rotary_inertia = false;
  const Matrix12d m = beam_mass(mesh, mesh.beams()[static_cast<std::size_t>(e)], mo);
  const double l = 0.7, ml = 7850 * mesh.section(sec).area * l / 420.0;
  // v1 rz1 v2 rz2 = DOFs 1 5 7 11: 156, 22L, 54, -13L; 4L^2, 13L, -3L^2; 156, -22L; 4L^2.
  CHECK(m(1, 1) == doctest::Approx(156 * ml));
  CHECK(m(1, 5) == doctest::Approx(22 * l * ml));
  CHECK(m(1, 7) == doctest::Approx(54 * ml));
  CHECK(m(1, 11) == doctest::Approx(-13 * l * ml));
  CHECK(m(5, 5) == doctest::Approx(4 * l * l * ml));
  CHECK(m(5, 11) == doctest::Approx(-3 * l * l * ml));
  CHECK(m(0, 0) == doctest::Approx(140 * ml));
  CHECK(m(0, 6) == doctest::Approx(70 * ml));
}

TEST_CASE("bad beam input gets a clear error") {
  Mesh mesh;
  const Index mat = mesh.add_material(steel());
  const Index sec = mesh.add_section(rectangular_hollow_section(0.15, 0.1, 0.004));
  const Index a = mesh.add_node(Vector3d::Zero());
  SUBCASE("zero-length beam") {
    const Index b = mesh.add_node(Vector3d::Zero());
    mesh.add_beam(a, b, mat, sec);
    auto r = assemble(mesh);
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().code == ErrorCode::degenerate_element);
    CHECK(r.error().message.find("beam 0 has zero length") != std::string::npos);
  }
  SUBCASE("missing node") {
    mesh.add_beam(a, 7, mat, sec);
    auto r = assemble(mesh);
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().message.find("beam 0 refers to node 7") != std::string::npos);
  }
  SUBCASE("non-finite coordinate") {
    const Index b = mesh.add_node(Vector3d(std::nan(""), 0, 0));
    mesh.add_beam(a, b, mat, sec);
    auto r = assemble(mesh);
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().message.find("node 1 has a non-finite coordinate") != std::string::npos);
  }
  SUBCASE("bad material") {
    Mesh m2;
    Material bad = steel();
    bad.youngs_modulus = -1;
    const Index bm = m2.add_material(bad);
    const Index s2 = m2.add_section(rectangular_hollow_section(0.15, 0.1, 0.004));
    m2.add_beam(m2.add_node(Vector3d::Zero()), m2.add_node(Vector3d::UnitX()), bm, s2);
    auto r = assemble(m2);
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().message.find("material 0: Young's modulus must be positive") !=
          std::string::npos);
  }
  SUBCASE("prescribed DOF on a node that does not exist") {
    const Index b = mesh.add_node(Vector3d::UnitX());
    mesh.add_beam(a, b, mat, sec);
    BoundaryConditions bc;
    bc.clamp(42);
    auto r = assemble(mesh, bc);
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().message.find("node 42, which does not exist") != std::string::npos);
  }
  SUBCASE("singular stiffness names the free rigid motions") {
    const Index b = mesh.add_node(Vector3d::UnitX());
    mesh.add_beam(a, b, mat, sec);
    BoundaryConditions bc;
    bc.pin(a);  // translations only: the beam can still spin about the pin
    auto model = assemble(mesh, bc);
    REQUIRE(model.ok());
    auto s = StaticSolver::factorize(mesh, *model);
    REQUIRE_FALSE(s.ok());
    CHECK(s.error().code == ErrorCode::singular_matrix);
    MESSAGE(s.error().message);
    CHECK(s.error().message.find("rotation about x") != std::string::npos);
    CHECK(s.error().message.find("rotation about y") != std::string::npos);
    CHECK(s.error().message.find("rotation about z") != std::string::npos);
    CHECK(s.error().message.find("translation") == std::string::npos);
  }
}

TEST_CASE("dense and subspace-iteration eigen solvers agree (with a Sturm check)") {
  BeamFixture f(60);
  BoundaryConditions bc;
  bc.clamp(f.line.nodes.front());
  auto model = assemble(f.mesh, bc);
  REQUIRE(model.ok());
  EigenOptions eo;
  eo.num_modes = 8;
  eo.method = EigenMethod::dense;
  auto dense = solve_eigen(model->stiffness, model->mass, eo);
  eo.method = EigenMethod::subspace_iteration;
  auto sub = solve_eigen(model->stiffness, model->mass, eo);
  REQUIRE(dense.ok());
  REQUIRE(sub.ok());
  for (int i = 0; i < 8; ++i) {
    CHECK(sub->eigenvalues(i) == doctest::Approx(dense->eigenvalues(i)).epsilon(1e-9));
  }
  // Same for a free-free model (K singular).
  auto free_model = assemble(f.mesh);
  REQUIRE(free_model.ok());
  eo.num_modes = 10;
  auto sub_free = solve_eigen(free_model->stiffness, free_model->mass, eo);
  eo.method = EigenMethod::dense;
  auto dense_free = solve_eigen(free_model->stiffness, free_model->mass, eo);
  REQUIRE(sub_free.ok());
  REQUIRE(dense_free.ok());
  for (int i = 6; i < 10; ++i)
    CHECK(sub_free->eigenvalues(i) == doctest::Approx(dense_free->eigenvalues(i)).epsilon(1e-9));
}

}  // namespace test_beam
