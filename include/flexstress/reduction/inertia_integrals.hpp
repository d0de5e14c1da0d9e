// Inertia shape integrals of a flexible body, consistent with its FE mass matrix.
//
// For fields a, b (a = 0: the undeformed position u0; a = k >= 1: deformation mode k) the
// second moments Lambda_ab = integral rho a b^T dV (3x3) and first moments S_a = integral rho a dV
// determine every term of the FFRF mass matrix and quadratic velocity vector (Shabana, Dynamics
// of Multibody Systems, ch. 5; the FFRF reference sheet): e.g. sum m u u^T = Lambda_00 +
// sum_k p_k (Lambda_0k + Lambda_0k^T) + sum_kl p_k p_l Lambda_kl, and M_ff = tr Lambda_kl.
//
// They are integrated with the elements' own interpolation, so they are exactly consistent with
// the assembled mass matrix (tr Lambda_kl = phi_k^T M phi_l):
//  - bricks: nodal-based, Lambda_ab = sum_ij m_ij a_i b_j^T with the scalar consistent (or lumped)
//    mass m_ij (Zwoelfer and Gerstmayr, "The nodal-based floating frame of reference
//    formulation with modal reduction", Acta Mech. 232 (2021));
//  - beams: Gauss quadrature of the centre-line field c(x) and the section field theta(x) x s,
//    integral (c + theta x s)(c' + theta' x s)^T dA = A c c'^T + skew(theta) I_s skew(theta')^T
//    with I_s = integral s s^T dA. Without bending rotary inertia a formal tensor
//    I_s = J/2 (1 - 2 e_x e_x^T) keeps only the torsional inertia J about the axis, as the FE
//    mass does;
//  - point masses: m and a rotational inertia J about the node, through the equivalent tensor
//    I = tr(J)/2 1 - J;
//  - matrix elements (imported solid models): nodal-based as the bricks, with the scalar mass
//    read from the given matrix, which must have the form m_ab I.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/skew.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/fe/beam3d.hpp"
#include "flexstress/fe/dof_map.hpp"
#include "flexstress/fe/hex8.hpp"
#include "flexstress/fe/mass_options.hpp"
#include "flexstress/fe/mesh.hpp"
#include "flexstress/reduction/inertia_moments.hpp"

