// The opt-in Spectra shift-invert eigen solver (eigen_solver_spectra.hpp) against the library's
// own subspace iteration with a Sturm check (eigen_solver.hpp, Bathe, Finite Element
// Procedures, sec. 11.6) on the RHS sub-model (about 9000 DOFs), and against the residual
// ||K x - lambda M x|| and M-orthonormality that define an eigenpair. Built only when CMake
// found Spectra (it defines FLEXSTRESS_TEST_SPECTRA).
#ifdef FLEXSTRESS_TEST_SPECTRA

#include <doctest/doctest.h>

#include <flexstress/fe/assembly.hpp>
#include <flexstress/fe/eigen_solver.hpp>
#include <flexstress/fe/eigen_solver_spectra.hpp>
#include <flexstress/fe/rhs_attachment_mesh.hpp>

namespace test_eigen_solver_spectra {

using namespace flexstress;
using namespace flexstress::fe;

TEST_CASE("Spectra shift-invert agrees with subspace iteration on the RHS sub-model" *
          doctest::test_suite("long")) {
  auto r = make_rhs_attachment_mesh();  // density 1: 1792 bricks
  REQUIRE(r.ok());
  Mesh& mesh = r->mesh;
  const Index m0 = mesh.add_node(Vector3d(r->spec.x0, 0, 0));
  mesh.add_rigid_link(m0, r->end_section_x0);
  BoundaryConditions bc;
  bc.clamp(m0);  // a short cantilever, clamped through the rigid end section
  auto model = assemble(mesh, bc);
  REQUIRE(model.ok());
  MESSAGE("RHS sub-model eigen problem: " << model->stiffness.rows() << " free DOFs");
  CHECK(model->stiffness.rows() > 5000);
  CHECK(model->stiffness.rows() < 10000);
  EigenOptions options;
  options.num_modes = 10;
  options.method = EigenMethod::subspace_iteration;
  auto subspace = solve_eigen(model->stiffness, model->mass, options);
  REQUIRE_MESSAGE(subspace.ok(), subspace.error().what());
  auto spectra = solve_eigen_spectra(model->stiffness, model->mass, options);
  REQUIRE_MESSAGE(spectra.ok(), spectra.error().what());
  const EigenSolution& s = *spectra;
  REQUIRE(s.eigenvalues.size() == 10);
  for (int i = 0; i < 10; ++i) {
    CAPTURE(i);
    CHECK(s.eigenvalues(i) == doctest::Approx(subspace->eigenvalues(i)).epsilon(1e-8));
  }
  MESSAGE("lowest frequencies [Hz]: " << s.frequencies_hz().transpose());
  // Mass-normalized, and each pair satisfies K x = lambda M x.
  const MatrixXd& x = s.vectors;
  CHECK((x.transpose() * (model->mass * x) - MatrixXd::Identity(10, 10)).cwiseAbs().maxCoeff() <
        1e-10);
  for (int i = 0; i < 10; ++i) {
    const VectorXd kx = model->stiffness * x.col(i);
    CHECK((kx - s.eigenvalues(i) * (model->mass * x.col(i))).norm() < 1e-8 * kx.norm());
  }
}

TEST_CASE("Spectra shift-invert: free-free structure and bad input") {
  auto r = make_rhs_attachment_mesh();
  REQUIRE(r.ok());
  auto model = assemble(r->mesh);
  REQUIRE(model.ok());
  EigenOptions options;
  options.num_modes = 8;
  auto s = solve_eigen_spectra(model->stiffness, model->mass, options);
  REQUIRE_MESSAGE(s.ok(), s.error().what());
  // Six rigid-body modes (zero frequency), then elastic ones (Craig & Kurdila, Fundamentals of
  // Structural Dynamics, sec. 10.5).
  for (int i = 0; i < 6; ++i) CHECK(std::abs(s->eigenvalues(i)) < 1e-6 * s->eigenvalues(6));
  CHECK(s->eigenvalues(6) > 0.0);
  options.num_modes = 0;
  CHECK_FALSE(solve_eigen_spectra(model->stiffness, model->mass, options).ok());
  const SparseMatrixd small(3, 3);
  options.num_modes = 2;
  auto bad = solve_eigen_spectra(model->stiffness, small, options);
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error().code == ErrorCode::size_mismatch);
}

}  // namespace test_eigen_solver_spectra

#endif  // FLEXSTRESS_TEST_SPECTRA
