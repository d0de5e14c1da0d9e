// VTK .vtu output, read back with the real VTK library (Debian's python3-vtk9, through
// /usr/bin/python3 and tests/fe/read_vtu.py): point and cell counts, cell types, connectivity,
// coordinates and field values must come back exactly. Reference fields: a linear displacement
// field u = G x, whose brick stress is D eps(G) at every brick node (any brick reproduces a
// linear field exactly, the patch-test property).
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <doctest/doctest.h>

#include <flexstress/fe/assembly.hpp>
#include <flexstress/fe/box_mesh.hpp>
#include <flexstress/fe/rhs_attachment_mesh.hpp>
#include <flexstress/fe/static_solver.hpp>
#include <flexstress/fe/vtk_writer.hpp>

namespace test_vtk_writer {

using namespace flexstress;
using namespace flexstress::fe;

namespace {

// Runs read_vtu.py on `vtu`; returns its dump as key -> tokens (the first word of each line,
// "point NAME" and "cell NAME" for arrays).
std::map<std::string, std::vector<std::string>> read_back(const std::string& vtu) {
  std::map<std::string, std::vector<std::string>> out;
  if (!std::filesystem::exists("/usr/bin/python3")) {
    FAIL(
        "/usr/bin/python3 is missing: install python3 and python3-vtk9 "
        "(apt-get install python3-vtk9) to check VTK output with the real VTK library");
    return out;
  }
  const std::string dump = vtu + ".txt";
  const std::string cmd = std::string("/usr/bin/python3 '") + FLEXSTRESS_TEST_SOURCE_DIR +
                          "/fe/read_vtu.py' '" + vtu + "' '" + dump + "'";
  const int rc = std::system(cmd.c_str());
  const int code = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  if (code == 3) {
    FAIL("python3 cannot import vtk: install python3-vtk9 (apt-get install python3-vtk9)");
    return out;
  }
  REQUIRE_MESSAGE(code == 0, "read_vtu.py failed on " << vtu << " (exit " << code << ")");
  std::ifstream in(dump);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string key, token;
    words >> key;
    if (key == "point" || key == "cell") {
      std::string name;
      words >> name;
      key += " " + name;
    }
    while (words >> token) out[key].push_back(token);
  }
  return out;
}

std::vector<double> numbers(const std::vector<std::string>& tokens, std::size_t skip = 0) {
  std::vector<double> v;
  for (std::size_t i = skip; i < tokens.size(); ++i) v.push_back(std::stod(tokens[i]));
  return v;
}

// Two bricks, a beam hanging off them with a point mass at its end, and a rigid link from a
// master node to the x = 0 face.
struct SmallModel {
  Mesh mesh;
  Index master = 0;
  SmallModel() {
    const Index mat = mesh.add_material(steel());
    const Index sec = mesh.add_section(rectangular_hollow_section(0.05, 0.05, 0.004));
    Index id[3][2][2];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 2; ++j)
        for (int k = 0; k < 2; ++k)
          id[i][j][k] = mesh.add_node(Vector3d(0.1 * i, 0.1 * j, 0.1 * k));
    for (int i = 0; i < 2; ++i)
      mesh.add_hex8({id[i][0][0], id[i + 1][0][0], id[i + 1][1][0], id[i][1][0], id[i][0][1],
                     id[i + 1][0][1], id[i + 1][1][1], id[i][1][1]},
                    mat);
    const Index tip = mesh.add_node(Vector3d(0.35, 0, 0));
    mesh.add_beam(id[2][0][0], tip, mat, sec);
    mesh.add_point_mass(tip, 2.5);
    master = mesh.add_node(Vector3d(-0.1, 0.05, 0.05));
    mesh.add_rigid_link(master, {id[0][0][0], id[0][1][0], id[0][0][1], id[0][1][1]});
  }
};

}  // namespace

