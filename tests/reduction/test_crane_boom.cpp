// The crane's boom (examples/crane/boom_reduction.hpp): the reduced body's lowest elastic
// frequencies against the full beam model it was reduced from. Craig-Bampton reduction is a
// Rayleigh-Ritz projection, so each reduced frequency is an upper bound of the full model's
// (Craig & Kurdila, Fundamentals of Structural Dynamics, 2nd ed., sec. 17.3), and with the
// interface's static modes and 4 fixed-interface modes the first two elastic modes (the ones the
// stroke and the payload excite) should be within 1 %.
#include <cmath>

#include <doctest/doctest.h>

#include <flexstress/fe/assembly.hpp>
#include <flexstress/fe/eigen_solver.hpp>

#include "../../examples/crane/boom_reduction.hpp"

namespace test_crane_boom {

using namespace flexstress;

namespace {

// Free-free elastic eigenvalues (omega^2) of the full beam model, lowest n.
VectorXd full_elastic_eigenvalues(const fe::Mesh& mesh, int n) {
  auto model = fe::assemble(mesh);
  REQUIRE(model.ok());
  fe::EigenOptions eo;
  eo.num_modes = 6 + n;
  eo.method = fe::EigenMethod::dense;
  auto s = fe::solve_eigen(model->stiffness, model->mass, eo);
  REQUIRE(s.ok());
  CHECK(s->eigenvalues.head(6).cwiseAbs().maxCoeff() < 1e-6 * s->eigenvalues(6));  // rigid
  return s->eigenvalues.tail(n);
}

}  // namespace

TEST_CASE("crane boom: reduced elastic frequencies bound the full beam model's from above") {
  for (double payload : {100.0, 0.0}) {
    crane::CraneSpec spec;
    spec.payload_mass = payload;
    auto boom = crane::make_boom(spec, 10);
    REQUIRE(boom.ok());
    REQUIRE(boom->data.num_modes == 10);
    const int n = 4;
    const VectorXd full = full_elastic_eigenvalues(boom->mesh, n);
    for (int i = 0; i < n; ++i) {
      const double f_full = std::sqrt(full(i)) / (2 * M_PI);
      const double f_reduced = std::sqrt(boom->data.eigenvalues(i)) / (2 * M_PI);
      const double rel = (f_reduced - f_full) / f_full;
      MESSAGE("payload " << payload << " kg, elastic mode " << i + 1 << ": full " << f_full
                         << " Hz, reduced " << f_reduced << " Hz (" << 100 * rel << " %)");
      CHECK(rel > -1e-9);  // Rayleigh-Ritz: never below the full model
      if (i < 2) CHECK(rel < 0.01);
    }
  }
}

}  // namespace test_crane_boom
