// Stiffness and mass matrices from another FE program, with node coordinates, as a matrix
// element of a Mesh: a body meshed and assembled elsewhere (Abaqus *MATRIX GENERATE,
// abaqus_matrix_reader.hpp; Nastran DMIG, nastran_dmig_reader.hpp) that the reductions,
// static and eigen solvers and inertia integrals of this library then take like any other mesh.
//
// Nodes are known by the other program's labels; DOFs are numbered as both programs do, 1, 2, 3
// for the translations x, y, z. Only translations are taken: solid models (bricks, tetrahedra),
// whose mass has the form m_ab I that the inertia integrals need; a rotational DOF is refused.
// A symmetric matrix may be given as one triangle or square; an entry and its mirror must agree.
#pragma once

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/fe/mesh.hpp"

namespace flexstress::fe {

/// One matrix entry as another program writes it, with where it came from (for messages).
struct LabeledEntry {
  long long row_node = 0;
  int row_dof = 0;  ///< 1..6 as written; 1..3 accepted
  long long col_node = 0;
  int col_dof = 0;
  double value = 0.0;
  std::string where;  ///< "file:line"
};

/// What the readers collect: coordinates by node label and the two matrices' entries.
struct LabeledModel {
  std::map<long long, Vector3d> coordinates;
  std::vector<LabeledEntry> stiffness, mass;
};

/// What add_labeled_model added to a mesh.
struct MatrixImport {
  Index element = -1;                  ///< index in mesh.matrix_elements()
  Index first_node = 0;                ///< mesh index of the first imported node
  std::vector<long long> node_labels;  ///< label of mesh node first_node + i (ascending)

  /// Mesh node of a label, or -1.
  Index node(long long label) const {
    const auto it = std::lower_bound(node_labels.begin(), node_labels.end(), label);
    if (it == node_labels.end() || *it != label) return -1;
    return first_node + static_cast<Index>(it - node_labels.begin());
  }
};

namespace detail {

// Local entries of one matrix: both triangles, each pair given once or mirrored equally.
inline Result<std::vector<MatrixEntry>> local_entries(const std::vector<LabeledEntry>& entries,
                                                      const std::vector<long long>& labels,
                                                      const char* which) {
  std::map<std::pair<Index, Index>, std::pair<double, const LabeledEntry*>> seen;
  for (const LabeledEntry& e : entries) {
    for (int dof : {e.row_dof, e.col_dof})
      if (dof < 1 || dof > 3)
        return make_error(ErrorCode::invalid_argument, e.where, ": ", which, " entry at DOF ", dof,
                          ": only translations (DOFs 1, 2, 3) can be imported (a solid "
                          "model; rotations need the elements' own mass distribution)");
    if (!std::isfinite(e.value))
      return make_error(ErrorCode::invalid_argument, e.where, ": ", which, " entry is not finite");
    const auto local = [&](long long label, int dof) {
      const auto it = std::lower_bound(labels.begin(), labels.end(), label);
      return 3 * static_cast<Index>(it - labels.begin()) + (dof - 1);
    };
    const Index r = local(e.row_node, e.row_dof), c = local(e.col_node, e.col_dof);
    const auto key = std::make_pair(std::min(r, c), std::max(r, c));
    const auto [it, inserted] = seen.emplace(key, std::make_pair(e.value, &e));
    if (!inserted) {
      const LabeledEntry& first = *it->second.second;
      const bool mirrored = first.row_node == e.col_node && first.row_dof == e.col_dof &&
                            first.col_node == e.row_node && first.col_dof == e.row_dof && r != c;
      if (!mirrored)
        return make_error(ErrorCode::invalid_argument, e.where, ": ", which, " entry (node ",
                          e.row_node, " DOF ", e.row_dof, ", node ", e.col_node, " DOF ", e.col_dof,
                          ") is given twice (first at ", first.where, ")");
      if (first.value != e.value)
        return make_error(ErrorCode::invalid_argument, e.where, ": ", which,
                          " is not symmetric: entry (node ", e.row_node, " DOF ", e.row_dof,
                          ", node ", e.col_node, " DOF ", e.col_dof, ") = ", e.value,
                          " but its mirror at ", first.where, " = ", first.value);
    }
  }
  std::vector<MatrixEntry> out;
  out.reserve(2 * seen.size());
  for (const auto& [key, value] : seen) {
    out.push_back(MatrixEntry{key.first, key.second, value.first});
    if (key.first != key.second) out.push_back(MatrixEntry{key.second, key.first, value.first});
  }
  return out;
}

}  // namespace detail

/// Adds the model's nodes (those its matrices use, in ascending label order) and one matrix
/// element to `mesh`. All or nothing: on error the mesh is unchanged. Errors name the file and
/// line of the entry: a node without coordinates, a rotational DOF, an entry given twice, a
/// mirror that differs, no entries at all.
inline Result<MatrixImport> add_labeled_model(Mesh& mesh, const LabeledModel& model) {
  if (model.stiffness.empty() || model.mass.empty())
    return make_error(ErrorCode::invalid_argument, "matrix import: the ",
                      model.stiffness.empty() ? "stiffness" : "mass",
                      " matrix has no entries (read both before adding the model)");
  std::vector<long long> labels;
  for (const auto* entries : {&model.stiffness, &model.mass})
    for (const LabeledEntry& e : *entries)
      for (long long label : {e.row_node, e.col_node}) {
        if (model.coordinates.count(label) == 0)
          return make_error(ErrorCode::invalid_argument, e.where, ": node ", label,
                            " has no coordinates (no *NODE line or GRID card gives them)");
        labels.push_back(label);
      }
  std::sort(labels.begin(), labels.end());
  labels.erase(std::unique(labels.begin(), labels.end()), labels.end());
  auto k = detail::local_entries(model.stiffness, labels, "stiffness");
  if (!k) return k.error();
  auto m = detail::local_entries(model.mass, labels, "mass");
  if (!m) return m.error();
  MatrixImport out;
  out.first_node = mesh.num_nodes();
  out.node_labels = labels;
  std::vector<Index> nodes;
  for (long long label : labels) nodes.push_back(mesh.add_node(model.coordinates.at(label)));
  out.element = mesh.add_matrix_element(std::move(nodes), std::move(*k), std::move(*m));
  return out;
}

}  // namespace flexstress::fe