TEST_CASE("VTK: a small mixed mesh with known fields reads back exactly with VTK") {
  SmallModel m;
  auto dofs = DofMap::build(m.mesh);
  REQUIRE(dofs.ok());
  Matrix3d g;
  g << 1.0, 0.2, 0.0,  //
      0.1, -0.5, 0.3,  //
      0.0, 0.2, 0.4;
  g *= 1e-3;
  VectorXd u = VectorXd::Zero(dofs->size());
  for (Index n = 0; n < m.mesh.num_nodes(); ++n) {
    const Vector3d un = g * m.mesh.node(n);
    for (int c = 0; c < 3; ++c) u(dofs->dof(n, c)) = un(c);
  }
  auto data = standard_fields(m.mesh, *dofs, u);
  REQUIRE(data.ok());
  VtkOptions options;
  options.rigid_links = true;
  const Index nc = vtk_num_cells(m.mesh, options);
  CHECK(nc == 2 + 1 + 1 + 4);
  MatrixXd cell_ids(1, nc), cell_vec(3, nc);
  for (Index c = 0; c < nc; ++c) {
    cell_ids(0, c) = static_cast<double>(c);
    cell_vec.col(c) = Vector3d(c, -0.5 * c, 1.0 / 3.0);
  }
  data->cell_data.push_back({"cell_index", cell_ids});
  data->cell_data.push_back({"cell_vector", cell_vec});
  const std::string path = std::string(FLEXSTRESS_TEST_OUTPUT_DIR) + "/fe_small_mesh.vtu";
  REQUIRE(write_vtu(path, m.mesh, *data, options).ok());

  auto back = read_back(path);
  REQUIRE(back.count("points") == 1);
  CHECK(std::stol(back["points"][0]) == m.mesh.num_nodes());
  CHECK(std::stol(back["cells"][0]) == nc);
  // VTK cell types (vtkCellType.h): hexahedron 12, line 3, vertex 1.
  const std::vector<std::string> types{"12", "12", "3", "1", "3", "3", "3", "3"};
  CHECK(back["types"] == types);
  // Connectivity: each cell's size, then its node ids, in the documented order.
  std::vector<std::string> conn;
  auto add = [&](std::vector<Index> ids) {
    conn.push_back(std::to_string(ids.size()));
    for (Index i : ids) conn.push_back(std::to_string(i));
  };
  for (const auto& h : m.mesh.hexes()) add({h.nodes.begin(), h.nodes.end()});
  add({m.mesh.beams()[0].nodes[0], m.mesh.beams()[0].nodes[1]});
  add({m.mesh.point_masses()[0].node});
  for (Index s : m.mesh.rigid_links()[0].slaves) add({m.master, s});
  CHECK(back["connectivity"] == conn);
  const std::vector<double> xyz = numbers(back["coords"]);
  REQUIRE(xyz.size() == static_cast<std::size_t>(3 * m.mesh.num_nodes()));
  for (Index n = 0; n < m.mesh.num_nodes(); ++n)
    for (int c = 0; c < 3; ++c)
      CHECK(xyz[static_cast<std::size_t>(3 * n + c)] == m.mesh.node(n)(c));
  // Fields: the exact linear displacement; brick-node stress D eps(G) (Hooke's law), zero
  // elsewhere; von Mises of that stress.
  const std::vector<double> disp = numbers(back["point displacement"], 1);
  const std::vector<double> stress = numbers(back["point stress"], 1);
  const std::vector<double> vm = numbers(back["point von_mises"], 1);
  CHECK(back["point stress"][0] == "6");
  REQUIRE(disp.size() == static_cast<std::size_t>(3 * m.mesh.num_nodes()));
  REQUIRE(stress.size() == static_cast<std::size_t>(6 * m.mesh.num_nodes()));
  REQUIRE(vm.size() == static_cast<std::size_t>(m.mesh.num_nodes()));
  Vector6d eps;
  eps << g(0, 0), g(1, 1), g(2, 2), g(0, 1) + g(1, 0), g(1, 2) + g(2, 1), g(2, 0) + g(0, 2);
  const Vector6d sigma = elasticity_matrix(steel()) * eps;
  for (Index n = 0; n < m.mesh.num_nodes(); ++n) {
    const Vector3d un = g * m.mesh.node(n);
    for (int c = 0; c < 3; ++c) CHECK(disp[static_cast<std::size_t>(3 * n + c)] == un(c));
    const bool on_brick = n < 12;
    for (int c = 0; c < 6; ++c)
      CHECK(stress[static_cast<std::size_t>(6 * n + c)] ==
            doctest::Approx(on_brick ? sigma(c) : 0.0).epsilon(1e-10).scale(sigma.norm()));
    CHECK(vm[static_cast<std::size_t>(n)] ==
          doctest::Approx(on_brick ? von_mises(sigma) : 0.0).epsilon(1e-10).scale(sigma.norm()));
  }
  // Written values come back bit for bit (17 significant digits).
  for (Index n = 0; n < m.mesh.num_nodes(); ++n)
    for (int c = 0; c < 6; ++c)
      CHECK(stress[static_cast<std::size_t>(6 * n + c)] == data->point_data[1].values(c, n));
  const std::vector<double> ids = numbers(back["cell cell_index"], 1);
  const std::vector<double> vec = numbers(back["cell cell_vector"], 1);
  REQUIRE(ids.size() == static_cast<std::size_t>(nc));
  REQUIRE(vec.size() == static_cast<std::size_t>(3 * nc));
  for (Index c = 0; c < nc; ++c) {
    CHECK(ids[static_cast<std::size_t>(c)] == static_cast<double>(c));
    for (int k = 0; k < 3; ++k) CHECK(vec[static_cast<std::size_t>(3 * c + k)] == cell_vec(k, c));
  }
}

