// The MSH 4.1 ASCII format, read into records: tokens with their line numbers, and the sections
// flexstress uses ($MeshFormat, $PhysicalNames, $Entities, $Nodes, $Elements; others are
// skipped). Format: Gmsh reference manual, "MSH file format", version 4.1. The records are
// turned into a Mesh by read_gmsh (gmsh_reader.hpp); the first error stops the parse and names
// the line.
#pragma once

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"

namespace flexstress::fe::gmsh_detail {

/// Gmsh element types (reference manual, "MSH file format": elm-type): nodes and dimension.
struct ElementType {
  int nodes = 0;
  int dimension = -1;
  const char* name = "";
};

inline ElementType element_type(int type) {
  switch (type) {
    case 1: return {2, 1, "2-node line"};
    case 2: return {3, 2, "3-node triangle"};
    case 3: return {4, 2, "4-node quadrangle"};
    case 4: return {4, 3, "4-node tetrahedron"};
    case 5: return {8, 3, "8-node hexahedron"};
    case 6: return {6, 3, "6-node prism"};
    case 7: return {5, 3, "5-node pyramid"};
    case 8: return {3, 1, "3-node line"};
    case 9: return {6, 2, "6-node triangle"};
    case 10: return {9, 2, "9-node quadrangle"};
    case 11: return {10, 3, "10-node tetrahedron"};
    case 12: return {27, 3, "27-node hexahedron"};
    case 13: return {18, 3, "18-node prism"};
    case 14: return {14, 3, "14-node pyramid"};
    case 15: return {1, 0, "point"};
    case 16: return {8, 2, "8-node quadrangle"};
    case 17: return {20, 3, "20-node hexahedron"};
    case 18: return {15, 3, "15-node prism"};
    case 19: return {13, 3, "13-node pyramid"};
    default: return {};
  }
}

/// Whitespace-separated tokens of a text, with the line each starts on.
class Cursor {
 public:
  explicit Cursor(std::string_view text) : text_(text) {}

  /// The next token (empty at the end of the text).
  std::string_view next() {
    skip_space();
    line_ = current_line_;
    const std::size_t begin = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_])) ++pos_;
    return text_.substr(begin, pos_ - begin);
  }

  /// A double-quoted string on the current line (names may hold spaces); false if none.
  bool quoted(std::string& out) {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\t')) ++pos_;
    line_ = current_line_;
    if (pos_ >= text_.size() || text_[pos_] != '"') return false;
    const std::size_t end = text_.find_first_of("\"\n", pos_ + 1);
    if (end == std::string_view::npos || text_[end] != '"') return false;
    out.assign(text_.substr(pos_ + 1, end - pos_ - 1));
    pos_ = end + 1;
    return true;
  }

  int line() const { return line_; }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
  void skip_space() {
    while (pos_ < text_.size() && is_space(text_[pos_])) {
      if (text_[pos_] == '\n') ++current_line_;
      ++pos_;
    }
  }

  std::string_view text_;
  std::size_t pos_ = 0;
  int current_line_ = 1;
  int line_ = 1;
};

struct HexRecord {
  std::int64_t tag = 0;
  std::array<std::int64_t, 8> nodes{};
  int entity = 0;
  int line = 0;
};

/// Nodes of a lower-dimensional element or a hexahedron, for group membership.
struct MemberRecord {
  int dimension = 0;
  int entity = 0;
  std::int64_t tag = 0;
  std::vector<std::int64_t> nodes;  ///< curves: the end nodes first (Gmsh's order)
  int line = 0;
};

struct NodeRecord {
  Vector3d x = Vector3d::Zero();
  int line = 0;
};

/// Parses the sections flexstress reads; the first error stops it.
class Parser {
 public:
  Parser(std::string_view text, std::string source) : cursor_(text), source_(std::move(source)) {}

  Status parse() {
    for (std::string_view t = cursor_.next(); !t.empty(); t = cursor_.next()) {
      if (t.front() != '$') return fail("expected a section such as $Nodes, found '", t, "'");
      const std::string name(t.substr(1));
      if (!format_seen_ && name != "MeshFormat")
        return fail("the file must begin with $MeshFormat (found '", t, "')");
      bool ok = true;
      if (name == "MeshFormat")
        ok = mesh_format();
      else if (name == "PhysicalNames")
        ok = physical_names();
      else if (name == "Entities")
        ok = entities();
      else if (name == "Nodes")
        ok = nodes();
      else if (name == "Elements")
        ok = elements();
      else
        ok = skip_section(name);
      if (!ok) return *error_;
    }
    if (!format_seen_) return fail("empty file: no $MeshFormat");
    if (!nodes_seen_ || !elements_seen_)
      return fail("the file ends without ", nodes_seen_ ? "an $Elements" : "a $Nodes", " section");
    return Status::success();
  }

