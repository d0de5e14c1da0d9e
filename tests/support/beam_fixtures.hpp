// Shared builders for the model and stress tests: reduced flexible bodies from FE models built in
// code.
#pragma once

#include <vector>

#include <doctest/doctest.h>

#include <flexstress/fe/assembly.hpp>
#include <flexstress/fe/beam_line.hpp>
#include <flexstress/fe/static_solver.hpp>
#include <flexstress/reduction/modal_body_data.hpp>

namespace flexstress::testing {

/// A straight steel beam along x from the origin, reduced by Craig-Bampton with the nodes at
/// `interface_positions` (distances from the origin) as six-DOF interface nodes.
struct BeamBody {
  fe::Mesh mesh;
  fe::BeamLine line;
  reduction::ModalBodyData data;
  std::vector<Index> interface_nodes;
};

inline BeamBody make_beam_body(double length, const fe::BeamSection& section, int elements,
                               std::vector<double> interface_positions, int fixed_modes,
                               fe::MassOptions mass = {},
                               const fe::Material& material = fe::steel()) {
  BeamBody b;
  fe::BeamLineSpec spec;
  spec.end = Vector3d(length, 0, 0);
  spec.num_elements = elements;
  spec.extra_positions = interface_positions;
  spec.material = b.mesh.add_material(material);
  spec.section = b.mesh.add_section(section);
  b.line = fe::add_beam_line(b.mesh, spec);
  reduction::ReductionSpec rs;
  for (double x : interface_positions) {
    b.interface_nodes.push_back(b.line.node_at(x));
    rs.interface.push_back({b.line.node_at(x)});
  }
  rs.dynamic_modes.count = fixed_modes;
  rs.mass = mass;
  auto data = reduction::reduce(b.mesh, rs);
  REQUIRE(data.ok());
  b.data = std::move(*data);
  return b;
}

/// The FE model of `b` (not reduced) clamped at node `clamped`, under its own weight along -y
/// (gravity 9.81 m/s^2 as consistent nodal loads M g): node `at`'s deflection along y.
inline double fe_deflection_under_weight(const BeamBody& b, Index clamped, Index at) {
  fe::BoundaryConditions bc;
  bc.clamp(clamped);
  auto full = fe::assemble(b.mesh, bc);
  REQUIRE(full.ok());
  auto solver = fe::StaticSolver::factorize(b.mesh, *full);
  REQUIRE(solver.ok());
  VectorXd g = VectorXd::Zero(full->dofs.size());
  for (Index n = 0; n < b.mesh.num_nodes(); ++n) g(full->dofs.dof(n, 1)) = -9.81;
  return solver->solve(full->mass_all * g)(full->dofs.dof(at, 1));
}

}  // namespace flexstress::testing
