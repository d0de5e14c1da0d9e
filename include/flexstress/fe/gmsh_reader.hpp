// Import of Gmsh meshes (MSH file format 4.1, ASCII): 8-node hexahedra become hex8 bricks of a
// Mesh, physical groups become named node sets (faces to tie, load or support, read-out lines).
//
// Format: Gmsh reference manual, "MSH file format", version 4.1 ($MeshFormat, $PhysicalNames,
// $Entities, $Nodes, $Elements; other sections are skipped). Gmsh's hexahedron node order
// (bottom face counter-clockwise seen from above, then the top face) is the order of
// Hex8Element, so connectivity is taken as written. Only the nodes of hexahedra enter the mesh:
// construction points and the nodes of lower-dimensional elements would add nodes without
// stiffness. Points, curves and surfaces only say which nodes belong to which physical group.
//
// The import is all or nothing: the mesh is changed only when the whole file is valid. Every
// error names the file and the line, what was expected and what was found.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/fe/gmsh_msh41.hpp"
#include "flexstress/fe/hex8.hpp"
#include "flexstress/fe/mesh.hpp"

namespace flexstress::fe {

/// A physical group of a Gmsh file, as nodes (and bricks) of the mesh it was imported into.
struct GmshGroup {
  int dimension = 0;         ///< 0 point, 1 curve, 2 surface, 3 volume
  int tag = 0;               ///< its physical tag
  std::string name;          ///< from $PhysicalNames; empty if the file gives none
  std::vector<Index> nodes;  ///< mesh node indices, ascending, each once
  std::vector<Index> hexes;  ///< volume groups: the mesh's hex8 element indices, ascending
  /// Curve groups whose line elements form one chain: its nodes in order along the curve (a
  /// closed chain ends with its first node again). Empty for branched or disconnected curves.
  std::vector<Index> path;
};

/// What read_gmsh added to a mesh.
struct GmshImport {
  Index first_node = 0;                 ///< mesh index of the first imported node
  Index first_hex = 0;                  ///< index of the first imported brick in mesh.hexes()
  std::vector<std::int64_t> node_tags;  ///< Gmsh tag of mesh node first_node + i
  std::vector<std::int64_t> hex_tags;   ///< Gmsh tag of brick first_hex + i
  std::vector<GmshGroup> groups;        ///< physical groups, by dimension, then tag

  /// The group with this name, or nullptr.
  const GmshGroup* find(std::string_view name) const {
    for (const GmshGroup& g : groups)
      if (g.name == name) return &g;
    return nullptr;
  }