  template <class... Parts>
  Error error_at(int line, const Parts&... parts) const {
    return make_error(ErrorCode::bad_file_format, source_, ":", line, ": ", parts...);
  }

  std::map<std::pair<int, int>, std::string> physical_names_;
  std::map<std::pair<int, int>, std::vector<int>> entity_groups_;  ///< (dim, entity) -> tags
  std::unordered_map<std::int64_t, NodeRecord> nodes_;
  std::vector<HexRecord> hexes_;
  std::vector<MemberRecord> members_;

 private:
  template <class... Parts>
  Status fail(const Parts&... parts) {
    error_ = error_at(cursor_.line(), parts...);
    return *error_;
  }
  template <class... Parts>
  bool failed(const Parts&... parts) {
    error_ = error_at(cursor_.line(), parts...);
    return false;
  }

  // The next token as an integer or a finite floating-point number (locale-independent).
  template <class T>
  bool number(T& value, const char* what) {
    const std::string_view t = cursor_.next();
    if (t.empty()) return failed("the file ends where ", what, " was expected");
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
    const char* kind = std::is_integral_v<T> ? " (an integer)" : " (a number)";
    if (ec != std::errc() || end != t.data() + t.size())
      return failed("expected ", what, kind, ", found '", t, "'");
    if constexpr (std::is_floating_point_v<T>)
      if (!std::isfinite(value)) return failed(what, " is not finite ('", t, "')");
    return true;
  }
  template <class T>
  bool integer(T& value, const char* what) {
    return number(value, what);
  }
  bool real(double& value, const char* what) { return number(value, what); }
  bool count(std::int64_t& value, const char* what) {
    if (!integer(value, what)) return false;
    if (value < 0) return failed(what, " is negative (", value, ")");
    return true;
  }
  bool section_end(const std::string& name) {
    const std::string_view t = cursor_.next();
    if (t != "$End" + name)
      return failed("expected $End", name, ", found '", t.empty() ? "end of file" : t, "'");
    return true;
  }

  bool mesh_format() {
    const std::string_view version = cursor_.next();
    if (version != "4.1")
      return failed("MSH version '", version,
                    "' is not supported; flexstress reads version 4.1 (Gmsh: -format msh41 or "
                    "Mesh.MshFileVersion = 4.1)");
    int file_type = 0, data_size = 0;
    if (!integer(file_type, "the file type") || !integer(data_size, "the data size")) return false;
    if (file_type != 0)
      return failed("binary MSH files are not supported; write ASCII (Gmsh: Mesh.Binary = 0)");
    format_seen_ = true;
    return section_end("MeshFormat");
  }

  bool physical_names() {
    std::int64_t n = 0;
    if (!count(n, "the number of physical names")) return false;
    for (std::int64_t i = 0; i < n; ++i) {
      int dim = 0, tag = 0;
      std::string name;
      if (!integer(dim, "a physical group's dimension") || !integer(tag, "a physical tag"))
        return false;
      if (!cursor_.quoted(name)) return failed("expected the physical group's \"name\"");
      physical_names_[{dim, tag}] = name;
    }
    return section_end("PhysicalNames");
  }

  // Physical tags, then (except for points) the bounding entities, which are read past.
  bool entity_record(int dim) {
    int tag = 0;
    if (!integer(tag, "an entity tag")) return false;
    double box = 0.0;
    for (int i = 0; i < (dim == 0 ? 3 : 6); ++i)
      if (!real(box, dim == 0 ? "a point coordinate" : "a bounding box coordinate")) return false;
    std::int64_t n = 0;
    if (!count(n, "the number of physical tags")) return false;
    std::vector<int>& groups = entity_groups_[{dim, tag}];
    for (std::int64_t i = 0; i < n; ++i) {
      int group = 0;
      if (!integer(group, "a physical tag")) return false;
      groups.push_back(group);
    }
    if (dim == 0) return true;
    if (!count(n, "the number of bounding entities")) return false;
    for (std::int64_t i = 0; i < n; ++i)
      if (!integer(tag, "a bounding entity tag")) return false;
    return true;
  }

  bool entities() {
    std::int64_t n[4] = {};
    for (std::int64_t& c : n)
      if (!count(c, "an entity count")) return false;
    for (int dim = 0; dim < 4; ++dim)
      for (std::int64_t i = 0; i < n[dim]; ++i)
        if (!entity_record(dim)) return false;
    return section_end("Entities");
  }

