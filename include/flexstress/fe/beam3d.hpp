// Two-node 3D beam element: Euler-Bernoulli with optional Timoshenko shear correction.
//
// Element DOFs (global axes): [u1 v1 w1 rx1 ry1 rz1 | u2 v2 w2 rx2 ry2 rz2]. Interpolation in
// local axes, xi = x / L in [0, 1]: axial u and torsion rx linear; v (x-y plane) and w (x-z
// plane) cubic Hermite, with rz = dv/dx and ry = -dw/dx. The mass matrix and every inertia
// integral of a beam (reduction/) integrate this same interpolation, so that the modal body's
// inertia is consistent with the FE mass matrix (Shabana, Dynamics of Multibody Systems, ch. 5).
//
// Stiffness: Przemieniecki, Theory of Matrix Structural Analysis (1968), ch. 5, with the shear
// parameters Phi_y = 12 E iz / (G As_y L^2), Phi_z = 12 E iy / (G As_z L^2) for Timoshenko
// (Phi = 0 for Euler-Bernoulli). The mass uses the Euler-Bernoulli interpolation in both cases.
#pragma once

#include <array>
#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/fe/beam_section.hpp"
#include "flexstress/fe/mass_options.hpp"
#include "flexstress/fe/material.hpp"
#include "flexstress/fe/mesh.hpp"

