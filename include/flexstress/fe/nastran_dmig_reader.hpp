// Nastran bulk data for matrix import (matrix_import.hpp): GRID cards (node coordinates) and
// DMIG cards (direct matrix input at grid points) for the stiffness and the mass, by the names
// the user gives (e.g. KAAX and MAAX, as written by a PARAM,EXTOUT,DMIGPCH run).
//
// Cards (MSC Nastran Quick Reference Guide, GRID and DMIG): small-field (8 columns per field,
// fields 2 to 9 of each line carry data) or free-field (comma-separated). A line whose first
// field is blank or starts with '+' continues the card above; '$' starts a comment. GRID:
// ID, CP, X1, X2, X3 (CP blank or 0: basic coordinates). DMIG header: NAME, "0", IFO (6
// symmetric or 1 square), TIN (1 or 2: real), TOUT, POLAR, -, NCOL; each column: NAME, GJ, CJ,
// -, then groups of four fields G, C, A, B (B is for complex input and stays blank). Reals may
// use Nastran's exponent without E (1.5+3, 2.-4). Other cards are skipped. Large-field cards
// (GRID*, DMIG*) are refused by name. Errors name the file and line.
#pragma once

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "flexstress/core/status.hpp"
#include "flexstress/fe/abaqus_matrix_reader.hpp"
#include "flexstress/fe/matrix_import.hpp"