namespace flexstress::reduction {

namespace detail {

/// Equivalent second-moment tensor of a rotational inertia J about a point: the I with
/// tr(I) 1 - I = J.
inline Matrix3d second_moment_of_inertia(const Matrix3d& j) {
  return 0.5 * j.trace() * Matrix3d::Identity() - j;
}

/// Adds a lumped mass m with equivalent tensor i_eq at a node whose field values are
/// c[a] (translation) and r[a] (rotation, zero when the node has none).
FLEXSTRESS_PRECOMPUTE
void add_lumped(InertiaIntegrals& out, double m, const Matrix3d& i_eq,
                const std::vector<Vector3d>& c, const std::vector<Vector3d>& r) {
  const Index nf = out.num_modes + 1;
  out.mass += m;
  for (Index a = 0; a < nf; ++a)
    out.first[static_cast<std::size_t>(a)] += m * c[static_cast<std::size_t>(a)];
  for (Index a = 0; a < nf; ++a)
    for (Index b = 0; b < nf; ++b) {
      const auto ia = static_cast<std::size_t>(a), ib = static_cast<std::size_t>(b);
      Matrix3d t = m * c[ia] * c[ib].transpose();
      if (a == 0 && b == 0)
        t += i_eq;
      else if (a == 0)
        t -= i_eq * skew(r[ib]);
      else if (b == 0)
        t -= (i_eq * skew(r[ia])).transpose();
      else
        t += skew(r[ia]) * i_eq * skew(r[ib]).transpose();
      out.lambda(a, b) += t;
    }
}

/// Nodal-based moments (bricks, matrix elements) of the fields x[a] (3 x n nodal values) over a
/// scalar mass m (n x n) with row sums m 1: mass += 1^T m 1, S_a += X_a m 1,
/// Lambda_ab += X_a m X_b^T. `xm` is scratch of the same shape as x.
template <class Field, class Mass, class RowSums>
void add_nodal_moments(InertiaIntegrals& out, const std::vector<Field>& x, std::vector<Field>& xm,
                       const Mass& m, const RowSums& row_sums) {
  const auto nf = static_cast<Index>(x.size());
  out.mass += row_sums.sum();
  for (Index a = 0; a < nf; ++a) {
    const auto ia = static_cast<std::size_t>(a);
    xm[ia] = x[ia] * m;
    out.first[ia] += x[ia] * row_sums;
  }
  for (Index a = 0; a < nf; ++a)
    for (Index b = 0; b < nf; ++b)
      out.lambda(a, b).noalias() +=
          xm[static_cast<std::size_t>(a)] * x[static_cast<std::size_t>(b)].transpose();
}

/// The scalar mass m_pq (nodes p, q) of a matrix element whose mass is m_pq I: translations
/// coupled only to the same component, alike in x, y and z (solid elements, consistent or
/// lumped). Anything else is refused: its inertia integrals are not defined by the matrix alone.
inline Result<Eigen::SparseMatrix<double>> matrix_element_scalar_mass(const fe::MatrixElement& me,
                                                                      std::size_t e) {
  const auto n = static_cast<Index>(me.nodes.size());
  std::array<std::vector<Eigen::Triplet<double>>, 3> trip;
  static constexpr const char* axis = "xyz";
  for (const fe::MatrixEntry& t : me.mass) {
    if (t.value == 0.0) continue;
    const Index cr = t.row % 3, cc = t.col % 3;
    if (cr != cc)
      return make_error(ErrorCode::invalid_argument, "matrix element ", e, ": the mass couples ",
                        axis[cr], " of its node ", t.row / 3, " with ", axis[cc], " of its node ",
                        t.col / 3,
                        "; inertia integrals need a mass of the form m_ab I (solid "
                        "elements: each translation coupled only to the same component)");
    trip[static_cast<std::size_t>(cr)].emplace_back(t.row / 3, t.col / 3, t.value);
  }
  std::array<Eigen::SparseMatrix<double>, 3> m;
  for (std::size_t c = 0; c < 3; ++c) {
    m[c].resize(n, n);
    m[c].setFromTriplets(trip[c].begin(), trip[c].end());
  }
  const double size = m[0].norm();
  for (std::size_t c = 1; c < 3; ++c) {
    const double differs = (m[c] - m[0]).norm();
    if (!(differs <= 1e-10 * size))
      return make_error(ErrorCode::invalid_argument, "matrix element ", e, ": the mass of ",
                        axis[c], " differs from that of x (relative ", differs / size,
                        "); inertia integrals need a mass of the form m_ab I");
  }
  return m[0];
}

}  // namespace detail

/// Integrates the first and second moments of u0 and of the columns of `modes` (all-DOF
/// vectors of `dofs`) over the mesh, with the same mass model as fe::assemble_mass(options).
FLEXSTRESS_PRECOMPUTE
Result<InertiaIntegrals> inertia_integrals(const fe::Mesh& mesh, const fe::DofMap& dofs,
                                           const MatrixXd& modes, const fe::MassOptions& options)
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  if (modes.rows() != dofs.size())
    return make_error(ErrorCode::size_mismatch, "inertia integrals: mode vectors have ",
                      modes.rows(), " rows but the mesh has ", dofs.size(), " DOFs");
  InertiaIntegrals out;
  out.num_modes = modes.cols();
  const Index nf = out.num_modes + 1;
  out.first.assign(static_cast<std::size_t>(nf), Vector3d::Zero());
  out.second.assign(static_cast<std::size_t>(nf * nf), Matrix3d::Zero());

  // Bricks: Lambda_ab += X_a m_e X_b^T with X_a the 3x8 nodal values of field a.
  std::vector<Eigen::Matrix<double, 3, 8>> x(static_cast<std::size_t>(nf)),
      xm(static_cast<std::size_t>(nf));
  for (std::size_t e = 0; e < mesh.hexes().size(); ++e) {
    const auto& h = mesh.hexes()[e];
    const fe::Hex8Coordinates coords = fe::hex8_coordinates(mesh, h);
    auto me = fe::hex8_scalar_mass(coords, mesh.material(h.material).density, options.lumping,
                                   static_cast<Index>(e));
    if (!me) return me.error();
    x[0] = coords;
    for (Index k = 0; k < out.num_modes; ++k)
      for (int a = 0; a < 8; ++a)
        for (int c = 0; c < 3; ++c)
          x[static_cast<std::size_t>(k + 1)](c, a) =
              modes(dofs.dof(h.nodes[static_cast<std::size_t>(a)], c), k);
    const Eigen::Matrix<double, 8, 1> row_sums = me->rowwise().sum();
    detail::add_nodal_moments(out, x, xm, *me, row_sums);
  }