namespace flexstress::fe {

using Matrix12d = Eigen::Matrix<double, 12, 12>;
using Vector12d = Eigen::Matrix<double, 12, 1>;
using Matrix3x12d = Eigen::Matrix<double, 3, 12>;

/// Rows are the local axes (x, y, z) in global coordinates: v_local = R v_global.
FLEXSTRESS_PRECOMPUTE
Matrix3d beam_local_axes(const Vector3d& x0, const Vector3d& x1, const Vector3d& orientation) {
  const Vector3d ex = (x1 - x0).normalized();
  Vector3d ref = orientation;
  if (ref.squaredNorm() == 0.0)
    ref = std::abs(ex.y()) > 0.99 ? Vector3d::UnitZ() : Vector3d::UnitY();
  const Vector3d ey = (ref - ref.dot(ex) * ex).normalized();
  const Vector3d ez = ex.cross(ey);
  Matrix3d r;
  r.row(0) = ex.transpose();
  r.row(1) = ey.transpose();
  r.row(2) = ez.transpose();
  return r;
}

/// 12x12 block-diagonal rotation global -> local for the element DOF vector.
FLEXSTRESS_PRECOMPUTE
Matrix12d beam_dof_rotation(const Matrix3d& r) {
  Matrix12d t = Matrix12d::Zero();
  for (int b = 0; b < 4; ++b) t.block<3, 3>(3 * b, 3 * b) = r;
  return t;
}

/// Local-axes stiffness (Przemieniecki). phi_y, phi_z: Timoshenko shear parameters (0 = EB).
FLEXSTRESS_PRECOMPUTE
Matrix12d beam_local_stiffness(const Material& mat, const BeamSection& s, double length,
                               double phi_y, double phi_z) {
  const double e = mat.youngs_modulus, g = mat.shear_modulus(), l = length;
  const double l2 = l * l, l3 = l2 * l;
  Matrix12d k = Matrix12d::Zero();
  // Axial and torsion.
  const double ka = e * s.area / l, kt = g * s.torsion_constant / l;
  k(0, 0) = k(6, 6) = ka;
  k(0, 6) = k(6, 0) = -ka;
  k(3, 3) = k(9, 9) = kt;
  k(3, 9) = k(9, 3) = -kt;
  // Bending in the x-y plane: DOFs v1 (1), rz1 (5), v2 (7), rz2 (11).
  {
    const double c = e * s.iz / ((1.0 + phi_y) * l3);
    const int v1 = 1, r1 = 5, v2 = 7, r2 = 11;
    k(v1, v1) = k(v2, v2) = 12 * c;
    k(v1, v2) = k(v2, v1) = -12 * c;
    k(v1, r1) = k(r1, v1) = k(v1, r2) = k(r2, v1) = 6 * l * c;
    k(v2, r1) = k(r1, v2) = k(v2, r2) = k(r2, v2) = -6 * l * c;
    k(r1, r1) = k(r2, r2) = (4.0 + phi_y) * l2 * c;
    k(r1, r2) = k(r2, r1) = (2.0 - phi_y) * l2 * c;
  }
  // Bending in the x-z plane: DOFs w1 (2), ry1 (4), w2 (8), ry2 (10); ry = -dw/dx flips signs
  // of the coupling terms.
  {
    const double c = e * s.iy / ((1.0 + phi_z) * l3);
    const int w1 = 2, r1 = 4, w2 = 8, r2 = 10;
    k(w1, w1) = k(w2, w2) = 12 * c;
    k(w1, w2) = k(w2, w1) = -12 * c;
    k(w1, r1) = k(r1, w1) = k(w1, r2) = k(r2, w1) = -6 * l * c;
    k(w2, r1) = k(r1, w2) = k(w2, r2) = k(r2, w2) = 6 * l * c;
    k(r1, r1) = k(r2, r2) = (4.0 + phi_z) * l2 * c;
    k(r1, r2) = k(r2, r1) = (2.0 - phi_z) * l2 * c;
  }
  return k;
}

/// Local-axes interpolation at xi in [0, 1]: centre-line displacement n_u (3x12) and section
/// rotation n_r (3x12), both in local axes, acting on the local element DOF vector.
FLEXSTRESS_PRECOMPUTE
void beam_local_interpolation(double xi, double length, Matrix3x12d& n_u, Matrix3x12d& n_r) {
  const double l = length, x2 = xi * xi, x3 = x2 * xi;
  const double h1 = 1 - 3 * x2 + 2 * x3, h2 = l * (xi - 2 * x2 + x3), h3 = 3 * x2 - 2 * x3,
               h4 = l * (-x2 + x3);
  // Derivatives d/dx = (1/L) d/dxi.
  const double d1 = (-6 * xi + 6 * x2) / l, d2 = 1 - 4 * xi + 3 * x2, d3 = (6 * xi - 6 * x2) / l,
               d4 = -2 * xi + 3 * x2;
  n_u.setZero();
  n_r.setZero();
  n_u(0, 0) = 1 - xi;
  n_u(0, 6) = xi;
  // v = h1 v1 + h2 rz1 + h3 v2 + h4 rz2
  n_u(1, 1) = h1;
  n_u(1, 5) = h2;
  n_u(1, 7) = h3;
  n_u(1, 11) = h4;
  // w = h1 w1 - h2 ry1 + h3 w2 - h4 ry2
  n_u(2, 2) = h1;
  n_u(2, 4) = -h2;
  n_u(2, 8) = h3;
  n_u(2, 10) = -h4;
  n_r(0, 3) = 1 - xi;
  n_r(0, 9) = xi;
  // ry = -dw/dx
  n_r(1, 2) = -d1;
  n_r(1, 4) = d2;
  n_r(1, 8) = -d3;
  n_r(1, 10) = d4;
  // rz = dv/dx
  n_r(2, 1) = d1;
  n_r(2, 5) = d2;
  n_r(2, 7) = d3;
  n_r(2, 11) = d4;
}

/// Gauss-Legendre points and weights on [0, 1]; four points integrate degree 7 exactly, enough
/// for products of the cubic interpolation.
struct GaussLine4 {
  static constexpr int n = 4;
  static constexpr std::array<double, 4> xi{0.0694318442029737, 0.3300094782075719,
                                            0.6699905217924281, 0.9305681557970263};
  static constexpr std::array<double, 4> w{0.1739274225687269, 0.3260725774312731,
                                           0.3260725774312731, 0.1739274225687269};
};

/// Geometry of one beam element: length, local axes and the element DOF rotation.
struct BeamGeometry {
  double length = 0.0;
  Matrix3d axes = Matrix3d::Identity();  ///< rows: local x, y, z in global coordinates
  Vector3d x0 = Vector3d::Zero();        ///< first node position