namespace flexstress::fe {

namespace detail {

/// One bulk data card: its fields (field 1 = name) and the line where it starts.
struct BulkCard {
  std::vector<std::string> fields;
  int line = 0;
};

inline std::string trimmed_upper(std::string_view f) {
  while (!f.empty() && std::isspace(static_cast<unsigned char>(f.front()))) f.remove_prefix(1);
  while (!f.empty() && std::isspace(static_cast<unsigned char>(f.back()))) f.remove_suffix(1);
  std::string s(f);
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

/// The fields of one line: free-field if it has a comma, else small-field (8 columns each;
/// the tenth field, a continuation mark, is dropped).
inline std::vector<std::string> bulk_fields(std::string_view line) {
  std::vector<std::string> out;
  if (line.find(',') != std::string_view::npos) {
    for (const std::string& f : comma_fields(line)) out.push_back(trimmed_upper(f));
    if (out.size() >= 10 && (out[9].empty() || out[9].front() == '+'))
      out.resize(9);  // the continuation mark
    return out;
  }
  for (std::size_t c = 0; c < 9 * 8 && c < line.size(); c += 8)
    out.push_back(trimmed_upper(line.substr(c, 8)));
  return out;
}

/// A Nastran real: strtod syntax, or a mantissa followed by a signed exponent without E
/// (1.5+3 = 1.5e3), or D for the exponent.
inline bool nastran_real(std::string s, double& out) {
  for (char& c : s)
    if (c == 'D') c = 'E';
  for (std::size_t i = 1; i < s.size(); ++i)
    if ((s[i] == '+' || s[i] == '-') && s[i - 1] != 'E' &&
        (std::isdigit(static_cast<unsigned char>(s[i - 1])) || s[i - 1] == '.')) {
      s.insert(i, 1, 'E');
      break;
    }
  return whole_real(s, out);
}

/// Splits bulk data into cards, joining continuation lines.
inline Result<std::vector<BulkCard>> bulk_cards(std::string_view text, const std::string& name) {
  std::vector<BulkCard> cards;
  // A whole input file: the executive and case control sections before BEGIN BULK are skipped.
  const bool whole_deck = [&] {
    std::istringstream scan{std::string(text)};
    std::string l;
    while (std::getline(scan, l))
      if (trimmed_upper(l).rfind("BEGIN BULK", 0) == 0) return true;
    return false;
  }();
  bool in_bulk = !whole_deck;
  std::istringstream in{std::string(text)};
  std::string line;
  for (int row = 1; std::getline(in, line); ++row) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (!in_bulk) {
      in_bulk = trimmed_upper(line).rfind("BEGIN BULK", 0) == 0;
      continue;
    }
    const std::size_t comment = line.find('$');
    if (comment != std::string::npos) line.erase(comment);
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    if (line.find('\t') != std::string::npos)
      return make_error(ErrorCode::bad_file_format, name, ":", row,
                        ": a tab in a small-field card (fields are 8 columns; use spaces or "
                        "commas)");
    auto fields = bulk_fields(line);
    fields.resize(std::max<std::size_t>(fields.size(), 9));  // blank trailing fields count too
    const std::string& first = fields.front();
    if (!first.empty() && first.back() == '*' && first.front() != '*')
      return make_error(ErrorCode::bad_file_format, name, ":", row, ": large-field card ", first,
                        " is not supported (write small-field or free-field cards)");
    if (first.empty() || first.front() == '+') {
      if (cards.empty())
        return make_error(ErrorCode::bad_file_format, name, ":", row,
                          ": a continuation line with no card before it");
      auto& f = cards.back().fields;
      f.insert(f.end(), std::make_move_iterator(fields.begin() + 1),
               std::make_move_iterator(fields.end()));
      continue;
    }
    cards.push_back(BulkCard{std::move(fields), row});
  }
  return cards;
}

}  // namespace detail

/// Reads GRID cards into model.coordinates and the DMIG matrices named `stiffness_name` and
/// `mass_name` into model.stiffness and model.mass (either name may be empty to skip it). `name`
/// (the file's name) prefixes messages. All or nothing.
inline Status read_nastran_bulk(std::string_view text, const std::string& stiffness_name,
                                const std::string& mass_name, LabeledModel& model,
                                const std::string& name = "<bulk>") {
  auto cards = detail::bulk_cards(text, name);
  if (!cards) return cards.error();
  const std::string stiffness_upper = detail::trimmed_upper(stiffness_name);
  const std::string mass_upper = detail::trimmed_upper(mass_name);
  std::map<long long, Vector3d> grids;
  std::vector<LabeledEntry> k, m;
  std::map<std::string, bool> headers;  // DMIG name -> header seen
  const auto field = [](const detail::BulkCard& c, std::size_t i) -> const std::string& {
    static const std::string blank;
    return i < c.fields.size() ? c.fields[i] : blank;
  };
  for (const detail::BulkCard& card : *cards) {
    const std::string where = name + ":" + std::to_string(card.line);
    const std::string& kind = card.fields.front();
    if (kind == "GRID") {
      long long id = 0, cp = 0;
      Vector3d x = Vector3d::Zero();
      bool ok = detail::whole_integer(field(card, 1), id) &&
                (field(card, 2).empty() || detail::whole_integer(field(card, 2), cp));
      for (int c = 0; ok && c < 3; ++c)
        ok = field(card, 3 + static_cast<std::size_t>(c)).empty() ||
             detail::nastran_real(field(card, 3 + static_cast<std::size_t>(c)), x(c));
      if (!ok || !x.allFinite())
        return make_error(ErrorCode::bad_file_format, where,
                          ": expected GRID, ID, CP, X1, X2, X3, got '", field(card, 1), ", ",
                          field(card, 2), ", ", field(card, 3), ", ", field(card, 4), ", ",
                          field(card, 5), "'");
      if (cp != 0)
        return make_error(ErrorCode::bad_file_format, where, ": GRID ", id,
                          " is given in coordinate system ", cp,
                          "; only basic coordinates (CP blank or 0) are supported");
      if (!grids.emplace(id, x).second || model.coordinates.count(id) != 0)
        return make_error(ErrorCode::bad_file_format, where, ": GRID ", id, " is defined twice");
      continue;
    }
    if (kind != "DMIG") continue;
    const std::string& matrix = field(card, 1);
    const bool is_k = !stiffness_upper.empty() && matrix == stiffness_upper;
    const bool is_m = !mass_upper.empty() && matrix == mass_upper;
    if (!is_k && !is_m) continue;
    if (field(card, 2) == "0") {  // the header
      long long ifo = 0, tin = 0;
      if (!detail::whole_integer(field(card, 3), ifo) ||
          !detail::whole_integer(field(card, 4), tin))
        return make_error(ErrorCode::bad_file_format, where, ": DMIG ", matrix,
                          " header: expected the integers IFO and TIN");
      if (ifo != 6 && ifo != 1)
        return make_error(ErrorCode::bad_file_format, where, ": DMIG ", matrix, " has IFO = ", ifo,
                          "; a stiffness or mass is square (1) or symmetric (6)");
      if (tin != 1 && tin != 2)
        return make_error(ErrorCode::bad_file_format, where, ": DMIG ", matrix, " has TIN = ", tin,
                          "; only real matrices (1 or 2) are supported");
      headers[matrix] = true;
      continue;
    }
    if (!headers[matrix])
      return make_error(ErrorCode::bad_file_format, where, ": DMIG ", matrix,
                        " column before its header card (GJ = \"0\")");
    long long gj = 0, cj = 0;
    if (!detail::whole_integer(field(card, 2), gj) || !detail::whole_integer(field(card, 3), cj))
      return make_error(ErrorCode::bad_file_format, where, ": DMIG ", matrix,
                        " column: expected the integers GJ and CJ, got '", field(card, 2), "', '",
                        field(card, 3), "'");
    const std::size_t groups = (card.fields.size() - 5 + 3) / 4;  // at least 9 fields
    std::size_t taken = 0;
    for (std::size_t g = 0; g < groups; ++g) {
      const std::size_t f0 = 5 + 4 * g;
      if (field(card, f0).empty() && field(card, f0 + 1).empty() && field(card, f0 + 2).empty())
        continue;  // blank padding of a small-field line
      LabeledEntry e;
      long long gi = 0, ci = 0;
      if (!detail::whole_integer(field(card, f0), gi) ||
          !detail::whole_integer(field(card, f0 + 1), ci) ||
          !detail::nastran_real(field(card, f0 + 2), e.value))
        return make_error(ErrorCode::bad_file_format, where, ": DMIG ", matrix, " column (", gj,
                          ", ", cj, ") entry ", g + 1, ": expected G, C, A, got '", field(card, f0),
                          "', '", field(card, f0 + 1), "', '", field(card, f0 + 2), "'");
      if (!field(card, f0 + 3).empty())
        return make_error(ErrorCode::bad_file_format, where, ": DMIG ", matrix,
                          " has an imaginary part; only real matrices are supported");
      for (long long c : {cj, ci})
        if (c < 1 || c > 6)
          return make_error(ErrorCode::bad_file_format, where, ": DMIG ", matrix, " component ", c,
                            " is not a grid point DOF (1 to 6)");
      e.row_node = gi;
      e.row_dof = static_cast<int>(ci);
      e.col_node = gj;
      e.col_dof = static_cast<int>(cj);
      e.where = where;
      (is_k ? k : m).push_back(std::move(e));
      ++taken;
    }
    if (taken == 0)
      return make_error(ErrorCode::bad_file_format, where, ": DMIG ", matrix, " column (", gj, ", ",
                        cj, ") has no entries");
  }
  for (const auto& [wanted, entries] : {std::pair{stiffness_upper, &k}, std::pair{mass_upper, &m}})
    if (!wanted.empty() && entries->empty())
      return make_error(ErrorCode::bad_file_format, name, ": no DMIG ", wanted, " entries");
  model.coordinates.insert(grids.begin(), grids.end());
  model.stiffness.insert(model.stiffness.end(), k.begin(), k.end());
  model.mass.insert(model.mass.end(), m.begin(), m.end());
  return Status::success();
}

/// The same from a file (messages name the file).
inline Status read_nastran_bulk_file(const std::string& path, const std::string& stiffness_name,
                                     const std::string& mass_name, LabeledModel& model) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return make_error(ErrorCode::io_error, "cannot open bulk data file '", path, "'");
  const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  return read_nastran_bulk(text, stiffness_name, mass_name, model, path);
}

}  // namespace flexstress::fe
