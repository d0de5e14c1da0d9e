// VTK output: a mesh with point and cell fields as an XML unstructured grid (.vtu, ASCII), the
// format ParaView and VisIt open directly (VTK file formats, "Serial XML: UnstructuredGrid",
// Kitware, The VTK User's Guide, 11th ed., ch. 19).
//
// Points are all mesh nodes, in id order (nodes no element uses are written too: link masters
// show as points). Cells, in this order:
//  1. bricks as VTK_HEXAHEDRON (12); VTK's node order is the Hex8Element order (Hughes);
//  2. beams as VTK_LINE (3);
//  3. point masses as VTK_VERTEX (1), if VtkOptions::point_masses;
//  4. one VTK_LINE per rigid-link slave (master to slave), if VtkOptions::rigid_links;
//  5. one VTK_LINE per averaging-link face node (reference to face node), if
//     VtkOptions::averaging_links.
// vtk_num_cells() gives the count, which cell fields must match. Six-component fields are read
// by ParaView as symmetric tensors in the order XX, YY, ZZ, XY, YZ, XZ, which is flexstress's
// Voigt order (xx, yy, zz, xy, yz, zx). Numbers are written with 17 significant digits, so a
// reader gets back the same doubles. Units are the caller's (SI in the FE kernel).
#pragma once

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/fe/dof_map.hpp"
#include "flexstress/fe/mesh.hpp"
#include "flexstress/fe/stress_measures.hpp"
#include "flexstress/fe/stress_recovery.hpp"

namespace flexstress::fe {

/// One data array: `values` is components x count (a column per point or per cell).
struct VtkField {
  std::string name;
  MatrixXd values;
};

/// Point and cell fields to write with a mesh.
struct VtkData {
  std::vector<VtkField> point_data;
  std::vector<VtkField> cell_data;
};

struct VtkOptions {
  bool point_masses = true;  ///< write point masses as VTK_VERTEX cells
  bool rigid_links = false;  ///< write rigid links as VTK_LINE cells, master to each slave
  /// write averaging (RBE3) links as VTK_LINE cells, reference to each face node
  bool averaging_links = false;
};

/// VTK cell type ids used here (vtkCellType.h).
enum class VtkCellType : unsigned char { vertex = 1, line = 3, hexahedron = 12 };

/// Number of cells write_vtu writes for `mesh` with `options` (the size of cell fields).
FLEXSTRESS_PRECOMPUTE
Index vtk_num_cells(const Mesh& mesh, const VtkOptions& options = {}) {
  Index n = static_cast<Index>(mesh.hexes().size() + mesh.beams().size());
  if (options.point_masses) n += static_cast<Index>(mesh.point_masses().size());
  if (options.rigid_links)
    for (const auto& l : mesh.rigid_links()) n += static_cast<Index>(l.slaves.size());
  if (options.averaging_links)
    for (const auto& l : mesh.averaging_links()) n += static_cast<Index>(l.face.size());
  return n;
}

/// Nodal translations (3 x num_nodes) from the all-DOF displacements u; nodes without DOFs
/// get zero.
FLEXSTRESS_PRECOMPUTE
Result<VtkField> displacement_field(const Mesh& mesh, const DofMap& dofs, const VectorXd& u,
                                    const std::string& name = "displacement") {
  if (dofs.num_nodes() != mesh.num_nodes() || u.size() != dofs.size())
    return make_error(ErrorCode::size_mismatch, "displacement_field: ", u.size(),
                      " displacements and a DOF map of ", dofs.size(), " DOFs over ",
                      dofs.num_nodes(), " nodes for a mesh of ", mesh.num_nodes(), " nodes");
  VtkField f{name, MatrixXd::Zero(3, mesh.num_nodes())};
  for (Index n = 0; n < mesh.num_nodes(); ++n)
    for (int c = 0; c < 3 && c < dofs.num_node_dofs(n); ++c) f.values(c, n) = u(dofs.dof(n, c));
  return f;
}

/// Displacement, averaged nodal brick stress (6 components, Voigt) and its von Mises value:
/// the point fields one usually wants. Nodes on no brick get zero stress.
FLEXSTRESS_PRECOMPUTE
Result<VtkData> standard_fields(const Mesh& mesh, const DofMap& dofs, const VectorXd& u)
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  auto disp = displacement_field(mesh, dofs, u);
  if (!disp) return disp.error();
  VtkData data;
  data.point_data.push_back(std::move(*disp));
  if (!mesh.hexes().empty()) {
    auto nodal = nodal_stresses(mesh, dofs, u);
    if (!nodal) return nodal.error();
    VtkField vm{"von_mises", MatrixXd::Zero(1, mesh.num_nodes())};
    for (Index n = 0; n < mesh.num_nodes(); ++n) vm.values(0, n) = von_mises(nodal->at(n));
    data.point_data.push_back(VtkField{"stress", std::move(nodal->stress)});
    data.point_data.push_back(std::move(vm));
  }
  return data;
}
#else
    ;
#endif