  BeamGeometry(const Mesh& mesh, const BeamElement& b)
      : length((mesh.node(b.nodes[1]) - mesh.node(b.nodes[0])).norm()),
        axes(beam_local_axes(mesh.node(b.nodes[0]), mesh.node(b.nodes[1]), b.orientation)),
        x0(mesh.node(b.nodes[0])) {}

  /// Interpolation matrices in *global* axes acting on the *global* element DOF vector.
  FLEXSTRESS_PRECOMPUTE
  void interpolation(double xi, Matrix3x12d& n_u, Matrix3x12d& n_r) const;
  /// Position on the undeformed centre line.
  Vector3d point(double xi) const { return x0 + xi * length * axes.row(0).transpose(); }
  /// Second moments of area tensor integral s s^T dA of the section, in global axes.
  Matrix3d section_tensor(const BeamSection& s) const {
    const Vector3d ey = axes.row(1).transpose(), ez = axes.row(2).transpose();
    return s.iz * ey * ey.transpose() + s.iy * ez * ez.transpose();
  }
};

#if FLEXSTRESS_PRECOMPUTE_BODIES
template <class>
void BeamGeometry::interpolation(double xi, Matrix3x12d& n_u, Matrix3x12d& n_r) const {
  Matrix3x12d lu, lr;
  beam_local_interpolation(xi, length, lu, lr);
  const Matrix12d t = beam_dof_rotation(axes);
  n_u = axes.transpose() * lu * t;
  n_r = axes.transpose() * lr * t;
}
#endif

/// Global-axes stiffness matrix of a beam element.
FLEXSTRESS_PRECOMPUTE
Matrix12d beam_stiffness(const Mesh& mesh, const BeamElement& b)
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  const BeamGeometry geo(mesh, b);
  const Material& mat = mesh.material(b.material);
  const BeamSection& s = mesh.section(b.section);
  double phi_y = 0.0, phi_z = 0.0;
  if (b.theory == BeamTheory::timoshenko) {
    const double g = mat.shear_modulus(), l2 = geo.length * geo.length;
    phi_y = 12.0 * mat.youngs_modulus * s.iz / (g * s.shear_area_y * l2);
    phi_z = 12.0 * mat.youngs_modulus * s.iy / (g * s.shear_area_z * l2);
  }
  const Matrix12d t = beam_dof_rotation(geo.axes);
  return t.transpose() * beam_local_stiffness(mat, s, geo.length, phi_y, phi_z) * t;
}
#else
    ;
#endif

/// Global-axes mass matrix of a beam element, integrated from the interpolation: kinetic energy
/// 1/2 integral rho (A |u_dot|^2 + theta_dot^T J_s theta_dot) dx, J_s the polar tensor of the
/// section (tr(I_s) 1 - I_s). Without rotary inertia J_s keeps only torsion about the axis.
FLEXSTRESS_PRECOMPUTE
Matrix12d beam_mass(const Mesh& mesh, const BeamElement& b, const MassOptions& opt)
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  const BeamGeometry geo(mesh, b);
  const double rho = mesh.material(b.material).density;
  const BeamSection& s = mesh.section(b.section);
  const Vector3d ex = geo.axes.row(0).transpose();
  Matrix3d js;  // polar inertia tensor of the section per unit length and density
  if (opt.beam_rotary_inertia) {
    const Matrix3d is = geo.section_tensor(s);
    js = is.trace() * Matrix3d::Identity() - is;
  } else {
    js = s.polar_moment() * ex * ex.transpose();
  }
  const double l = geo.length;
  if (opt.lumping == MassLumping::lumped) {
    Matrix12d m = Matrix12d::Zero();
    const double half = 0.5 * rho * s.area * l;
    // Bending rotations get half the section's rotary inertia even when rotary inertia is off,
    // so that the lumped matrix stays positive definite.
    const Matrix3d is = geo.section_tensor(s);
    const Matrix3d jl = 0.5 * rho * l * (is.trace() * Matrix3d::Identity() - is);
    for (int n = 0; n < 2; ++n) {
      m.block<3, 3>(6 * n, 6 * n).diagonal().setConstant(half);
      m.block<3, 3>(6 * n + 3, 6 * n + 3) = jl;
    }
    return m;
  }
  Matrix12d m = Matrix12d::Zero();
  Matrix3x12d nu, nr;
  for (int g = 0; g < GaussLine4::n; ++g) {
    geo.interpolation(GaussLine4::xi[static_cast<std::size_t>(g)], nu, nr);
    const double w = GaussLine4::w[static_cast<std::size_t>(g)] * l * rho;
    m.noalias() += w * (s.area * nu.transpose() * nu + nr.transpose() * js * nr);
  }
  return m;
}
#else
    ;
