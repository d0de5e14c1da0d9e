// Geometric (initial-stress) stiffness of beams and bricks: the change of the internal forces'
// directions under a pre-existing stress state, K_G(sigma) u = the work-conjugate of
// 1/2 int sigma : (grad u)^T grad u dV. It is linear in the stress state, so a structure's
// K_G for any combination of load cases is the same combination of the load cases' K_G.
//
// Beam (axial force N, tension positive), consistent with the cubic Hermite interpolation of
// beam3d.hpp: McGuire, Gallagher & Ziemian, Matrix Structural Analysis (2000), eq. 9.18, i.e.
// N/(30 L) [36, 3L, -36, 3L; 3L, 4L^2, -3L, -L^2; ...] in each bending plane, plus the Wagner
// torsion term N (iy + iz) / (A L) for a doubly symmetric section. Bending moments and torque
// of the pre-stress are left out (their terms are small for slender beams and vanish for the
// axial stress states that stiffen rotating beams).
//
// Hex8: K_G(3a+i, 3b+i) = int grad N_a . sigma grad N_b dV (Bathe, Finite Element Procedures,
// sec. 6.3.2, the K_NL term), 2x2x2 Gauss points, with the stress of the element's own
// formulation (incompatible modes included) at those points.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/fe/assembly.hpp"
#include "flexstress/fe/beam3d.hpp"
#include "flexstress/fe/dof_map.hpp"
#include "flexstress/fe/hex8.hpp"
#include "flexstress/fe/mesh.hpp"

