// Geometric stiffness of beams and bricks against Euler's buckling load of a cantilever column,
// P_cr = pi^2 E I / (4 L^2) (Timoshenko & Gere, Theory of Elastic Stability, 2nd ed., sec. 2.1):
// the stress state of a unit compressive end load gives K_G, and the smallest lambda with
// (K + lambda K_G) x = 0 is the critical load.
#include <cmath>

#include <doctest/doctest.h>
#include <Eigen/Eigenvalues>

#include <flexstress/fe/assembly.hpp>
#include <flexstress/fe/beam_line.hpp>
#include <flexstress/fe/box_mesh.hpp>
#include <flexstress/fe/geometric_stiffness.hpp>
#include <flexstress/fe/static_solver.hpp>

namespace test_geometric_stiffness {

using namespace flexstress;
using namespace flexstress::fe;

namespace {

constexpr double kPi = 3.14159265358979323846;

// Smallest load factor of (K + lambda K_G) x = 0 over the free DOFs: the largest mu of
// -K_G x = mu K x (K positive definite, -K_G semi-definite under compression), lambda = 1/mu.
double critical_load_factor(const Mesh& mesh, const AssembledModel& model, const VectorXd& u) {
  auto kg = assemble_geometric_stiffness(mesh, model.dofs, u);
  REQUIRE(kg.ok());
  const SparseMatrixd& t = model.constraints.free_to_all();
  const MatrixXd g = MatrixXd(SparseMatrixd(t.transpose() * (*kg * t)));
  const MatrixXd k = MatrixXd(model.stiffness);
  Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> es(-g, k);
  REQUIRE(es.info() == Eigen::Success);
  return 1.0 / es.eigenvalues().maxCoeff();
}

// End-loaded column: static solution under a unit compressive force at the free end.
VectorXd unit_end_load_solution(const Mesh& mesh, const AssembledModel& model, Index tip,
                                int axis) {
  auto solver = StaticSolver::factorize(mesh, model);
  REQUIRE(solver.ok());
  VectorXd f = VectorXd::Zero(model.dofs.size());
  f(model.dofs.dof(tip, axis)) = -1.0;
  return solver->solve(f);
}

}  // namespace

TEST_CASE("beam geometric stiffness: Euler load of a cantilever column") {
  // Steel RHS 40 x 20 x 2 mm, 2 m: buckles about its weak axis (iy, in the x-z plane).
  Mesh mesh;
  BeamLineSpec spec;
  spec.end = Vector3d(2.0, 0, 0);
  spec.num_elements = 20;
  spec.material = mesh.add_material(steel());
  spec.section = mesh.add_section(rectangular_hollow_section(0.04, 0.02, 0.002));
  const BeamLine line = add_beam_line(mesh, spec);
  BoundaryConditions bc;
  bc.clamp(line.nodes.front());
  auto model = assemble(mesh, bc);
  REQUIRE(model.ok());
  const VectorXd u = unit_end_load_solution(mesh, *model, line.nodes.back(), 0);
  const double lambda = critical_load_factor(mesh, *model, u);
  const BeamSection& s = mesh.section(0);
  const double euler = kPi * kPi * 210e9 * std::min(s.iy, s.iz) / (4 * 2.0 * 2.0);
  MESSAGE("beam column: critical load " << lambda << " N, Euler " << euler << " N");
  // 20 cubic elements: the consistent K_G converges as h^2 from above (error ~1e-5 here).
  CHECK(lambda == doctest::Approx(euler).epsilon(1e-4));
  CHECK(lambda >= euler * (1 - 1e-9));
}

TEST_CASE("brick geometric stiffness: Euler load of a square column of hex8 bricks") {
  // 0.1 x 0.1 x 2 m column along z, 2 x 2 x 40 incompatible-mode bricks, clamped at z = 0.
  const double a = 0.1, len = 2.0;
  const int nxy = 2, nz = 40;
  Mesh mesh;
  BoxMeshSpec spec;
  spec.origin = Vector3d(-a / 2, -a / 2, 0);
  spec.size = Vector3d(a, a, len);
  spec.divisions = {nxy, nxy, nz};
  spec.material = mesh.add_material(steel());
  auto box = add_box_mesh(mesh, spec);
  REQUIRE(box.ok());
  auto id = [&](int i, int j, int k) { return box->node(i, j, k); };
  BoundaryConditions bc;
  for (int j = 0; j <= nxy; ++j)
    for (int i = 0; i <= nxy; ++i) bc.fix(id(i, j, 0), translation_components);
  auto model = assemble(mesh, bc);
  REQUIRE(model.ok());
  // A uniform compressive stress: the end load spread over the top face's nodes by their
  // tributary areas (corner 1, edge 2, centre 4 of 16).
  auto solver = StaticSolver::factorize(mesh, *model);
  REQUIRE(solver.ok());
  VectorXd f = VectorXd::Zero(model->dofs.size());
  for (int j = 0; j <= nxy; ++j)
    for (int i = 0; i <= nxy; ++i) {
      const double w = (i == 1 ? 2.0 : 1.0) * (j == 1 ? 2.0 : 1.0) / 16.0;
      f(model->dofs.dof(id(i, j, nz), 2)) = -w;
    }
  const VectorXd u = solver->solve(f);
  const double lambda = critical_load_factor(mesh, *model, u);
  const double euler = kPi * kPi * 210e9 * (a * a * a * a / 12) / (4 * len * len);
  MESSAGE("brick column: critical load " << lambda << " N, Euler " << euler << " N");
  // Slenderness 69: shear flexibility lowers the load by P/(k G A) ~ 0.1 %; the bricks'
  // discretization raises it. Two bricks across the section bend well with incompatible modes.
  CHECK(lambda == doctest::Approx(euler).epsilon(0.02));
}

TEST_CASE("geometric stiffness: no stress, no stiffness; tension stiffens, compression softens") {
  Mesh mesh;
  BeamLineSpec spec;
  spec.num_elements = 4;
  spec.material = mesh.add_material(steel());
  spec.section = mesh.add_section(rectangular_hollow_section(0.04, 0.02, 0.002));
  add_beam_line(mesh, spec);
  auto dofs = DofMap::build(mesh);
  REQUIRE(dofs.ok());
  auto zero = assemble_geometric_stiffness(mesh, *dofs, VectorXd::Zero(dofs->size()));
  REQUIRE(zero.ok());
  CHECK(zero->norm() == 0.0);
  auto bad = assemble_geometric_stiffness(mesh, *dofs, VectorXd::Zero(3));
  REQUIRE_FALSE(bad.ok());
  CHECK(std::string(bad.error().what()).find("3 entries") != std::string::npos);
  // Stretch the line uniformly: a transverse displacement field then gains energy.
  VectorXd stretch = VectorXd::Zero(dofs->size());
  for (Index n = 0; n < mesh.num_nodes(); ++n) stretch(dofs->dof(n, 0)) = 1e-3 * mesh.node(n).x();
  auto kg = assemble_geometric_stiffness(mesh, *dofs, stretch);
  REQUIRE(kg.ok());
  VectorXd bend = VectorXd::Zero(dofs->size());
  for (Index n = 0; n < mesh.num_nodes(); ++n)
    bend(dofs->dof(n, 1)) = std::pow(mesh.node(n).x(), 2);
  CHECK(bend.dot(*kg * bend) > 0.0);
  CHECK(bend.dot(*kg * bend) ==
        doctest::Approx(-bend.dot(*assemble_geometric_stiffness(mesh, *dofs, -stretch) * bend)));
}

}  // namespace test_geometric_stiffness
