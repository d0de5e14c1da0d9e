// Gmsh import (MSH 4.1, ASCII). References: the Gmsh reference manual's format description
// (the hand-written file below follows it line by line), Gmsh itself (Debian's gmsh meshes
// tests/fe/gmsh/cantilever.geo when the build finds it), flexstress's own box generator for the
// same bricks, and Euler-Bernoulli beam theory for the bending stress.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include <flexstress/fe/assembly.hpp>
#include <flexstress/fe/box_mesh.hpp>
#include <flexstress/fe/brick_locator.hpp>
#include <flexstress/fe/gmsh_reader.hpp>
#include <flexstress/fe/static_solver.hpp>
#include <flexstress/fe/stress_recovery.hpp>

namespace test_gmsh_reader {

using namespace flexstress;
using namespace flexstress::fe;

const std::string hand_written = FLEXSTRESS_TEST_SOURCE_DIR "/fe/gmsh/two_bricks.msh";

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Mesh index of the node with Gmsh tag `tag`.
Index node_of(const GmshImport& g, std::int64_t tag) {
  for (std::size_t i = 0; i < g.node_tags.size(); ++i)
    if (g.node_tags[i] == tag) return g.first_node + static_cast<Index>(i);
  return -1;
}

TEST_CASE("a hand-written MSH 4.1 file: nodes, bricks, physical groups, a read-out path") {
  Mesh mesh;
  const Index material = mesh.add_material(steel());
  mesh.add_node(Vector3d(5, 5, 5));  // the import appends to what is there
  auto g = read_gmsh_file(hand_written, mesh, material);
  REQUIRE_MESSAGE(g.ok(), g.error().what());

  // Twelve nodes (tags 101..112 in ascending order), appended after the existing node.
  CHECK(g->first_node == 1);
  CHECK(mesh.num_nodes() == 13);
  REQUIRE(g->node_tags.size() == 12);
  for (std::size_t i = 0; i < 12; ++i) CHECK(g->node_tags[i] == 101 + static_cast<int>(i));
  // Coordinates from each kind of block: a point entity, a parametric curve block, the volume.
  CHECK((mesh.node(node_of(*g, 108)) - Vector3d(1, 0.2, 0.1)).norm() == 0.0);
  CHECK((mesh.node(node_of(*g, 111)) - Vector3d(1, 0, 0)).norm() == 0.0);
  CHECK((mesh.node(node_of(*g, 112)) - Vector3d(0, 0.2, 0.1)).norm() == 0.0);

  // Connectivity as written (Gmsh's hexahedron order is Hex8Element's).
  REQUIRE(mesh.hexes().size() == 2);
  CHECK(g->hex_tags == std::vector<std::int64_t>{1, 2});
  const std::array<std::int64_t, 8> first = {107, 103, 105, 101, 102, 110, 106, 112};
  for (std::size_t a = 0; a < 8; ++a) CHECK(mesh.hexes()[0].nodes[a] == node_of(*g, first[a]));
  CHECK(mesh.hexes()[1].material == material);

  // Groups by dimension, then tag, with their names.
  REQUIRE(g->groups.size() == 4);
  const GmshGroup* corner = g->find("corner");
  const GmshGroup* edge = g->find("bottom edge");
  const GmshGroup* root = g->find("root");
  const GmshGroup* body = g->find("body");
  REQUIRE((corner && edge && root && body));
  CHECK(corner->dimension == 0);
  CHECK(corner->nodes == std::vector<Index>{node_of(*g, 108)});
  CHECK(root->dimension == 2);
  CHECK(root->nodes ==
        std::vector<Index>{node_of(*g, 101), node_of(*g, 102), node_of(*g, 107), node_of(*g, 112)});
  CHECK(body->hexes == std::vector<Index>{0, 1});
  CHECK(body->nodes.size() == 12);
  // The curve's two line elements are listed out of order; the path follows the curve from
  // x = 0 to x = 1, the direction of its elements.
  CHECK(edge->path == std::vector<Index>{node_of(*g, 107), node_of(*g, 103), node_of(*g, 111)});
  CHECK(root->path.empty());
  auto root_nodes = g->nodes_of("root");
  REQUIRE(root_nodes.ok());
  CHECK(*root_nodes == root->nodes);
  auto missing = g->nodes_of("tip");
  REQUIRE_FALSE(missing.ok());
  CHECK(missing.error().message ==
        "Gmsh import: no physical group named 'tip' (the file has 'corner', 'bottom edge', "
        "'root', 'body')");

  // The bricks' volume, 1.0 x 0.2 x 0.1 m: the mass matrix carries density x volume in each
  // translation (positive Jacobians everywhere, so the node order was understood).
  auto dofs = DofMap::build(mesh);
  REQUIRE(dofs.ok());
  auto m = assemble_mass(mesh, *dofs);
  REQUIRE(m.ok());
  VectorXd ex = VectorXd::Zero(dofs->size());
  for (Index n = g->first_node; n < mesh.num_nodes(); ++n) ex(dofs->dof(n, 0)) = 1.0;
  CHECK(ex.dot(*m * ex) == doctest::Approx(steel().density * 0.02).epsilon(1e-12));
}

struct Malformed {
  const char* what;
  const char* find;     ///< text of the valid file to replace ...
  const char* replace;  ///< ... by this
  const char* marker;   ///< the error names the line this text starts on in the changed file
  const char* message;  ///< and says this
};

TEST_CASE("malformed MSH files: errors name the file and the line; the mesh is not touched") {
  const std::string valid = read_text(hand_written);
  const Malformed cases[] = {
      {"old version", "4.1 0 8", "2.2 0 8", "2.2 0 8", "MSH version '2.2' is not supported"},
      {"binary", "4.1 0 8", "4.1 1 8", "4.1 1 8", "binary MSH files are not supported"},
      {"word for a number", "0.5 0.2 0.1\n", "0.5 abc 0.1\n", "0.5 abc",
       "expected a node coordinate (a number), found 'abc'"},
      {"NaN coordinate", "0 0.2 0\n", "nan 0.2 0\n", "nan 0.2", "a node coordinate is not finite"},
      {"node defined twice", "110\n112\n", "110\n101\n", "0 0.2 0.1\n$EndNodes",
       "node tag 101 (line 42) is defined twice"},
      {"node count", "3 12 101 112", "3 13 101 112", "3 13 101 112",
       "$Nodes announces 13 nodes but its blocks hold 12"},
      {"unterminated section", "$EndNodes", "$EndNode", "$EndNode",
       "expected $EndNodes, found '$EndNode'"},
      {"unterminated unknown section", "$EndComments", "$EndComment", "$Comments",
       "section $Comments has no $EndComments"},
      {"undefined node", "108 106\n$EndElements", "108 199\n$EndElements", "2 103 111",
       "element 2 refers to node 199, which $Nodes does not define"},
      {"tetrahedra", "3 1 5 2", "3 1 4 2", "3 1 4 2",
       "the block holds 4-node tetrahedron elements (type 4); flexstress imports 8-node "
       "hexahedra"},
      {"type on the wrong entity", "2 1 3 1", "2 1 5 1", "2 1 5 1",
       "a block of 8-node hexahedron elements (dimension 3) on an entity of dimension 2"},
      {"inverted brick", "1 107 103 105 101 102 110 106 112", "1 102 110 106 112 107 103 105 101",
       "1 102 110", "hexahedron 1 is inverted or flat"},
      {"brick using a node twice", "1 107 103 105 101 102 110 106 112",
       "1 107 103 105 101 102 110 106 107", "1 107 103", "hexahedron 1 uses node 107 twice"},
      {"group node off the volume mesh", "31 108", "31 113", "31 113",
       "element 31 of physical group 4 (dimension 0) has node 113, which is not a node of any "
       "hexahedron"},
      {"unquoted group name", "\"root\"", "root", "2 3 root",
       "expected the physical group's \"name\""},
      {"truncated", "106\n$EndElements\n", "", "2 103 111",
       "the file ends where an element's node tag was expected"},
      {"section before $MeshFormat", "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n", "", "$Comments",
       "the file must begin with $MeshFormat"},
  };
  for (const Malformed& c : cases) {
    const std::string what = c.what;
    CAPTURE(what);
    std::string text = valid;
    const std::size_t at = text.find(c.find);
    REQUIRE(at != std::string::npos);
    text.replace(at, std::string(c.find).size(), c.replace);
    const std::size_t marker = text.find(c.marker);
    REQUIRE(marker != std::string::npos);
    const long line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(marker), '\n');

    Mesh mesh;
    const Index material = mesh.add_material(steel());
    mesh.add_node(Vector3d::Zero());
    auto g = read_gmsh(text, mesh, material, "two_bricks.msh");
    REQUIRE_FALSE(g.ok());
    CHECK(g.error().code == ErrorCode::bad_file_format);
    const std::string where = "two_bricks.msh:" + std::to_string(line) + ": ";
    CHECK_MESSAGE(g.error().message.rfind(where, 0) == 0, g.error().message);
    CHECK_MESSAGE(g.error().message.find(c.message) != std::string::npos, g.error().message);
    CHECK(mesh.num_nodes() == 1);
    CHECK(mesh.hexes().empty());
  }

