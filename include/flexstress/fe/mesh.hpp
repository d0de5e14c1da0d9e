// A finite-element mesh built in code: nodes, materials, sections and elements (3D beams,
// 8-node bricks, point masses, rigid massless links, averaging links, and matrix elements that
// carry matrices assembled elsewhere).
//
// Building a mesh never fails: add_* only records what it is given. `validate()` (called by
// every algorithm that consumes a mesh) checks everything at once and names the offending node,
// element, material or section. Ids are dense indices in order of creation.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products

#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/fe/averaging_link.hpp"
#include "flexstress/fe/beam_section.hpp"
#include "flexstress/fe/material.hpp"

namespace flexstress::fe {

/// Beam theory of a 3D beam element.
enum class BeamTheory : unsigned char {
  euler_bernoulli,  ///< No shear deformation.
  timoshenko,       ///< Shear deformation through the section's shear areas (shear correction).
};

/// Formulation of an 8-node brick.
enum class Hex8Formulation : unsigned char {
  full_integration,    ///< Standard trilinear hex, 2x2x2 Gauss. Locks in bending.
  incompatible_modes,  ///< Wilson-Taylor incompatible modes with the Taylor-Beresford-Wilson
                       ///< modification: bends well with one element through the thickness and
                       ///< passes the patch test on distorted meshes.
};

/// One entry of a matrix given as data: row and column are local DOFs,
/// 3 * (position in the element's node list) + component (0, 1, 2 = x, y, z).
struct MatrixEntry {
  Index row = 0, col = 0;
  double value = 0.0;
};

/// Stiffness and mass given as matrices over the translations of a set of nodes instead of
/// integrated from a material: a model assembled by another FE program (matrix_import.hpp:
/// Abaqus *MATRIX GENERATE, Nastran DMIG). Both triangles of each symmetric matrix are listed.
/// The mass is used as it is (MassOptions do not apply); the inertia integrals need it in the
/// solid-element form m_ab I (translations coupled only to the same component, alike in x, y, z).
struct MatrixElement {
  std::vector<Index> nodes;
  std::vector<MatrixEntry> stiffness, mass;
};

/// Two-node 3D beam. Local x runs from nodes[0] to nodes[1]; local y is the component of
/// `orientation` normal to x; local z = x cross y. A zero orientation means global y, or global
/// z for a beam within about 8 degrees of the y axis (see beam_local_axes in beam3d.hpp).
struct BeamElement {
  std::array<Index, 2> nodes{};
  Index material = 0;
  Index section = 0;
  Vector3d orientation = Vector3d::Zero();
  BeamTheory theory = BeamTheory::euler_bernoulli;
};

/// Eight-node brick; node order as in Hughes (The Finite Element Method, fig. 3.5.1): nodes 0-3
/// counter-clockwise on the face zeta = -1, nodes 4-7 above them on zeta = +1.
struct Hex8Element {
  std::array<Index, 8> nodes{};
  Index material = 0;
  Hex8Formulation formulation = Hex8Formulation::incompatible_modes;
};

/// A concentrated mass at a node, with a rotational inertia tensor about the node (global axes).
struct PointMass {
  Index node = 0;
  double mass = 0.0;
  Matrix3d inertia = Matrix3d::Zero();
};

/// Rigid massless link (RBE2): every slave node follows the master rigidly,
/// u_s = u_m + theta_m x (x_s - x_m), and slave rotations (if the slave has them) equal the
/// master's. Eliminated exactly by a transformation, never by a penalty.
struct RigidLink {
  Index master = 0;
  std::vector<Index> slaves;
};

/// Names of the six nodal DOF components, for messages.
inline const char* dof_component_name(int component) {
  static const char* names[6] = {"ux", "uy", "uz", "rx", "ry", "rz"};
  return component >= 0 && component < 6 ? names[component] : "?";
}

class Mesh {
 public:
  Index add_node(const Vector3d& x) {
    nodes_.push_back(x);
    return static_cast<Index>(nodes_.size()) - 1;
  }
  Index add_material(const Material& m) {
    materials_.push_back(m);
    return static_cast<Index>(materials_.size()) - 1;
  }
  Index add_section(const BeamSection& s) {
    sections_.push_back(s);
    return static_cast<Index>(sections_.size()) - 1;
  }
  Index add_beam(Index n0, Index n1, Index material, Index section,
                 const Vector3d& orientation = Vector3d::Zero(),
                 BeamTheory theory = BeamTheory::euler_bernoulli) {
    beams_.push_back(BeamElement{{n0, n1}, material, section, orientation, theory});
    return static_cast<Index>(beams_.size()) - 1;
  }
  Index add_hex8(const std::array<Index, 8>& nodes, Index material,
                 Hex8Formulation formulation = Hex8Formulation::incompatible_modes) {
    hexes_.push_back(Hex8Element{nodes, material, formulation});
    return static_cast<Index>(hexes_.size()) - 1;
  }
  Index add_point_mass(Index node, double mass, const Matrix3d& inertia = Matrix3d::Zero()) {
    point_masses_.push_back(PointMass{node, mass, inertia});
    return static_cast<Index>(point_masses_.size()) - 1;
  }
  Index add_rigid_link(Index master, std::vector<Index> slaves) {
    rigid_links_.push_back(RigidLink{master, std::move(slaves)});
    return static_cast<Index>(rigid_links_.size()) - 1;
  }
  /// An averaging link (RBE3): `reference` follows the weighted least-squares rigid fit of the
  /// face nodes (weights empty: all 1). See averaging_link.hpp.
  Index add_averaging_link(Index reference, std::vector<Index> face,
                           std::vector<double> weights = {}) {
    averaging_links_.push_back(AveragingLink{reference, std::move(face), std::move(weights)});
    return static_cast<Index>(averaging_links_.size()) - 1;
  }
  /// A matrix element (see MatrixElement) over `nodes`.
  Index add_matrix_element(std::vector<Index> nodes, std::vector<MatrixEntry> stiffness,
                           std::vector<MatrixEntry> mass) {
    matrix_elements_.push_back(
        MatrixElement{std::move(nodes), std::move(stiffness), std::move(mass)});
    return static_cast<Index>(matrix_elements_.size()) - 1;
  }
  /// Gives a node rotational DOFs even if no element needs them (e.g. an interface node).
  void require_rotations(Index node) { rotation_nodes_.push_back(node); }