  // The first line of $Nodes and $Elements: numEntityBlocks, numNodes (numElements), and the
  // smallest and largest tag (not needed: tags are mapped, not indexed).
  struct SectionHeader {
    std::int64_t blocks = 0, total = 0;
    int line = 0;
  };
  bool section_header(bool& seen, const char* section, const char* items, SectionHeader& h) {
    if (seen) return failed("a second $", section, " section");
    seen = true;
    std::int64_t tag = 0;
    if (!count(h.blocks, "the number of blocks")) return false;
    h.line = cursor_.line();
    return count(h.total, items) && integer(tag, "the smallest tag") &&
           integer(tag, "the largest tag");
  }
  bool check_total(const SectionHeader& h, std::int64_t read, const char* section,
                   const char* items) {
    if (read == h.total) return true;
    error_ = error_at(h.line, "$", section, " announces ", h.total, " ", items,
                      " but its blocks hold ", read);
    return false;
  }

  bool nodes() {
    SectionHeader header;
    if (!section_header(nodes_seen_, "Nodes", "the number of nodes", header)) return false;
    const std::int64_t blocks = header.blocks;
    std::int64_t read = 0;
    std::vector<std::pair<std::int64_t, int>> tags;
    for (std::int64_t b = 0; b < blocks; ++b) {
      int dim = 0, entity = 0, parametric = 0;
      std::int64_t n = 0;
      if (!integer(dim, "a node block's entity dimension") ||
          !integer(entity, "a node block's entity tag") ||
          !integer(parametric, "the parametric flag") || !count(n, "the block's node count"))
        return false;
      if (dim < 0 || dim > 3) return failed("entity dimension ", dim, " is not 0 to 3");
      if (parametric != 0 && parametric != 1)
        return failed("the parametric flag is ", parametric, " (0 or 1 expected)");
      tags.clear();
      for (std::int64_t i = 0; i < n; ++i) {
        std::int64_t tag = 0;
        if (!integer(tag, "a node tag")) return false;
        if (tag <= 0) return failed("node tag ", tag, " is not positive");
        tags.emplace_back(tag, cursor_.line());
      }
      const int parameters = parametric ? dim : 0;
      for (const auto& [tag, line] : tags) {
        NodeRecord node;
        for (int c = 0; c < 3; ++c)
          if (!real(node.x(c), "a node coordinate")) return false;
        double u = 0.0;
        for (int c = 0; c < parameters; ++c)
          if (!real(u, "a node's parametric coordinate")) return false;
        node.line = line;
        if (!nodes_.emplace(tag, node).second)
          return failed("node tag ", tag, " (line ", line, ") is defined twice");
      }
      read += n;
    }
    return check_total(header, read, "Nodes", "nodes") && section_end("Nodes");
  }

  bool elements() {
    SectionHeader header;
    if (!section_header(elements_seen_, "Elements", "the number of elements", header)) return false;
    const std::int64_t blocks = header.blocks;
    std::int64_t read = 0;
    for (std::int64_t b = 0; b < blocks; ++b) {
      int dim = 0, entity = 0, type = 0;
      std::int64_t n = 0;
      if (!integer(dim, "an element block's entity dimension") ||
          !integer(entity, "an element block's entity tag") || !integer(type, "an element type") ||
          !count(n, "the block's element count"))
        return false;
      const ElementType kind = element_type(type);
      if (kind.nodes == 0) return failed("element type ", type, " is not a Gmsh element type");
      if (kind.dimension != dim)
        return failed("a block of ", kind.name, " elements (dimension ", kind.dimension,
                      ") on an entity of dimension ", dim);
      if (kind.dimension == 3 && type != 5)
        return failed("the block holds ", kind.name, " elements (type ", type,
                      "); flexstress imports 8-node hexahedra (type 5): mesh the volume with "
                      "hexahedra (transfinite and recombined, or Mesh.SubdivisionAlgorithm = 2)");
      for (std::int64_t i = 0; i < n; ++i) {
        MemberRecord e;
        e.dimension = dim;
        e.entity = entity;
        if (!integer(e.tag, "an element tag")) return false;
        e.line = cursor_.line();
        e.nodes.resize(static_cast<std::size_t>(kind.nodes));
        for (std::int64_t& node : e.nodes)
          if (!integer(node, "an element's node tag")) return false;
        if (type == 5) {
          HexRecord h;
          h.tag = e.tag;
          std::copy(e.nodes.begin(), e.nodes.end(), h.nodes.begin());
          h.entity = entity;
          h.line = e.line;
          hexes_.push_back(h);
        }
        members_.push_back(std::move(e));
      }
      read += n;
    }
    return check_total(header, read, "Elements", "elements") && section_end("Elements");
  }

  bool skip_section(const std::string& name) {
    const std::string end = "$End" + name;
    const int start = cursor_.line();
    for (std::string_view t = cursor_.next(); t != end; t = cursor_.next())
      if (t.empty()) {
        error_ = error_at(start, "section $", name, " has no ", end);
        return false;
      }
    return true;
  }

  Cursor cursor_;
  std::string source_;
  std::optional<Error> error_;
  bool format_seen_ = false, nodes_seen_ = false, elements_seen_ = false;
};

}  // namespace flexstress::fe::gmsh_detail
