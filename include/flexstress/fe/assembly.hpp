// Sparse assembly of stiffness and mass over all nodal DOFs, and the constrained system
// K_ff = T^T K T, M_ff = T^T M T (see constraint_transform.hpp).
#pragma once

#include <vector>

#include <Eigen/SparseCore>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/fe/beam3d.hpp"
#include "flexstress/fe/boundary_conditions.hpp"
#include "flexstress/fe/constraint_transform.hpp"
#include "flexstress/fe/dof_map.hpp"
#include "flexstress/fe/hex8.hpp"
#include "flexstress/fe/mass_options.hpp"
#include "flexstress/fe/mesh.hpp"

namespace flexstress::fe {

namespace detail {

template <class ElementMatrix>
void scatter(std::vector<Eigen::Triplet<double>>& trip, const ElementMatrix& ke,
             const Index* dof_of_row) {
  for (Index i = 0; i < ke.rows(); ++i)
    for (Index j = 0; j < ke.cols(); ++j)
      if (ke(i, j) != 0.0) trip.emplace_back(dof_of_row[i], dof_of_row[j], ke(i, j));
}

FLEXSTRESS_PRECOMPUTE
std::array<Index, 12> beam_dofs(const DofMap& dofs, const BeamElement& b) {
  std::array<Index, 12> d{};
  for (int n = 0; n < 2; ++n)
    for (int c = 0; c < 6; ++c)
      d[static_cast<std::size_t>(6 * n + c)] = dofs.dof(b.nodes[static_cast<std::size_t>(n)], c);
  return d;
}

FLEXSTRESS_PRECOMPUTE
std::array<Index, 24> hex8_dofs(const DofMap& dofs, const Hex8Element& h) {
  std::array<Index, 24> d{};
  for (int n = 0; n < 8; ++n)
    for (int c = 0; c < 3; ++c)
      d[static_cast<std::size_t>(3 * n + c)] = dofs.dof(h.nodes[static_cast<std::size_t>(n)], c);
  return d;
}

/// Adds a matrix element's entries (stiffness or mass) at their global DOFs.
inline void scatter_matrix_element(std::vector<Eigen::Triplet<double>>& trip, const DofMap& dofs,
                                   const MatrixElement& m,
                                   const std::vector<MatrixEntry>& entries) {
  const auto global = [&](Index local) {
    return dofs.dof(m.nodes[static_cast<std::size_t>(local / 3)], static_cast<int>(local % 3));
  };
  for (const MatrixEntry& e : entries)
    if (e.value != 0.0) trip.emplace_back(global(e.row), global(e.col), e.value);
}

}  // namespace detail

/// Global stiffness over all nodal DOFs. Fails on degenerate bricks (naming the element).
FLEXSTRESS_PRECOMPUTE
Result<SparseMatrixd> assemble_stiffness(const Mesh& mesh, const DofMap& dofs)
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(mesh.beams().size() * 144 + mesh.hexes().size() * 576);
  for (const auto& b : mesh.beams()) {
    const auto d = detail::beam_dofs(dofs, b);
    detail::scatter(trip, beam_stiffness(mesh, b), d.data());
  }
  for (std::size_t e = 0; e < mesh.hexes().size(); ++e) {
    const auto& h = mesh.hexes()[e];
    auto ke = hex8_stiffness(hex8_coordinates(mesh, h), mesh.material(h.material), h.formulation,
                             static_cast<Index>(e));
    if (!ke) return ke.error();
    const auto d = detail::hex8_dofs(dofs, h);
    detail::scatter(trip, *ke, d.data());
  }
  for (const auto& m : mesh.matrix_elements())
    detail::scatter_matrix_element(trip, dofs, m, m.stiffness);
  SparseMatrixd k(dofs.size(), dofs.size());
  k.setFromTriplets(trip.begin(), trip.end());
  return k;
}
#else
    ;
#endif

/// Global mass over all nodal DOFs (beams, bricks, point masses, matrix elements).
FLEXSTRESS_PRECOMPUTE
Result<SparseMatrixd> assemble_mass(const Mesh& mesh, const DofMap& dofs,
                                    const MassOptions& options = {})
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(mesh.beams().size() * 144 + mesh.hexes().size() * 192);
  for (const auto& b : mesh.beams()) {
    const auto d = detail::beam_dofs(dofs, b);
    detail::scatter(trip, beam_mass(mesh, b, options), d.data());
  }
  for (std::size_t e = 0; e < mesh.hexes().size(); ++e) {
    const auto& h = mesh.hexes()[e];
    auto me = hex8_mass(hex8_coordinates(mesh, h), mesh.material(h.material).density,
                        options.lumping, static_cast<Index>(e));
    if (!me) return me.error();
    const auto d = detail::hex8_dofs(dofs, h);
    detail::scatter(trip, *me, d.data());
  }
  for (const auto& p : mesh.point_masses()) {
    for (int c = 0; c < 3; ++c) trip.emplace_back(dofs.dof(p.node, c), dofs.dof(p.node, c), p.mass);
    if (dofs.has_rotations(p.node))
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          if (p.inertia(a, b) != 0.0)
            trip.emplace_back(dofs.dof(p.node, 3 + a), dofs.dof(p.node, 3 + b), p.inertia(a, b));
  }
  for (const auto& me : mesh.matrix_elements())
    detail::scatter_matrix_element(trip, dofs, me, me.mass);
  SparseMatrixd m(dofs.size(), dofs.size());
  m.setFromTriplets(trip.begin(), trip.end());
  return m;
}
#else
    ;