#endif

/// Section forces in local axes at xi, from the element's own displacement field (curvature of
/// the cubic Hermite field): normal force N = E A u', torque T = G J rx', bending moments
/// Mz = E iz v'' and My = -E iy w'' (right-hand rule about the local axes).
struct BeamSectionForces {
  double normal = 0.0, torque = 0.0, moment_y = 0.0, moment_z = 0.0;
};

FLEXSTRESS_PRECOMPUTE
BeamSectionForces beam_section_forces(const Mesh& mesh, const BeamElement& b,
                                      const Vector12d& u_global, double xi) {
  const BeamGeometry geo(mesh, b);
  const Material& mat = mesh.material(b.material);
  const BeamSection& s = mesh.section(b.section);
  const Vector12d u = beam_dof_rotation(geo.axes) * u_global;
  const double l = geo.length;
  // Second derivatives of the Hermite functions with respect to x.
  const double b1 = (-6 + 12 * xi) / (l * l), b2 = (-4 + 6 * xi) / l, b3 = (6 - 12 * xi) / (l * l),
               b4 = (-2 + 6 * xi) / l;
  const double v_xx = b1 * u(1) + b2 * u(5) + b3 * u(7) + b4 * u(11);
  const double w_xx = b1 * u(2) - b2 * u(4) + b3 * u(8) - b4 * u(10);
  BeamSectionForces f;
  f.normal = mat.youngs_modulus * s.area * (u(6) - u(0)) / l;
  f.torque = mat.shear_modulus() * s.torsion_constant * (u(9) - u(3)) / l;
  f.moment_z = mat.youngs_modulus * s.iz * v_xx;
  f.moment_y = -mat.youngs_modulus * s.iy * w_xx;
  return f;
}

/// Axial (normal) stress at a fibre (y, z) of the section (local axes), at xi (0 at the
/// element's first node, 1 at its second): sigma_xx = N / A - Mz y / iz + My z / iy, i.e.
/// E (u' - y v'' - z w''). u_global: the two nodes' displacements and rotations in global axes,
/// [u(0); theta(0); u(1); theta(1)] (a flexible body's mode k: phi_r(node).col(k) and
/// phi_theta(node).col(k) of its ModalBodyData, for a stress output row).
FLEXSTRESS_PRECOMPUTE
double beam_fibre_stress(const Mesh& mesh, const BeamElement& b, const Vector12d& u_global,
                         double xi, double y, double z) {
  const BeamSection& s = mesh.section(b.section);
  const BeamSectionForces f = beam_section_forces(mesh, b, u_global, xi);
  return f.normal / s.area - f.moment_z * y / s.iz + f.moment_y * z / s.iy;
}

}  // namespace flexstress::fe

// This header's precompute entry points (core/precompute.hpp).
#define FLEXSTRESS_PRECOMPUTE_FE_BEAM3D(X)                                           \
  X(3, fe::Matrix12d, fe::beam_stiffness, (const fe::Mesh&, const fe::BeamElement&)) \
  X(3, fe::Matrix12d, fe::beam_mass,                                                 \
    (const fe::Mesh&, const fe::BeamElement&, const fe::MassOptions&))               \
  X(3, void, fe::BeamGeometry::interpolation, (double, fe::Matrix3x12d&, fe::Matrix3x12d&) const)
namespace flexstress {
FLEXSTRESS_PRECOMPUTE_EXTERN(FLEXSTRESS_PRECOMPUTE_FE_BEAM3D)
}  // namespace flexstress
