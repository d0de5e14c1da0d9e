// Eight-node brick (hex8): trilinear displacement, full 2x2x2 Gauss integration, optionally
// enhanced by Wilson-Taylor incompatible modes with the Taylor-Beresford-Wilson modification.
//
// Incompatible modes (Wilson, Taylor, Doherty, Ghaboussi 1973; Taylor, Beresford, Wilson,
// Int. J. Num. Meth. Eng. 10 (1976) 1211-1219): nine extra displacement modes
// (1 - xi^2, 1 - eta^2, 1 - zeta^2 in each direction) remove the parasitic shear that locks the
// trilinear brick in bending. Their strains are formed with the Jacobian at the element centre
// and scaled by det J0 / det J, so that they integrate to zero over any element: a constant
// stress does no work on them and the element passes the patch test on distorted meshes. The
// modes are condensed out statically; stress recovery rebuilds them from the nodal displacements.
//
// Element DOFs: [u v w] of node 0, then node 1, ...; node order of Hex8Element (mesh.hpp).
// Stress and strain in Voigt order (xx, yy, zz, xy, yz, zx), engineering shear strains.
#pragma once

#include <array>
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/fe/mass_options.hpp"
#include "flexstress/fe/material.hpp"
#include "flexstress/fe/mesh.hpp"