namespace detail {

FLEXSTRESS_PRECOMPUTE
Status check_vtk_field(const VtkField& f, Index count, const char* kind) {
  if (f.name.empty() || f.name.find_first_of("<>&\"'") != std::string::npos)
    return make_error(ErrorCode::invalid_argument, "VTK ", kind, " field '", f.name,
                      "': a name must be non-empty and free of < > & \" '");
  if (f.values.cols() != count || f.values.rows() < 1)
    return make_error(ErrorCode::size_mismatch, "VTK ", kind, " field '", f.name, "' has ",
                      f.values.rows(), " x ", f.values.cols(), " values; expected components x ",
                      count);
  for (Index j = 0; j < f.values.cols(); ++j)
    for (Index i = 0; i < f.values.rows(); ++i)
      if (!std::isfinite(f.values(i, j)))
        return make_error(ErrorCode::invalid_argument, "VTK ", kind, " field '", f.name,
                          "': component ", i, " of entry ", j, " is not finite");
  return Status::success();
}

FLEXSTRESS_PRECOMPUTE
void write_vtk_array(std::FILE* out, const VtkField& f) {
  std::fprintf(out,
               "        <DataArray type=\"Float64\" Name=\"%s\" NumberOfComponents=\"%d\" "
               "format=\"ascii\">\n",
               f.name.c_str(), static_cast<int>(f.values.rows()));
  for (Index j = 0; j < f.values.cols(); ++j) {
    std::fputs("         ", out);
    for (Index i = 0; i < f.values.rows(); ++i) std::fprintf(out, " %.17g", f.values(i, j));
    std::fputc('\n', out);
  }
  std::fputs("        </DataArray>\n", out);
}

}  // namespace detail

/// Writes `mesh` and `data` to `path` as an ASCII .vtu file. Fails, naming the field or the
/// path, for fields of the wrong size, bad names or non-finite values (nothing is written),
/// and when the file cannot be opened or written (io_error).
FLEXSTRESS_PRECOMPUTE
Status write_vtu(const std::string& path, const Mesh& mesh, const VtkData& data = {},
                 const VtkOptions& options = {})
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  if (Status s = mesh.validate(); !s) return s;
  const Index np = mesh.num_nodes(), nc = vtk_num_cells(mesh, options);
  for (const auto& f : data.point_data)
    if (Status s = detail::check_vtk_field(f, np, "point"); !s) return s;
  for (const auto& f : data.cell_data)
    if (Status s = detail::check_vtk_field(f, nc, "cell"); !s) return s;

  // Connectivity, offsets and types, in the documented cell order.
  std::vector<Index> conn, offsets;
  std::vector<int> types;
  auto cell = [&](VtkCellType type, std::initializer_list<Index> nodes) {
    conn.insert(conn.end(), nodes.begin(), nodes.end());
    offsets.push_back(static_cast<Index>(conn.size()));
    types.push_back(static_cast<int>(type));
  };
  for (const auto& h : mesh.hexes())
    cell(VtkCellType::hexahedron, {h.nodes[0], h.nodes[1], h.nodes[2], h.nodes[3], h.nodes[4],
                                   h.nodes[5], h.nodes[6], h.nodes[7]});
  for (const auto& b : mesh.beams()) cell(VtkCellType::line, {b.nodes[0], b.nodes[1]});
  if (options.point_masses)
    for (const auto& p : mesh.point_masses()) cell(VtkCellType::vertex, {p.node});
  if (options.rigid_links)
    for (const auto& l : mesh.rigid_links())
      for (Index s : l.slaves) cell(VtkCellType::line, {l.master, s});
  if (options.averaging_links)
    for (const auto& l : mesh.averaging_links())
      for (Index f : l.face) cell(VtkCellType::line, {l.reference, f});

  std::FILE* out = std::fopen(path.c_str(), "w");
  if (out == nullptr)
    return make_error(ErrorCode::io_error, "cannot open '", path,
                      "' for writing: ", std::string(std::strerror(errno)));
  std::fputs("<?xml version=\"1.0\"?>\n", out);
  std::fputs(
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n  <UnstructuredGrid>\n",
      out);
  std::fprintf(out, "    <Piece NumberOfPoints=\"%lld\" NumberOfCells=\"%lld\">\n",
               static_cast<long long>(np), static_cast<long long>(nc));
  std::fputs("      <PointData>\n", out);
  for (const auto& f : data.point_data) detail::write_vtk_array(out, f);
  std::fputs("      </PointData>\n      <CellData>\n", out);
  for (const auto& f : data.cell_data) detail::write_vtk_array(out, f);
  std::fputs("      </CellData>\n      <Points>\n", out);
  MatrixXd xyz(3, np);
  for (Index n = 0; n < np; ++n) xyz.col(n) = mesh.node(n);
  detail::write_vtk_array(out, VtkField{"Points", xyz});
  std::fputs("      </Points>\n      <Cells>\n", out);
  auto ints = [&](const char* name, const char* type, auto const& v) {
    std::fprintf(out, "        <DataArray type=\"%s\" Name=\"%s\" format=\"ascii\">\n", type, name);
    for (std::size_t i = 0; i < v.size(); ++i)
      std::fprintf(out, i % 16 == 0 ? "\n          %lld" : " %lld", static_cast<long long>(v[i]));
    std::fputs("\n        </DataArray>\n", out);
  };
  ints("connectivity", "Int64", conn);
  ints("offsets", "Int64", offsets);
  ints("types", "UInt8", types);
  std::fputs("      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n", out);
  const bool write_failed = std::ferror(out) != 0;
  if (std::fclose(out) != 0 || write_failed)
    return make_error(ErrorCode::io_error, "writing '", path,
                      "' failed (disk full or the file system refused it)");
  return Status::success();
}
#else
    ;
#endif

}  // namespace flexstress::fe

// This header's precompute entry points (core/precompute.hpp).
#define FLEXSTRESS_PRECOMPUTE_FE_VTK_WRITER(X)             \
  X(6, Result<fe::VtkData>, fe::standard_fields,           \
    (const fe::Mesh&, const fe::DofMap&, const VectorXd&)) \
  X(6, Status, fe::write_vtu,                              \
    (const std::string&, const fe::Mesh&, const fe::VtkData&, const fe::VtkOptions&))
namespace flexstress {
FLEXSTRESS_PRECOMPUTE_EXTERN(FLEXSTRESS_PRECOMPUTE_FE_VTK_WRITER)
}  // namespace flexstress