  Index num_nodes() const { return static_cast<Index>(nodes_.size()); }
  const Vector3d& node(Index i) const { return nodes_[static_cast<std::size_t>(i)]; }
  const std::vector<Vector3d>& nodes() const { return nodes_; }
  const std::vector<Material>& materials() const { return materials_; }
  const std::vector<BeamSection>& sections() const { return sections_; }
  const std::vector<BeamElement>& beams() const { return beams_; }
  const std::vector<Hex8Element>& hexes() const { return hexes_; }
  const std::vector<PointMass>& point_masses() const { return point_masses_; }
  const std::vector<RigidLink>& rigid_links() const { return rigid_links_; }
  const std::vector<AveragingLink>& averaging_links() const { return averaging_links_; }
  const std::vector<Index>& rotation_nodes() const { return rotation_nodes_; }
  const std::vector<MatrixElement>& matrix_elements() const { return matrix_elements_; }
  const Material& material(Index i) const { return materials_[static_cast<std::size_t>(i)]; }
  const BeamSection& section(Index i) const { return sections_[static_cast<std::size_t>(i)]; }

  /// Sets the formulation of every brick (an accuracy knob of the sub-model).
  void set_hex8_formulation(Hex8Formulation f) {
    for (auto& h : hexes_) h.formulation = f;
  }