namespace flexstress::fe {

using Matrix24d = Eigen::Matrix<double, 24, 24>;
using Vector24d = Eigen::Matrix<double, 24, 1>;
using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Hex8Coordinates = Eigen::Matrix<double, 3, 8>;      ///< columns: node positions
using Hex8StressOperator = Eigen::Matrix<double, 6, 24>;  ///< sigma = S u_e

namespace hex8 {

/// Natural coordinates of the nodes (Hex8Element order).
inline constexpr double node_xi[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                         {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
/// 2x2x2 Gauss points are at +-1/sqrt(3) in each direction, at the nodes' signs; weights 1.
inline constexpr double gauss = 0.57735026918962576451;

/// Shape functions at a natural point.
FLEXSTRESS_PRECOMPUTE
Eigen::Matrix<double, 8, 1> shape(const Vector3d& xi) {
  Eigen::Matrix<double, 8, 1> n;
  for (int a = 0; a < 8; ++a)
    n(a) = 0.125 * (1 + node_xi[a][0] * xi(0)) * (1 + node_xi[a][1] * xi(1)) *
           (1 + node_xi[a][2] * xi(2));
  return n;
}

/// Derivatives dN_a/dxi_j (3 x 8) at a natural point.
FLEXSTRESS_PRECOMPUTE
Eigen::Matrix<double, 3, 8> shape_derivatives(const Vector3d& xi) {
  Eigen::Matrix<double, 3, 8> d;
  for (int a = 0; a < 8; ++a) {
    const double s = node_xi[a][0], t = node_xi[a][1], u = node_xi[a][2];
    d(0, a) = 0.125 * s * (1 + t * xi(1)) * (1 + u * xi(2));
    d(1, a) = 0.125 * t * (1 + s * xi(0)) * (1 + u * xi(2));
    d(2, a) = 0.125 * u * (1 + s * xi(0)) * (1 + t * xi(1));
  }
  return d;
}

/// Natural coordinates of Gauss point g (same sign pattern as node g).
inline Vector3d gauss_point(int g) {
  return Vector3d(node_xi[g][0], node_xi[g][1], node_xi[g][2]) * gauss;
}

/// Strain-displacement matrix (6 x 3k) from Cartesian derivatives dN/dx (3 x k).
template <int K>
Eigen::Matrix<double, 6, 3 * K> strain_matrix(const Eigen::Matrix<double, 3, K>& dx) {
  Eigen::Matrix<double, 6, 3 * K> b = Eigen::Matrix<double, 6, 3 * K>::Zero();
  for (int a = 0; a < K; ++a) {
    const double nx = dx(0, a), ny = dx(1, a), nz = dx(2, a);
    b(0, 3 * a) = nx;
    b(1, 3 * a + 1) = ny;
    b(2, 3 * a + 2) = nz;
    b(3, 3 * a) = ny;
    b(3, 3 * a + 1) = nx;
    b(4, 3 * a + 1) = nz;
    b(4, 3 * a + 2) = ny;
    b(5, 3 * a) = nz;
    b(5, 3 * a + 2) = nx;
  }
  return b;
}

/// Strain matrix of the nine incompatible modes at xi (TBW form): derivatives of
/// (1 - xi_k^2) mapped with the centre Jacobian inverse j0_inv_t = J0^-T and scaled by
/// det J0 / det J.
FLEXSTRESS_PRECOMPUTE
Eigen::Matrix<double, 6, 9> incompatible_strain_matrix(const Vector3d& xi, const Matrix3d& j0_inv_t,
                                                       double det_ratio) {
  // dP_k/dxi_j = -2 xi_k delta_jk, so the Cartesian derivatives of mode k are a column of J0^-T.
  Eigen::Matrix<double, 3, 3> dx;
  for (int k = 0; k < 3; ++k) dx.col(k) = (-2.0 * xi(k) * det_ratio) * j0_inv_t.col(k);
  return strain_matrix<3>(dx);
}

}  // namespace hex8

/// J^-T of a 3x3 Jacobian by cofactors, cof(J) / det(J). (Also sidesteps false
/// maybe-uninitialized warnings of GCC 12 on Eigen's Inverse expression at -O1.)
FLEXSTRESS_PRECOMPUTE
Matrix3d inverse_transpose(const Matrix3d& j) {
  Matrix3d c;
  c.col(0) = j.col(1).cross(j.col(2));
  c.col(1) = j.col(2).cross(j.col(0));
  c.col(2) = j.col(0).cross(j.col(1));
  // Columns of J are a, b, c; rows of J^-1 are (b x c, c x a, a x b) / det, so J^-T has them
  // as columns.
  return c / j.col(0).dot(c.col(0));
}

/// Everything an element integration needs, computed once per element.
struct Hex8Kinematics {
  std::array<Eigen::Matrix<double, 6, 24>, 8> b;  ///< compatible strain matrices at Gauss pts
  std::array<double, 8> det_j{};                  ///< Jacobian determinants at Gauss points
  Matrix3d j0_inv_t = Matrix3d::Identity();       ///< J0^-T at the centre
  double det_j0 = 0.0;
};

/// Jacobian checks and Gauss-point kinematics. Fails for inverted or degenerate bricks
/// (non-positive Jacobian determinant at a Gauss point or the centre), naming the element.
FLEXSTRESS_PRECOMPUTE
Result<Hex8Kinematics> hex8_kinematics(const Hex8Coordinates& x, Index element_id)
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  Hex8Kinematics k;
  const double size = (x.rowwise().maxCoeff() - x.rowwise().minCoeff()).norm();
  const double tiny = 1e-12 * size * size * size;
  auto jacobian = [&](const Vector3d& xi) -> Matrix3d {
    return x * hex8::shape_derivatives(xi).transpose();  // J_ij = dx_i / dxi_j
  };
  const Matrix3d j0 = jacobian(Vector3d::Zero());
  k.det_j0 = j0.determinant();
  if (!(k.det_j0 > tiny))
    return make_error(ErrorCode::degenerate_element, "hex8 element ", element_id,
                      ": Jacobian determinant ", k.det_j0,
                      " at the centre is not positive (inverted, flat or mis-ordered nodes)");
  k.j0_inv_t = inverse_transpose(j0);
  for (int g = 0; g < 8; ++g) {
    const Vector3d xi = hex8::gauss_point(g);
    const Matrix3d j = jacobian(xi);
    const double det = j.determinant();
    if (!(det > tiny))
      return make_error(ErrorCode::degenerate_element, "hex8 element ", element_id,
                        ": Jacobian determinant ", det, " at Gauss point ", g,
                        " is not positive (inverted or badly distorted element)");
    k.det_j[static_cast<std::size_t>(g)] = det;
    const Eigen::Matrix<double, 3, 8> dx = inverse_transpose(j) * hex8::shape_derivatives(xi);
    k.b[static_cast<std::size_t>(g)] = hex8::strain_matrix<8>(dx);
  }
  return k;
}
#else
    ;
#endif

/// Condensation data of the incompatible modes: alpha = -K_aa^-1 K_au u_e.
struct Hex8Condensation {
  Eigen::Matrix<double, 9, 24> alpha_from_u = Eigen::Matrix<double, 9, 24>::Zero();
};

namespace detail {
// Stiffness blocks of the incompatible-mode element.
FLEXSTRESS_PRECOMPUTE
void hex8_incompatible_blocks(const Hex8Kinematics& k, const Matrix6d& d, Matrix24d& kuu,
                              Eigen::Matrix<double, 24, 9>& kua, Eigen::Matrix<double, 9, 9>& kaa) {
  kuu.setZero();
  kua.setZero();
  kaa.setZero();
  for (int g = 0; g < 8; ++g) {
    const auto gi = static_cast<std::size_t>(g);
    const double w = k.det_j[gi];
    const Eigen::Matrix<double, 6, 9> ba =
        hex8::incompatible_strain_matrix(hex8::gauss_point(g), k.j0_inv_t, k.det_j0 / w);
    const Eigen::Matrix<double, 6, 24> db = d * k.b[gi];
    kuu.noalias() += w * k.b[gi].transpose() * db;
    kua.noalias() += w * db.transpose() * ba;
    kaa.noalias() += w * ba.transpose() * d * ba;
  }
}
}  // namespace detail

/// Element stiffness (24 x 24) in global axes.
FLEXSTRESS_PRECOMPUTE
Result<Matrix24d> hex8_stiffness(const Hex8Coordinates& x, const Material& mat,
                                 Hex8Formulation formulation, Index element_id)
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  auto kin = hex8_kinematics(x, element_id);
  if (!kin) return kin.error();
  const Matrix6d d = elasticity_matrix(mat);
  if (formulation == Hex8Formulation::full_integration) {
    Matrix24d kk = Matrix24d::Zero();
    for (std::size_t g = 0; g < 8; ++g)
      kk.noalias() += kin->det_j[g] * kin->b[g].transpose() * d * kin->b[g];
    return kk;
  }
  Matrix24d kuu;
  Eigen::Matrix<double, 24, 9> kua;
  Eigen::Matrix<double, 9, 9> kaa;
  detail::hex8_incompatible_blocks(*kin, d, kuu, kua, kaa);
  const Eigen::Matrix<double, 9, 24> kaa_inv_kau = kaa.ldlt().solve(kua.transpose());
  return Matrix24d(kuu - kua * kaa_inv_kau);
}
#else
    ;
#endif

/// Consistent mass rho integral N^T N dV (2x2x2 Gauss, exact for the trilinear field on a
/// parallelepiped), or its row-sum lumped diagonal.
FLEXSTRESS_PRECOMPUTE
Result<Matrix24d> hex8_mass(const Hex8Coordinates& x, double density, MassLumping lumping,
                            Index element_id)
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  auto kin = hex8_kinematics(x, element_id);
  if (!kin) return kin.error();
  Eigen::Matrix<double, 8, 8> m = Eigen::Matrix<double, 8, 8>::Zero();
  for (int g = 0; g < 8; ++g) {
    const Eigen::Matrix<double, 8, 1> n = hex8::shape(hex8::gauss_point(g));
    m.noalias() += density * kin->det_j[static_cast<std::size_t>(g)] * n * n.transpose();
  }
  if (lumping == MassLumping::lumped) {
    const Eigen::Matrix<double, 8, 1> rows = m.rowwise().sum();
    m.setZero();
    m.diagonal() = rows;
  }
  Matrix24d out = Matrix24d::Zero();
  for (int a = 0; a < 8; ++a)
    for (int b = 0; b < 8; ++b)
      for (int c = 0; c < 3; ++c) out(3 * a + c, 3 * b + c) = m(a, b);
  return out;
}
#else
    ;