  /// The nodes of the group with this name; an error lists the names there are.
  Result<std::vector<Index>> nodes_of(std::string_view name) const {
    if (const GmshGroup* g = find(name)) return g->nodes;
    std::string names;
    for (const GmshGroup& g : groups)
      if (!g.name.empty()) names += (names.empty() ? "'" : ", '") + g.name + "'";
    return make_error(ErrorCode::invalid_argument, "Gmsh import: no physical group named '",
                      std::string(name), "' (the file has ",
                      names.empty() ? std::string("no named groups") : names, ")");
  }
};

namespace gmsh_detail {

/// The nodes of a curve group in order along it, if its line elements form one chain.
inline std::vector<Index> chain(const std::vector<std::pair<Index, Index>>& edges) {
  std::map<Index, std::vector<Index>> next;
  std::map<Index, int> degree;
  for (const auto& [a, b] : edges) {
    if (a == b) return {};
    next[a].push_back(b);
    next[b].push_back(a);
    ++degree[a];
    ++degree[b];
  }
  Index start = edges.empty() ? -1 : edges.front().first;
  int ends = 0;
  for (const auto& [node, d] : degree) {
    if (d > 2) return {};
    if (d == 1 && ends++ == 0) start = node;
  }
  if (ends != 0 && ends != 2) return {};
  if (ends == 2)  // follow Gmsh's orientation: begin where an element begins
    for (const auto& [a, b] : edges)
      if (degree[a] == 1) start = a;
  std::vector<Index> path{start};
  Index previous = -1, current = start;
  for (std::size_t k = 0; k < edges.size(); ++k) {
    const std::vector<Index>& n = next[current];
    const Index step = (n[0] != previous || n.size() == 1) ? n[0] : n[1];
    previous = current;
    current = step;
    path.push_back(current);
  }
  // One connected chain visits every edge once: each node once (a closed one returns to start).
  std::set<Index> seen(path.begin(), path.end());
  if (seen.size() != degree.size()) return {};
  return path;
}

}  // namespace gmsh_detail

/// Reads a Gmsh mesh (MSH 4.1, ASCII) from `text` into `mesh`: its hexahedra become hex8 bricks
/// of `material`, its physical groups node sets. `source` names the text in errors (a file
/// name). Nothing is added to the mesh unless the whole file is valid.
inline Result<GmshImport> read_gmsh(std::string_view text, Mesh& mesh, Index material,
                                    const std::string& source = "Gmsh input") {
  using gmsh_detail::MemberRecord;
  if (material < 0 || material >= static_cast<Index>(mesh.materials().size()))
    return make_error(ErrorCode::invalid_argument, "Gmsh import of '", source, "': material ",
                      material, " does not exist (the mesh has ", mesh.materials().size(),
                      " materials; add it first)");
  gmsh_detail::Parser parser(text, source);
  if (Status s = parser.parse(); !s) return s.error();
  if (parser.hexes_.empty())
    return make_error(ErrorCode::bad_file_format, source,
                      ": no 8-node hexahedra (element type 5); flexstress imports hexahedral "
                      "volume meshes");

  // Mesh nodes: the hexahedra's nodes, in ascending tag order.
  std::map<std::int64_t, Index> node_index;
  for (const gmsh_detail::HexRecord& h : parser.hexes_)
    for (std::int64_t tag : h.nodes) {
      if (parser.nodes_.count(tag) == 0)
        return parser.error_at(h.line, "element ", h.tag, " refers to node ", tag,
                               ", which $Nodes does not define");
      node_index.emplace(tag, 0);
    }
  GmshImport out;
  out.first_node = mesh.num_nodes();
  out.first_hex = static_cast<Index>(mesh.hexes().size());
  for (auto& [tag, index] : node_index) {
    index = out.first_node + static_cast<Index>(out.node_tags.size());
    out.node_tags.push_back(tag);
  }
  std::vector<std::array<Index, 8>> connectivity;
  for (const gmsh_detail::HexRecord& h : parser.hexes_) {
    std::array<Index, 8> c{};
    Hex8Coordinates x;
    for (std::size_t a = 0; a < 8; ++a) {
      c[a] = node_index.at(h.nodes[a]);
      x.col(static_cast<Index>(a)) = parser.nodes_.at(h.nodes[a]).x;
    }
    for (std::size_t a = 0; a < 8; ++a)
      for (std::size_t b = a + 1; b < 8; ++b)
        if (c[a] == c[b])
          return parser.error_at(h.line, "hexahedron ", h.tag, " uses node ", h.nodes[a], " twice");
    // The Jacobian at the centre: negative for a mirrored node order, zero for a flat brick.
    const Matrix3d jacobian = hex8::shape_derivatives(Vector3d::Zero()) * x.transpose();
    const double det = jacobian.determinant();
    const double scale = (x.rowwise().maxCoeff() - x.rowwise().minCoeff()).prod();
    if (!(det > 1e-12 * scale / 8.0))
      return parser.error_at(h.line, "hexahedron ", h.tag, " is inverted or flat (det J = ", det,
                             " at its centre); Gmsh's order is the bottom face counter-clockwise "
                             "seen from the top face, then the top face");
    connectivity.push_back(c);
    out.hex_tags.push_back(h.tag);
  }

  // Physical groups: the nodes (and for volumes the bricks) of their entities' elements.
  std::map<std::pair<int, int>, GmshGroup> groups;
  std::map<std::pair<int, int>, std::vector<std::pair<Index, Index>>> edges;
  Index hex = out.first_hex;
  for (const MemberRecord& e : parser.members_) {
    const bool is_hex = e.dimension == 3;
    const auto tags = parser.entity_groups_.find({e.dimension, e.entity});
    if (tags != parser.entity_groups_.end())
      for (int tag : tags->second) {
        GmshGroup& g = groups[{e.dimension, tag}];
        for (std::int64_t node : e.nodes) {
          const auto it = node_index.find(node);
          if (it == node_index.end())
            return parser.error_at(e.line, "element ", e.tag, " of physical group ", tag,
                                   " (dimension ", e.dimension, ") has node ", node,
                                   ", which is not a node of any hexahedron (only the volume "
                                   "mesh is imported)");
          g.nodes.push_back(it->second);
        }
        if (is_hex) g.hexes.push_back(hex);
        if (e.dimension == 1)
          edges[{1, tag}].emplace_back(node_index.at(e.nodes[0]), node_index.at(e.nodes[1]));
      }
    if (is_hex) ++hex;
  }
  for (auto& [key, g] : groups) {
    g.dimension = key.first;
    g.tag = key.second;
    const auto name = parser.physical_names_.find(key);
    if (name != parser.physical_names_.end()) g.name = name->second;
    std::sort(g.nodes.begin(), g.nodes.end());
    g.nodes.erase(std::unique(g.nodes.begin(), g.nodes.end()), g.nodes.end());
    if (g.dimension == 1) g.path = gmsh_detail::chain(edges[key]);
    out.groups.push_back(std::move(g));
  }

  for (const auto& [tag, index] : node_index) mesh.add_node(parser.nodes_.at(tag).x);
  for (const std::array<Index, 8>& c : connectivity) mesh.add_hex8(c, material);
  return out;
}

/// Reads a Gmsh mesh file (MSH 4.1, ASCII) into `mesh`; see read_gmsh.
inline Result<GmshImport> read_gmsh_file(const std::string& path, Mesh& mesh, Index material) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return make_error(ErrorCode::io_error, "cannot open Gmsh file '", path, "'");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) return make_error(ErrorCode::io_error, "cannot read Gmsh file '", path, "'");
  return read_gmsh(text, mesh, material, path);
}

}  // namespace flexstress::fe