  // Beams.
  std::vector<Vector3d> c(static_cast<std::size_t>(nf)), r(static_cast<std::size_t>(nf));
  for (const auto& b : mesh.beams()) {
    const fe::BeamGeometry geo(mesh, b);
    const fe::BeamSection& s = mesh.section(b.section);
    const double rho = mesh.material(b.material).density, l = geo.length;
    const Vector3d ex = geo.axes.row(0).transpose();
    Eigen::Matrix<double, 12, Eigen::Dynamic> qe(12, out.num_modes);
    for (Index k = 0; k < out.num_modes; ++k)
      for (int n = 0; n < 2; ++n)
        for (int cc = 0; cc < 6; ++cc)
          qe(6 * n + cc, k) = modes(dofs.dof(b.nodes[static_cast<std::size_t>(n)], cc), k);
    if (options.lumping == fe::MassLumping::lumped) {
      // Same lumping as fe::beam_mass: half the mass and half the section inertia per node.
      const Matrix3d is = geo.section_tensor(s);
      const Matrix3d jl = 0.5 * rho * l * (is.trace() * Matrix3d::Identity() - is);
      for (int n = 0; n < 2; ++n) {
        const Index node = b.nodes[static_cast<std::size_t>(n)];
        c[0] = mesh.node(node);
        r[0].setZero();
        for (Index k = 0; k < out.num_modes; ++k) {
          c[static_cast<std::size_t>(k + 1)] = qe.col(k).segment<3>(6 * n);
          r[static_cast<std::size_t>(k + 1)] = qe.col(k).segment<3>(6 * n + 3);
        }
        detail::add_lumped(out, 0.5 * rho * s.area * l, detail::second_moment_of_inertia(jl), c, r);
      }
      continue;
    }
    const Matrix3d i_s =
        options.beam_rotary_inertia
            ? geo.section_tensor(s)
            : Matrix3d(0.5 * s.polar_moment() * (Matrix3d::Identity() - 2.0 * ex * ex.transpose()));
    fe::Matrix3x12d nu, nr;
    for (int g = 0; g < fe::GaussLine4::n; ++g) {
      const double xi = fe::GaussLine4::xi[static_cast<std::size_t>(g)];
      const double w = fe::GaussLine4::w[static_cast<std::size_t>(g)] * l * rho;
      geo.interpolation(xi, nu, nr);
      c[0] = geo.point(xi);
      r[0].setZero();
      for (Index k = 0; k < out.num_modes; ++k) {
        c[static_cast<std::size_t>(k + 1)] = nu * qe.col(k);
        r[static_cast<std::size_t>(k + 1)] = nr * qe.col(k);
      }
      detail::add_lumped(out, w * s.area, w * i_s, c, r);
    }
  }

  // Point masses.
  for (const auto& p : mesh.point_masses()) {
    c[0] = mesh.node(p.node);
    r[0].setZero();
    const bool rot = dofs.has_rotations(p.node);
    for (Index k = 0; k < out.num_modes; ++k) {
      for (int cc = 0; cc < 3; ++cc) {
        c[static_cast<std::size_t>(k + 1)](cc) = modes(dofs.dof(p.node, cc), k);
        r[static_cast<std::size_t>(k + 1)](cc) = rot ? modes(dofs.dof(p.node, 3 + cc), k) : 0.0;
      }
    }
    detail::add_lumped(out, p.mass,
                       rot ? detail::second_moment_of_inertia(p.inertia) : Matrix3d::Zero(), c, r);
  }

  // Matrix elements: nodal-based like the bricks, Lambda_ab += X_a m X_b^T with the scalar mass
  // m of the element (its mass is m I).
  for (std::size_t e = 0; e < mesh.matrix_elements().size(); ++e) {
    const fe::MatrixElement& me = mesh.matrix_elements()[e];
    auto m = detail::matrix_element_scalar_mass(me, e);
    if (!m) return m.error();
    const auto n = static_cast<Index>(me.nodes.size());
    std::vector<Eigen::Matrix3Xd> field(static_cast<std::size_t>(nf), Eigen::Matrix3Xd(3, n)),
        weighted(static_cast<std::size_t>(nf));
    for (Index a = 0; a < n; ++a) {
      const Index node = me.nodes[static_cast<std::size_t>(a)];
      field[0].col(a) = mesh.node(node);
      for (Index k = 0; k < out.num_modes; ++k)
        for (int cc = 0; cc < 3; ++cc)
          field[static_cast<std::size_t>(k + 1)](cc, a) = modes(dofs.dof(node, cc), k);
    }
    const VectorXd row_sums = *m * VectorXd::Ones(n);
    detail::add_nodal_moments(out, field, weighted, *m, row_sums);
  }
  return out;
}
#else
    ;
#endif

}  // namespace flexstress::reduction

// This header's precompute entry points (core/precompute.hpp).
#define FLEXSTRESS_PRECOMPUTE_REDUCTION_INERTIA_INTEGRALS(X)               \
  X(12, Result<reduction::InertiaIntegrals>, reduction::inertia_integrals, \
    (const fe::Mesh&, const fe::DofMap&, const MatrixXd&, const fe::MassOptions&))
namespace flexstress {
FLEXSTRESS_PRECOMPUTE_EXTERN(FLEXSTRESS_PRECOMPUTE_REDUCTION_INERTIA_INTEGRALS)
}  // namespace flexstress