  Mesh mesh;
  const Index material = mesh.add_material(steel());
  SUBCASE("a file without hexahedra") {
    std::string text = valid;
    const std::size_t begin = text.find("3 1 5 2\n"), end = text.find("$EndElements");
    text.erase(begin, end - begin);
    text.replace(text.find("4 6 1 31"), 8, "3 4 1 31");
    auto g = read_gmsh(text, mesh, material, "two_bricks.msh");
    REQUIRE_FALSE(g.ok());
    CHECK(g.error().message ==
          "two_bricks.msh: no 8-node hexahedra (element type 5); flexstress imports hexahedral "
          "volume meshes");
  }
  SUBCASE("a material that does not exist") {
    auto g = read_gmsh(valid, mesh, 3, "two_bricks.msh");
    REQUIRE_FALSE(g.ok());
    CHECK(g.error().code == ErrorCode::invalid_argument);
    CHECK(g.error().message ==
          "Gmsh import of 'two_bricks.msh': material 3 does not exist (the mesh has 1 materials; "
          "add it first)");
  }
  SUBCASE("a file that does not exist") {
    auto g = read_gmsh_file("no/such/file.msh", mesh, material);
    REQUIRE_FALSE(g.ok());
    CHECK(g.error().code == ErrorCode::io_error);
    CHECK(g.error().message == "cannot open Gmsh file 'no/such/file.msh'");
  }
  SUBCASE("an empty file") {
    auto g = read_gmsh("", mesh, material, "empty.msh");
    REQUIRE_FALSE(g.ok());
    CHECK(g.error().message == "empty.msh:1: empty file: no $MeshFormat");
  }
  CHECK(mesh.num_nodes() == 0);
}