namespace flexstress::fe {

/// Local-axes geometric stiffness of a beam element under the axial force `normal`.
FLEXSTRESS_PRECOMPUTE
Matrix12d beam_local_geometric_stiffness(const BeamSection& s, double length, double normal) {
  const double l = length, c = normal / (30.0 * l);
  Matrix12d k = Matrix12d::Zero();
  // x-y plane: v1 (1), rz1 (5), v2 (7), rz2 (11), rz = dv/dx.
  {
    const int v1 = 1, r1 = 5, v2 = 7, r2 = 11;
    k(v1, v1) = k(v2, v2) = 36 * c;
    k(v1, v2) = k(v2, v1) = -36 * c;
    k(v1, r1) = k(r1, v1) = k(v1, r2) = k(r2, v1) = 3 * l * c;
    k(v2, r1) = k(r1, v2) = k(v2, r2) = k(r2, v2) = -3 * l * c;
    k(r1, r1) = k(r2, r2) = 4 * l * l * c;
    k(r1, r2) = k(r2, r1) = -l * l * c;
  }
  // x-z plane: w1 (2), ry1 (4), w2 (8), ry2 (10), ry = -dw/dx flips the coupling signs.
  {
    const int w1 = 2, r1 = 4, w2 = 8, r2 = 10;
    k(w1, w1) = k(w2, w2) = 36 * c;
    k(w1, w2) = k(w2, w1) = -36 * c;
    k(w1, r1) = k(r1, w1) = k(w1, r2) = k(r2, w1) = -3 * l * c;
    k(w2, r1) = k(r1, w2) = k(w2, r2) = k(r2, w2) = 3 * l * c;
    k(r1, r1) = k(r2, r2) = 4 * l * l * c;
    k(r1, r2) = k(r2, r1) = -l * l * c;
  }
  // Wagner term: a twisted bar under tension N stiffens by N r_p^2, r_p^2 = (iy + iz) / A.
  const double kt = normal * (s.iy + s.iz) / (s.area * l);
  k(3, 3) = k(9, 9) = kt;
  k(3, 9) = k(9, 3) = -kt;
  return k;
}

/// Global-axes geometric stiffness of a beam element whose nodal displacements (global) are
/// `u_global`: the axial force is that of the element under u.
FLEXSTRESS_PRECOMPUTE
Matrix12d beam_geometric_stiffness(const Mesh& mesh, const BeamElement& b,
                                   const Vector12d& u_global) {
  const BeamGeometry geo(mesh, b);
  const double normal = beam_section_forces(mesh, b, u_global, 0.5).normal;
  const Matrix12d t = beam_dof_rotation(geo.axes);
  return t.transpose() *
         beam_local_geometric_stiffness(mesh.section(b.section), geo.length, normal) * t;
}

/// Geometric stiffness of a hex8 element whose nodal displacements are `u_e` (24, node-major).
FLEXSTRESS_PRECOMPUTE
Result<Matrix24d> hex8_geometric_stiffness(const Hex8Coordinates& x, const Material& mat,
                                           Hex8Formulation formulation,
                                           const Eigen::Matrix<double, 24, 1>& u_e,
                                           Index element_id) {
  Matrix24d k = Matrix24d::Zero();
  const double g = hex8::gauss;
  for (int p = 0; p < 8; ++p) {
    const Vector3d xi((p & 1) ? g : -g, (p & 2) ? g : -g, (p & 4) ? g : -g);
    auto op = hex8_stress_operator(x, mat, formulation, xi, element_id);
    if (!op) return op.error();
    const Vector6d s = *op * u_e;  // xx yy zz xy yz zx (Voigt, as hex8.hpp)
    Matrix3d sigma;
    sigma << s(0), s(3), s(5), s(3), s(1), s(4), s(5), s(4), s(2);
    const Eigen::Matrix<double, 3, 8> dn_xi = hex8::shape_derivatives(xi);
    const Matrix3d j = x * dn_xi.transpose();
    const double det = j.determinant();
    const Eigen::Matrix<double, 3, 8> dn = inverse_transpose(j) * dn_xi;
    const Eigen::Matrix<double, 8, 8> kab = det * dn.transpose() * sigma * dn;
    for (int a = 0; a < 8; ++a)
      for (int b = 0; b < 8; ++b)
        for (int i = 0; i < 3; ++i) k(3 * a + i, 3 * b + i) += kab(a, b);
  }
  return k;
}

/// The structure's geometric stiffness (all nodal DOFs) for the stress state of the nodal
/// displacements `u` (all DOFs of `dofs`). Rigid links carry no stress and add nothing.
FLEXSTRESS_PRECOMPUTE
Result<SparseMatrixd> assemble_geometric_stiffness(const Mesh& mesh, const DofMap& dofs,
                                                   const VectorXd& u)
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  if (u.size() != dofs.size())
    return make_error(ErrorCode::size_mismatch, "geometric stiffness: displacement vector has ",
                      u.size(), " entries, the model ", dofs.size(), " DOFs");
  std::vector<Eigen::Triplet<double>> trip;
  for (Index e = 0; e < static_cast<Index>(mesh.beams().size()); ++e) {
    const BeamElement& b = mesh.beams()[static_cast<std::size_t>(e)];
    const auto d = detail::beam_dofs(dofs, b);
    Vector12d ue;
    for (int i = 0; i < 12; ++i) ue(i) = u(d[static_cast<std::size_t>(i)]);
    detail::scatter(trip, beam_geometric_stiffness(mesh, b, ue), d.data());
  }
  for (Index e = 0; e < static_cast<Index>(mesh.hexes().size()); ++e) {
    const Hex8Element& h = mesh.hexes()[static_cast<std::size_t>(e)];
    const auto d = detail::hex8_dofs(dofs, h);
    Eigen::Matrix<double, 24, 1> ue;
    for (int i = 0; i < 24; ++i) ue(i) = u(d[static_cast<std::size_t>(i)]);
    auto ke = hex8_geometric_stiffness(hex8_coordinates(mesh, h), mesh.material(h.material),
                                       h.formulation, ue, e);
    if (!ke) return ke.error();
    detail::scatter(trip, *ke, d.data());
  }
  SparseMatrixd k(dofs.size(), dofs.size());
  k.setFromTriplets(trip.begin(), trip.end());
  return k;
}
#else
    ;
#endif

}  // namespace flexstress::fe

// This header's precompute entry points (core/precompute.hpp).
#define FLEXSTRESS_PRECOMPUTE_FE_GEOMETRIC_STIFFNESS(X)             \
  X(4, Result<fe::SparseMatrixd>, fe::assemble_geometric_stiffness, \
    (const fe::Mesh&, const fe::DofMap&, const VectorXd&))
namespace flexstress {
FLEXSTRESS_PRECOMPUTE_EXTERN(FLEXSTRESS_PRECOMPUTE_FE_GEOMETRIC_STIFFNESS)
}  // namespace flexstress