#endif

/// Scalar (per-direction) consistent mass matrix rho integral N_a N_b dV (8 x 8): the full mass
/// is this matrix times the 3x3 identity. Used for inertia integrals (nodal-based FFRF).
FLEXSTRESS_PRECOMPUTE
Result<Eigen::Matrix<double, 8, 8>> hex8_scalar_mass(const Hex8Coordinates& x, double density,
                                                     MassLumping lumping, Index element_id) {
  auto full = hex8_mass(x, density, lumping, element_id);
  if (!full) return full.error();
  Eigen::Matrix<double, 8, 8> m;
  for (int a = 0; a < 8; ++a)
    for (int b = 0; b < 8; ++b) m(a, b) = (*full)(3 * a, 3 * b);
  return m;
}

/// Linear operator from element displacements to the stress at natural point xi:
/// sigma = D (B(xi) u_e + B_alpha(xi) alpha(u_e)). For incompatible modes the condensed modes are
/// recovered from u_e exactly as in the stiffness condensation.
FLEXSTRESS_PRECOMPUTE
Result<Hex8StressOperator> hex8_stress_operator(const Hex8Coordinates& x, const Material& mat,
                                                Hex8Formulation formulation, const Vector3d& xi,
                                                Index element_id)
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  auto kin = hex8_kinematics(x, element_id);
  if (!kin) return kin.error();
  const Matrix6d d = elasticity_matrix(mat);
  const Matrix3d j = x * hex8::shape_derivatives(xi).transpose();
  const double det = j.determinant();
  if (!(det > 0.0))
    return make_error(ErrorCode::degenerate_element, "hex8 element ", element_id,
                      ": Jacobian determinant ", det, " at the stress point is not positive");
  const Eigen::Matrix<double, 6, 24> b = hex8::strain_matrix<8>(
      Eigen::Matrix<double, 3, 8>(inverse_transpose(j) * hex8::shape_derivatives(xi)));
  if (formulation == Hex8Formulation::full_integration) return Hex8StressOperator(d * b);
  Matrix24d kuu;
  Eigen::Matrix<double, 24, 9> kua;
  Eigen::Matrix<double, 9, 9> kaa;
  detail::hex8_incompatible_blocks(*kin, d, kuu, kua, kaa);
  const Eigen::Matrix<double, 9, 24> alpha = -kaa.ldlt().solve(kua.transpose());
  const Eigen::Matrix<double, 6, 9> ba =
      hex8::incompatible_strain_matrix(xi, kin->j0_inv_t, kin->det_j0 / det);
  return Hex8StressOperator(d * (b + ba * alpha));
}
#else
    ;