#ifdef FLEXSTRESS_TEST_GMSH_MESH

// A cantilever clamped (pinned nodes) at x = 0 and loaded by P at x = L, split equally over the
// tip face's nodes. Returns the nodal displacements and the stress at `p`.
struct Cantilever {
  VectorXd u;
  Vector6d stress_top;
};
Cantilever bend(const Mesh& mesh, const std::vector<Index>& root, const std::vector<Index>& tip,
                double p, const Vector3d& point) {
  BoundaryConditions bc;
  for (Index n : root) bc.pin(n);
  auto model = assemble(mesh, bc);
  REQUIRE(model.ok());
  auto solver = StaticSolver::factorize(mesh, *model);
  REQUIRE(solver.ok());
  std::vector<NodalLoad> loads;
  for (Index n : tip) loads.push_back({n, 2, -p / static_cast<double>(tip.size())});
  auto f = load_vector(model->dofs, loads);
  REQUIRE(f.ok());
  Cantilever c;
  c.u = solver->solve(*f);
  auto locator = BrickLocator::build(mesh);
  REQUIRE(locator.ok());
  auto s = stress_at_point(mesh, model->dofs, *locator, c.u, point);
  REQUIRE(s.ok());
  c.stress_top = *s;
  return c;
}

TEST_CASE("a mesh from Gmsh bends like the same bricks from add_box_mesh, and like a beam") {
  const double length = 0.4, width = 0.04, depth = 0.04, p = 1000.0;
  Mesh gmsh_mesh;
  auto g = read_gmsh_file(FLEXSTRESS_TEST_GMSH_MESH, gmsh_mesh, gmsh_mesh.add_material(steel()));
  REQUIRE_MESSAGE(g.ok(), g.error().what());
  CHECK(gmsh_mesh.num_nodes() == 9 * 3 * 3);
  CHECK(gmsh_mesh.hexes().size() == 8 * 2 * 2);
  auto root = g->nodes_of("root");
  auto tip = g->nodes_of("tip");
  REQUIRE((root.ok() && tip.ok()));
  CHECK(root->size() == 9);
  CHECK(tip->size() == 9);
  // The read-out line along the top edge: nine nodes in order along x.
  const GmshGroup* edge = g->find("top edge");
  REQUIRE(edge != nullptr);
  REQUIRE(edge->path.size() == 9);
  const double direction =
      gmsh_mesh.node(edge->path.back()).x() > gmsh_mesh.node(edge->path[0]).x() ? 1 : -1;
  for (std::size_t i = 1; i < edge->path.size(); ++i)
    CHECK(direction * (gmsh_mesh.node(edge->path[i]).x() - gmsh_mesh.node(edge->path[i - 1]).x()) ==
          doctest::Approx(length / 8));

  Mesh box_mesh;
  BoxMeshSpec spec;
  spec.origin = Vector3d(0, -width / 2, -depth / 2);
  spec.size = Vector3d(length, width, depth);
  spec.divisions = {8, 2, 2};
  spec.material = box_mesh.add_material(steel());
  const BoxMesh box = *add_box_mesh(box_mesh, spec);
  std::vector<Index> box_root, box_tip;
  for (int k = 0; k <= 2; ++k)
    for (int j = 0; j <= 2; ++j) {
      box_root.push_back(box.node(0, j, k));
      box_tip.push_back(box.node(8, j, k));
    }

  // Top surface, at the centre of a brick's top face (between nodes: the point is located and
  // interpolated inside the brick).
  const Vector3d top(0.225, 0.01, depth / 2);
  const Cantilever from_gmsh = bend(gmsh_mesh, *root, *tip, p, top);
  const Cantilever from_box = bend(box_mesh, box_root, box_tip, p, top);

  // Same bricks, other numbering: node by node the same displacements.
  std::map<std::array<long, 3>, Index> box_node;
  auto key = [](const Vector3d& x) {
    return std::array<long, 3>{std::lround(x.x() * 1e6), std::lround(x.y() * 1e6),
                               std::lround(x.z() * 1e6)};
  };
  for (Index n = 0; n < box_mesh.num_nodes(); ++n) box_node[key(box_mesh.node(n))] = n;
  double largest = 0.0, difference = 0.0;
  for (Index n = 0; n < gmsh_mesh.num_nodes(); ++n) {
    const auto it = box_node.find(key(gmsh_mesh.node(n)));
    REQUIRE(it != box_node.end());
    const Vector3d a = from_gmsh.u.segment<3>(3 * n), b = from_box.u.segment<3>(3 * it->second);
    largest = std::max(largest, b.norm());
    difference = std::max(difference, (a - b).norm());
  }
  MESSAGE("tip deflection ", largest * 1e3, " mm; largest difference ", difference / largest);
  CHECK(difference < 1e-10 * largest);
  CHECK((from_gmsh.stress_top - from_box.stress_top).norm() < 1e-10 * from_box.stress_top.norm());

  // Euler-Bernoulli: sigma_xx = M c / I at the top, M = P (L - x): tension on top for a load
  // along -z. An incompatible-mode brick bends with constant curvature along its length, so its
  // stress is the moment at its centre's; two through the depth make it linear across.
  const double moment = p * (length - top.x());
  const double second_moment = width * depth * depth * depth / 12.0;
  const double sigma = moment * (depth / 2) / second_moment;
  MESSAGE("top stress at x = ", top.x(), ": ", from_gmsh.stress_top(0) / 1e6, " MPa; beam theory ",
          sigma / 1e6, " MPa");
  CHECK(from_gmsh.stress_top(0) == doctest::Approx(sigma).epsilon(0.01));
}

#else

TEST_CASE("a mesh from Gmsh (skipped: the build found no gmsh program)") {
  MESSAGE("install Debian's gmsh to run the test that imports a mesh Gmsh made");
}

#endif

}  // namespace test_gmsh_reader