TEST_CASE("VTK: averaging links are drawn as lines from the reference to each face node") {
  // One brick and an averaging link from a node beyond its x = 1 face to that face's corners.
  Mesh mesh;
  BoxMeshSpec spec;
  spec.material = mesh.add_material(steel());
  const BoxMesh box = *add_box_mesh(mesh, spec);
  const std::vector<Index> face = {box.node(1, 0, 0), box.node(1, 1, 0), box.node(1, 1, 1),
                                   box.node(1, 0, 1)};
  const Index reference = mesh.add_node(Vector3d(1.5, 0.5, 0.5));
  mesh.add_averaging_link(reference, face);
  VtkOptions options;
  CHECK(vtk_num_cells(mesh, options) == 1);  // off by default, like rigid links
  options.averaging_links = true;
  CHECK(vtk_num_cells(mesh, options) == 1 + 4);
  auto dofs = DofMap::build(mesh);
  REQUIRE(dofs.ok());
  auto data = standard_fields(mesh, *dofs, VectorXd::Zero(dofs->size()));
  REQUIRE(data.ok());
  const std::string path = std::string(FLEXSTRESS_TEST_OUTPUT_DIR) + "/fe_averaging_link.vtu";
  REQUIRE(write_vtu(path, mesh, *data, options).ok());
  auto back = read_back(path);
  CHECK(back["types"] == std::vector<std::string>{"12", "3", "3", "3", "3"});
  std::vector<std::string> conn{"8"};
  for (Index n : mesh.hexes()[0].nodes) conn.push_back(std::to_string(n));
  for (Index f : face)
    for (const std::string& t : {std::string("2"), std::to_string(reference), std::to_string(f)})
      conn.push_back(t);
  CHECK(back["connectivity"] == conn);
}

TEST_CASE("VTK: the RHS sub-model under bending (the file docs/fe.md renders)") {
  RhsAttachmentSpec spec;
  auto r = make_rhs_attachment_mesh(spec);
  REQUIRE(r.ok());
  Mesh& mesh = r->mesh;
  const Index m0 = mesh.add_node(Vector3d(spec.x0, 0, 0)),
              m1 = mesh.add_node(Vector3d(spec.x1, 0, 0));
  mesh.add_rigid_link(m0, r->end_section_x0);
  mesh.add_rigid_link(m1, r->end_section_x1);
  BoundaryConditions bc;
  bc.clamp(m0);
  auto model = assemble(mesh, bc);
  REQUIRE(model.ok());
  auto solver = StaticSolver::factorize(mesh, *model);
  REQUIRE(solver.ok());
  const BeamSection sec = rectangular_hollow_section(spec.height, spec.width, spec.wall);
  auto f = load_vector(model->dofs, {{m1, 5, -100e6 * sec.iz / 0.075}});  // 100 MPa top tension
  REQUIRE(f.ok());
  const VectorXd u = solver->solve(*f);
  auto data = standard_fields(mesh, model->dofs, u);
  REQUIRE(data.ok());
  const std::string path = std::string(FLEXSTRESS_TEST_OUTPUT_DIR) + "/rhs_attachment_bending.vtu";
  REQUIRE(write_vtu(path, mesh, *data).ok());
  auto back = read_back(path);
  CHECK(std::stol(back["points"][0]) == mesh.num_nodes());
  CHECK(std::stol(back["cells"][0]) == static_cast<long>(mesh.hexes().size()));
  const std::vector<double> vm = numbers(back["point von_mises"], 1);
  REQUIRE(vm.size() == static_cast<std::size_t>(mesh.num_nodes()));
  CHECK(*std::max_element(vm.begin(), vm.end()) == data->point_data[2].values.maxCoeff());
}

TEST_CASE("VTK: clear errors") {
  SmallModel m;
  SUBCASE("a file that cannot be written") {
    const std::string path = std::string(FLEXSTRESS_TEST_OUTPUT_DIR) + "/no/such/dir/out.vtu";
    Status s = write_vtu(path, m.mesh);
    REQUIRE_FALSE(s.ok());
    CHECK(s.error().code == ErrorCode::io_error);
    CHECK(s.error().message.find("cannot open '" + path + "' for writing") != std::string::npos);
  }
  SUBCASE("a field of the wrong size") {
    VtkData data;
    data.point_data.push_back({"displacement", MatrixXd::Zero(3, 4)});
    Status s = write_vtu(std::string(FLEXSTRESS_TEST_OUTPUT_DIR) + "/bad.vtu", m.mesh, data);
    REQUIRE_FALSE(s.ok());
    CHECK(s.error().code == ErrorCode::size_mismatch);
    CHECK(s.error().message.find("point field 'displacement' has 3 x 4 values") !=
          std::string::npos);
  }
  SUBCASE("a non-finite value") {
    VtkData data;
    data.cell_data.push_back({"damage", MatrixXd::Zero(1, vtk_num_cells(m.mesh))});
    data.cell_data[0].values(0, 2) = std::nan("");
    Status s = write_vtu(std::string(FLEXSTRESS_TEST_OUTPUT_DIR) + "/bad.vtu", m.mesh, data);
    REQUIRE_FALSE(s.ok());
    CHECK(s.error().message.find("cell field 'damage': component 0 of entry 2 is not finite") !=
          std::string::npos);
  }
  SUBCASE("a name that would break the XML") {
    VtkData data;
    data.point_data.push_back({"a<b", MatrixXd::Zero(1, m.mesh.num_nodes())});
    Status s = write_vtu(std::string(FLEXSTRESS_TEST_OUTPUT_DIR) + "/bad.vtu", m.mesh, data);
    REQUIRE_FALSE(s.ok());
    CHECK(s.error().code == ErrorCode::invalid_argument);
  }
}

}  // namespace test_vtk_writer