#endif

/// Natural coordinates of a physical point (inverse isoparametric map, Newton's method).
/// Returns the natural coordinates whether or not the point lies inside; check
/// hex8_contains(). Fails only if Newton does not converge (point far outside a distorted
/// element).
FLEXSTRESS_PRECOMPUTE
Result<Vector3d> hex8_natural_coordinates(const Hex8Coordinates& x, const Vector3d& p,
                                          Index element_id) {
  Vector3d xi = Vector3d::Zero();
  const double size = (x.rowwise().maxCoeff() - x.rowwise().minCoeff()).norm();
  for (int it = 0; it < 50; ++it) {
    const Vector3d r = x * hex8::shape(xi) - p;
    if (r.norm() <= 1e-13 * size) return xi;
    const Matrix3d j = x * hex8::shape_derivatives(xi).transpose();
    const Vector3d step = j.partialPivLu().solve(r);
    if (!step.allFinite()) break;
    xi -= step;
    if (xi.cwiseAbs().maxCoeff() > 1e3) break;  // far away: no point in iterating on
  }
  return make_error(ErrorCode::not_converged, "hex8 element ", element_id,
                    ": inverse map of point (", p.x(), ", ", p.y(), ", ", p.z(),
                    ") did not converge");
}

/// True if natural coordinates lie in the element (with a relative tolerance).
inline bool hex8_contains(const Vector3d& xi, double tolerance = 1e-9) {
  return xi.cwiseAbs().maxCoeff() <= 1.0 + tolerance;
}

/// Coordinates of a brick's nodes from the mesh.
FLEXSTRESS_PRECOMPUTE
Hex8Coordinates hex8_coordinates(const Mesh& mesh, const Hex8Element& h) {
  Hex8Coordinates x;
  for (int a = 0; a < 8; ++a) x.col(a) = mesh.node(h.nodes[static_cast<std::size_t>(a)]);
  return x;
}

}  // namespace flexstress::fe

// This header's precompute entry points (core/precompute.hpp).
#define FLEXSTRESS_PRECOMPUTE_FE_HEX8(X)                                                     \
  X(3, Result<fe::Matrix24d>, fe::hex8_stiffness,                                            \
    (const fe::Hex8Coordinates&, const fe::Material&, fe::Hex8Formulation, Index))           \
  X(3, Result<fe::Matrix24d>, fe::hex8_mass,                                                 \
    (const fe::Hex8Coordinates&, double, fe::MassLumping, Index))                            \
  X(3, Result<fe::Hex8Kinematics>, fe::hex8_kinematics, (const fe::Hex8Coordinates&, Index)) \
  X(5, Result<fe::Hex8StressOperator>, fe::hex8_stress_operator,                             \
    (const fe::Hex8Coordinates&, const fe::Material&, fe::Hex8Formulation, const Vector3d&,  \
     Index))
namespace flexstress {
FLEXSTRESS_PRECOMPUTE_EXTERN(FLEXSTRESS_PRECOMPUTE_FE_HEX8)
}  // namespace flexstress