  /// Checks ids, finiteness and element geometry that does not need element integration
  /// (zero-length beams, beam orientation parallel to the axis, duplicate brick nodes). Brick
  /// Jacobians are checked where they are integrated.
  Status validate() const {
    const Index nn = num_nodes();
    for (Index i = 0; i < nn; ++i)
      if (!node(i).allFinite())
        return make_error(ErrorCode::invalid_argument, "node ", i, " has a non-finite coordinate");
    for (std::size_t i = 0; i < materials_.size(); ++i)
      if (Status s = fe::validate(materials_[i], "material " + std::to_string(i)); !s) return s;
    for (std::size_t i = 0; i < sections_.size(); ++i)
      if (Status s = fe::validate(sections_[i], "section " + std::to_string(i)); !s) return s;
    auto bad_node = [&](Index n) { return n < 0 || n >= nn; };
    for (std::size_t e = 0; e < beams_.size(); ++e) {
      const BeamElement& b = beams_[e];
      for (Index n : b.nodes)
        if (bad_node(n))
          return make_error(ErrorCode::invalid_mesh, "beam ", e, " refers to node ", n,
                            ", which does not exist (the mesh has ", nn, " nodes)");
      if (b.material < 0 || b.material >= static_cast<Index>(materials_.size()))
        return make_error(ErrorCode::invalid_mesh, "beam ", e, " refers to material ", b.material,
                          ", which does not exist");
      if (b.section < 0 || b.section >= static_cast<Index>(sections_.size()))
        return make_error(ErrorCode::invalid_mesh, "beam ", e, " refers to section ", b.section,
                          ", which does not exist");
      const Vector3d d = node(b.nodes[1]) - node(b.nodes[0]);
      const double length = d.norm();
      if (!(length > 1e-12 * (1.0 + node(b.nodes[0]).norm())))
        return make_error(ErrorCode::degenerate_element, "beam ", e, " has zero length (nodes ",
                          b.nodes[0], " and ", b.nodes[1], " coincide)");
      if (!b.orientation.allFinite())
        return make_error(ErrorCode::invalid_argument, "beam ", e,
                          " has a non-finite orientation vector");
      if (b.orientation.squaredNorm() > 0.0 &&
          d.normalized().cross(b.orientation.normalized()).norm() < 1e-9)
        return make_error(ErrorCode::invalid_argument, "beam ", e,
                          ": orientation vector is parallel to the beam axis");
      if (b.theory == BeamTheory::timoshenko) {
        const BeamSection& s = section(b.section);
        if (!(s.shear_area_y > 0.0) || !(s.shear_area_z > 0.0))
          return make_error(ErrorCode::invalid_argument, "beam ", e, " is Timoshenko but section ",
                            b.section, " has no shear areas");
      }
    }
    for (std::size_t e = 0; e < hexes_.size(); ++e) {
      const Hex8Element& h = hexes_[e];
      for (Index n : h.nodes)
        if (bad_node(n))
          return make_error(ErrorCode::invalid_mesh, "hex8 element ", e, " refers to node ", n,
                            ", which does not exist (the mesh has ", nn, " nodes)");
      for (int a = 0; a < 8; ++a)
        for (int b = a + 1; b < 8; ++b)
          if (h.nodes[static_cast<std::size_t>(a)] == h.nodes[static_cast<std::size_t>(b)])
            return make_error(ErrorCode::degenerate_element, "hex8 element ", e, " uses node ",
                              h.nodes[static_cast<std::size_t>(a)], " twice");
      if (h.material < 0 || h.material >= static_cast<Index>(materials_.size()))
        return make_error(ErrorCode::invalid_mesh, "hex8 element ", e, " refers to material ",
                          h.material, ", which does not exist");
    }
    for (std::size_t i = 0; i < point_masses_.size(); ++i) {
      const PointMass& p = point_masses_[i];
      if (bad_node(p.node))
        return make_error(ErrorCode::invalid_mesh, "point mass ", i, " refers to node ", p.node,
                          ", which does not exist");
      if (!std::isfinite(p.mass) || p.mass < 0.0 || !p.inertia.allFinite())
        return make_error(ErrorCode::invalid_argument, "point mass ", i,
                          " has a negative or non-finite mass or inertia");
    }
    for (std::size_t i = 0; i < rigid_links_.size(); ++i) {
      const RigidLink& l = rigid_links_[i];
      if (bad_node(l.master))
        return make_error(ErrorCode::invalid_mesh, "rigid link ", i, " has master node ", l.master,
                          ", which does not exist");
      if (l.slaves.empty())
        return make_error(ErrorCode::invalid_mesh, "rigid link ", i, " has no slave nodes");
      for (Index s : l.slaves) {
        if (bad_node(s))
          return make_error(ErrorCode::invalid_mesh, "rigid link ", i, " has slave node ", s,
                            ", which does not exist");
        if (s == l.master)
          return make_error(ErrorCode::invalid_mesh, "rigid link ", i, ": node ", s,
                            " is both master and slave");
      }
    }
    for (std::size_t i = 0; i < averaging_links_.size(); ++i) {
      const AveragingLink& l = averaging_links_[i];
      if (bad_node(l.reference))
        return make_error(ErrorCode::invalid_mesh, "averaging link ", i, " has reference node ",
                          l.reference, ", which does not exist");
      std::vector<Index> sorted = l.face;
      std::sort(sorted.begin(), sorted.end());
      for (std::size_t k = 0; k < sorted.size(); ++k) {
        if (bad_node(sorted[k]))
          return make_error(ErrorCode::invalid_mesh, "averaging link ", i, " has face node ",
                            sorted[k], ", which does not exist");
        if (sorted[k] == l.reference)
          return make_error(ErrorCode::invalid_mesh, "averaging link ", i, ": node ", sorted[k],
                            " is both its reference and a face node");
        if (k > 0 && sorted[k] == sorted[k - 1])
          return make_error(ErrorCode::invalid_mesh, "averaging link ", i, " lists face node ",
                            sorted[k], " twice");
      }
    }
    for (std::size_t i = 0; i < matrix_elements_.size(); ++i) {
      const MatrixElement& m = matrix_elements_[i];
      std::vector<Index> sorted = m.nodes;
      std::sort(sorted.begin(), sorted.end());
      for (std::size_t k = 0; k < sorted.size(); ++k) {
        if (bad_node(sorted[k]))
          return make_error(ErrorCode::invalid_mesh, "matrix element ", i, " refers to node ",
                            sorted[k], ", which does not exist (the mesh has ", nn, " nodes)");
        if (k > 0 && sorted[k] == sorted[k - 1])
          return make_error(ErrorCode::invalid_mesh, "matrix element ", i, " lists node ",
                            sorted[k], " twice");
      }
      const Index size = 3 * static_cast<Index>(m.nodes.size());
      for (const auto* entries : {&m.stiffness, &m.mass})
        for (const MatrixEntry& e : *entries) {
          const char* which = entries == &m.stiffness ? "stiffness" : "mass";
          if (e.row < 0 || e.row >= size || e.col < 0 || e.col >= size)
            return make_error(ErrorCode::invalid_mesh, "matrix element ", i, ": ", which,
                              " entry (", e.row, ", ", e.col, ") is outside its ", size, " DOFs");
          if (!std::isfinite(e.value))
            return make_error(ErrorCode::invalid_argument, "matrix element ", i, ": ", which,
                              " entry (", e.row, ", ", e.col, ") is not finite");
        }
    }
    for (Index n : rotation_nodes_)
      if (bad_node(n))
        return make_error(ErrorCode::invalid_mesh, "require_rotations: node ", n,
                          " does not exist");
    return Status::success();
  }

 private:
  std::vector<Vector3d> nodes_;
  std::vector<Material> materials_;
  std::vector<BeamSection> sections_;
  std::vector<BeamElement> beams_;
  std::vector<Hex8Element> hexes_;
  std::vector<PointMass> point_masses_;
  std::vector<RigidLink> rigid_links_;
  std::vector<AveragingLink> averaging_links_;
  std::vector<Index> rotation_nodes_;
  std::vector<MatrixElement> matrix_elements_;
};

}  // namespace flexstress::fe
