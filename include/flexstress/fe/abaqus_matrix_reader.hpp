// Abaqus text input for matrix import (matrix_import.hpp): the matrices Abaqus/Standard writes
// with *MATRIX GENERATE, STIFFNESS, MASS and *MATRIX OUTPUT, STIFFNESS, MASS (FORMAT=MATRIX
// INPUT, the default: files <job>_STIF<step>.mtx and <job>_MASS<step>.mtx), and the node
// coordinates of the *NODE blocks of the input file (.inp).
//
// Matrix lines (Abaqus Keywords Reference, *MATRIX INPUT, data lines): "row node, row DOF,
// column node, column DOF, value", one nonzero per line, a triangle or the square of a
// symmetric matrix. *NODE data lines: "label, x, y[, z]" until the next keyword. Lines starting
// with ** are comments. A flat input file (no parts and instances, or one written with
// "*Preprint" flattening) gives labels that match the matrix files'. Errors name the file and
// line and what was expected.
#pragma once

#include <cctype>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "flexstress/core/status.hpp"
#include "flexstress/fe/matrix_import.hpp"

namespace flexstress::fe {

namespace detail {

/// Comma-separated fields with the blanks around them trimmed.
inline std::vector<std::string> comma_fields(std::string_view line) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t end = line.find(',', start);
    std::string_view f = line.substr(start, end == std::string_view::npos ? end : end - start);
    while (!f.empty() && std::isspace(static_cast<unsigned char>(f.front()))) f.remove_prefix(1);
    while (!f.empty() && std::isspace(static_cast<unsigned char>(f.back()))) f.remove_suffix(1);
    out.emplace_back(f);
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  return out;
}

/// Parses a whole field as an integer / a real (strtod syntax); false if any of it is left.
inline bool whole_integer(const std::string& s, long long& out) {
  if (s.empty()) return false;
  char* end = nullptr;
  out = std::strtoll(s.c_str(), &end, 10);
  return *end == '\0';
}
inline bool whole_real(const std::string& s, double& out) {
  if (s.empty()) return false;
  char* end = nullptr;
  out = std::strtod(s.c_str(), &end);
  return *end == '\0';
}

inline bool starts_with_keyword(std::string_view line, std::string_view keyword) {
  if (line.size() < keyword.size()) return false;
  for (std::size_t i = 0; i < keyword.size(); ++i)
    if (std::toupper(static_cast<unsigned char>(line[i])) != keyword[i]) return false;
  return line.size() == keyword.size() || line[keyword.size()] == ',' ||
         std::isspace(static_cast<unsigned char>(line[keyword.size()]));
}

}  // namespace detail

/// Which matrix a file holds.
enum class ImportedMatrix { stiffness, mass };

/// Reads an Abaqus matrix file (FORMAT=MATRIX INPUT) into model.stiffness or model.mass. `name`
/// (the file's name) prefixes messages. All or nothing.
inline Status read_abaqus_matrix(std::string_view text, ImportedMatrix which, LabeledModel& model,
                                 const std::string& name = "<matrix>") {
  std::vector<LabeledEntry> entries;
  std::istringstream in{std::string(text)};
  std::string line;
  for (int row = 1; std::getline(in, line); ++row) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos || line.rfind("**", 0) == 0) continue;
    const std::string where = name + ":" + std::to_string(row);
    const auto f = detail::comma_fields(line);
    LabeledEntry e;
    long long dof_i = 0, dof_j = 0;
    if (f.size() != 5 || !detail::whole_integer(f[0], e.row_node) ||
        !detail::whole_integer(f[1], dof_i) || !detail::whole_integer(f[2], e.col_node) ||
        !detail::whole_integer(f[3], dof_j) || !detail::whole_real(f[4], e.value))
      return make_error(ErrorCode::bad_file_format, where,
                        ": expected 'row node, row DOF, column node, column DOF, value', got '",
                        line, "'");
    if (dof_i < 1 || dof_i > 6 || dof_j < 1 || dof_j > 6)
      return make_error(ErrorCode::bad_file_format, where, ": DOF ",
                        dof_i < 1 || dof_i > 6 ? dof_i : dof_j,
                        " is not an Abaqus DOF of a node (1 to 6)");
    e.row_dof = static_cast<int>(dof_i);
    e.col_dof = static_cast<int>(dof_j);
    e.where = where;
    entries.push_back(std::move(e));
  }
  if (entries.empty()) return make_error(ErrorCode::bad_file_format, name, ": no matrix entries");
  auto& target = which == ImportedMatrix::stiffness ? model.stiffness : model.mass;
  target.insert(target.end(), std::make_move_iterator(entries.begin()),
                std::make_move_iterator(entries.end()));
  return Status::success();
}

/// Reads the *NODE blocks of an Abaqus input file into model.coordinates (a missing z is 0).
/// Other keywords and their data are skipped. All or nothing.
inline Status read_abaqus_nodes(std::string_view text, LabeledModel& model,
                                const std::string& name = "<input>") {
  std::map<long long, Vector3d> nodes;
  std::map<long long, int> line_of;
  std::istringstream in{std::string(text)};
  std::string line;
  bool in_nodes = false;
  for (int row = 1; std::getline(in, line); ++row) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos || line.rfind("**", 0) == 0) continue;
    if (line[0] == '*') {
      in_nodes = detail::starts_with_keyword(line, "*NODE");
      continue;
    }
    if (!in_nodes) continue;
    const std::string where = name + ":" + std::to_string(row);
    const auto f = detail::comma_fields(line);
    long long label = 0;
    Vector3d x = Vector3d::Zero();
    bool ok = (f.size() == 3 || f.size() == 4) && detail::whole_integer(f[0], label);
    for (std::size_t c = 1; ok && c < f.size(); ++c)
      ok = detail::whole_real(f[c], x(static_cast<Index>(c - 1)));
    if (!ok || !x.allFinite())
      return make_error(ErrorCode::bad_file_format, where,
                        ": expected a *NODE line 'label, x, y[, z]', got '", line, "'");
    if (const auto [it, inserted] = line_of.emplace(label, row); !inserted)
      return make_error(ErrorCode::bad_file_format, where, ": node ", label,
                        " is defined twice (first at line ", it->second, ")");
    if (model.coordinates.count(label) != 0)
      return make_error(ErrorCode::invalid_argument, where, ": node ", label,
                        " already has coordinates (from another file)");
    nodes.emplace(label, x);
  }
  if (nodes.empty()) return make_error(ErrorCode::bad_file_format, name, ": no *NODE data lines");
  model.coordinates.insert(nodes.begin(), nodes.end());
  return Status::success();
}

/// The same from files (messages name the file).
inline Status read_abaqus_matrix_file(const std::string& path, ImportedMatrix which,
                                      LabeledModel& model) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return make_error(ErrorCode::io_error, "cannot open matrix file '", path, "'");
  const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  return read_abaqus_matrix(text, which, model, path);
}
inline Status read_abaqus_nodes_file(const std::string& path, LabeledModel& model) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return make_error(ErrorCode::io_error, "cannot open input file '", path, "'");
  const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  return read_abaqus_nodes(text, model, path);
}

}  // namespace flexstress::fe