#endif

/// A mesh with its DOF numbering, constraints and assembled matrices: the input of the static
/// and eigen solvers, the reductions and the sub-model influence matrices.
struct AssembledModel {
  DofMap dofs;
  ConstraintTransform constraints;
  SparseMatrixd stiffness_all;  ///< K over all nodal DOFs
  SparseMatrixd mass_all;       ///< M over all nodal DOFs
  SparseMatrixd stiffness;      ///< T^T K T over the free DOFs
  SparseMatrixd mass;           ///< T^T M T over the free DOFs
  /// Coupling of free and prescribed DOFs, T^T K G: the load of unit prescribed values is
  /// -stiffness_prescribed * v.
  SparseMatrixd stiffness_prescribed;
};

/// Numbers the DOFs, builds the constraint transformation and assembles K and M.
FLEXSTRESS_PRECOMPUTE
Result<AssembledModel> assemble(const Mesh& mesh, const BoundaryConditions& bc = {},
                                const MassOptions& mass_options = {})
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  auto dofs = DofMap::build(mesh);
  if (!dofs) return dofs.error();
  auto ct = ConstraintTransform::build(mesh, *dofs, bc);
  if (!ct) return ct.error();
  auto k = assemble_stiffness(mesh, *dofs);
  if (!k) return k.error();
  auto m = assemble_mass(mesh, *dofs, mass_options);
  if (!m) return m.error();
  AssembledModel a{std::move(*dofs), std::move(*ct), std::move(*k), std::move(*m), {}, {}, {}};
  const SparseMatrixd& t = a.constraints.free_to_all();
  const SparseMatrixd kt = a.stiffness_all * t;
  a.stiffness = SparseMatrixd(t.transpose() * kt);
  a.mass = SparseMatrixd(t.transpose() * (a.mass_all * t));
  a.stiffness_prescribed =
      SparseMatrixd(t.transpose() * (a.stiffness_all * a.constraints.prescribed_to_all()));
  return a;
}
#else
    ;
#endif

/// Load vector over all DOFs from nodal forces/moments: (node, component, value) triples.
struct NodalLoad {
  Index node = 0;
  int component = 0;  ///< 0..2 force, 3..5 moment (global axes)
  double value = 0.0;
};

FLEXSTRESS_PRECOMPUTE
Result<VectorXd> load_vector(const DofMap& dofs, const std::vector<NodalLoad>& loads)
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  VectorXd f = VectorXd::Zero(dofs.size());
  for (std::size_t i = 0; i < loads.size(); ++i) {
    const auto& l = loads[i];
    const Index d = dofs.dof(l.node, l.component);
    if (d < 0)
      return make_error(ErrorCode::invalid_argument, "load ", i, " on node ", l.node, " component ",
                        dof_component_name(l.component),
                        ": the node does not exist or lacks that DOF");
    if (!std::isfinite(l.value))
      return make_error(ErrorCode::invalid_argument, "load ", i, " on node ", l.node,
                        " is not finite");
    f(d) += l.value;
  }
  return f;
}
#else
    ;
#endif

}  // namespace flexstress::fe

// This header's precompute entry points (core/precompute.hpp).
#define FLEXSTRESS_PRECOMPUTE_FE_ASSEMBLY(X)                                                    \
  X(1, Result<fe::SparseMatrixd>, fe::assemble_stiffness, (const fe::Mesh&, const fe::DofMap&)) \
  X(1, Result<fe::SparseMatrixd>, fe::assemble_mass,                                            \
    (const fe::Mesh&, const fe::DofMap&, const fe::MassOptions&))                               \
  X(1, Result<fe::AssembledModel>, fe::assemble,                                                \
    (const fe::Mesh&, const fe::BoundaryConditions&, const fe::MassOptions&))                   \
  X(1, Result<VectorXd>, fe::load_vector, (const fe::DofMap&, const std::vector<fe::NodalLoad>&))
namespace flexstress {
FLEXSTRESS_PRECOMPUTE_EXTERN(FLEXSTRESS_PRECOMPUTE_FE_ASSEMBLY)
}  // namespace flexstress
