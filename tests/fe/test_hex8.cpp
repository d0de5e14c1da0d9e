// Eight-node bricks (full integration and incompatible modes) and rigid links, against the
// MacNeal-Harder patch test (MacNeal & Harder, Finite Elements in Analysis and Design 1 (1985)
// 3-20) and Euler-Bernoulli beam theory for slender bending.
#include <cmath>

#include <doctest/doctest.h>

#include <flexstress/fe/assembly.hpp>
#include <flexstress/fe/static_solver.hpp>

namespace test_hex8 {

using namespace flexstress;
using namespace flexstress::fe;

namespace {

// Adds a brick whose faces are given as two quads (bottom, top). If the node order gives a
// negative Jacobian, the quads are reversed so the element is positively oriented.
Index add_oriented_hex(Mesh& mesh, std::array<Index, 4> bottom, std::array<Index, 4> top, Index mat,
                       Hex8Formulation f) {
  std::array<Index, 8> n{bottom[0], bottom[1], bottom[2], bottom[3],
                         top[0],    top[1],    top[2],    top[3]};
  Hex8Coordinates x;
  for (int a = 0; a < 8; ++a) x.col(a) = mesh.node(n[a]);
  const Matrix3d j = x * hex8::shape_derivatives(Vector3d::Zero()).transpose();
  if (j.determinant() < 0)
    n = {bottom[0], bottom[3], bottom[2], bottom[1], top[0], top[3], top[2], top[1]};
  return mesh.add_hex8(n, mat, f);
}

struct PatchTest {
  Mesh mesh;
  BoundaryConditions bc;
  explicit PatchTest(Hex8Formulation f) {
    Material m;
    m.youngs_modulus = 1e6;
    m.poissons_ratio = 0.25;
    m.density = 1.0;
    const Index mat = mesh.add_material(m);
    const double inner[8][3] = {{0.249, 0.342, 0.192}, {0.826, 0.288, 0.288}, {0.850, 0.649, 0.263},
                                {0.273, 0.750, 0.230}, {0.320, 0.186, 0.643}, {0.677, 0.305, 0.683},
                                {0.788, 0.693, 0.644}, {0.165, 0.745, 0.702}};
    for (int a = 0; a < 8; ++a)
      mesh.add_node(
          Vector3d(hex8::node_xi[a][0] + 1, hex8::node_xi[a][1] + 1, hex8::node_xi[a][2] + 1) *
          0.5);
    for (auto& p : inner) mesh.add_node(Vector3d(p[0], p[1], p[2]));
    // Inner node i sits near outer corner i. The inner brick, then one brick per cube face.
    mesh.add_hex8({8, 9, 10, 11, 12, 13, 14, 15}, mat, f);
    const std::array<std::array<Index, 4>, 6> faces{
        {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4}, {3, 2, 6, 7}, {0, 3, 7, 4}, {1, 2, 6, 5}}};
    for (const auto& face : faces)
      add_oriented_hex(mesh, face, {face[0] + 8, face[1] + 8, face[2] + 8, face[3] + 8}, mat, f);
    for (Index a = 0; a < 8; ++a) {
      const Vector3d x = mesh.node(a);
      bc.fix(a, 0, 1e-3 * (2 * x.x() + x.y() + x.z()) / 2);
      bc.fix(a, 1, 1e-3 * (x.x() + 2 * x.y() + x.z()) / 2);
      bc.fix(a, 2, 1e-3 * (x.x() + x.y() + 2 * x.z()) / 2);
    }
  }
};

}  // namespace

TEST_CASE("MacNeal-Harder patch test: constant strain and stress to machine precision") {
  for (auto f : {Hex8Formulation::full_integration, Hex8Formulation::incompatible_modes}) {
    CAPTURE(static_cast<int>(f));
    PatchTest pt(f);
    auto model = assemble(pt.mesh, pt.bc);
    REQUIRE(model.ok());
    auto solver = StaticSolver::factorize(pt.mesh, *model);
    REQUIRE(solver.ok());
    const VectorXd u = solver->solve(VectorXd::Zero(model->dofs.size()));
    // Published values: sigma_xx = sigma_yy = sigma_zz = 2000, shear 400, everywhere.
    double worst = 0.0;
    for (std::size_t e = 0; e < pt.mesh.hexes().size(); ++e) {
      const auto& h = pt.mesh.hexes()[e];
      Vector24d ue;
      for (int a = 0; a < 8; ++a)
        for (int c = 0; c < 3; ++c) ue(3 * a + c) = u(model->dofs.dof(h.nodes[a], c));
      for (const Vector3d& xi :
           {Vector3d(0, 0, 0), Vector3d(0.577, -0.3, 0.9), Vector3d(-1, 1, -1)}) {
        auto s = hex8_stress_operator(hex8_coordinates(pt.mesh, h), pt.mesh.material(0), f, xi,
                                      static_cast<Index>(e));
        REQUIRE(s.ok());
        const Vector6d sigma = *s * ue;
        Vector6d expected;
        expected << 2000, 2000, 2000, 400, 400, 400;
        worst = std::max(worst, (sigma - expected).cwiseAbs().maxCoeff());
      }
    }
    CHECK(worst < 1e-9 * 2000);
  }
}

TEST_CASE(
    "slender cantilever, one brick through the thickness: incompatible modes bend, full "
    "integration locks") {
  // L = 10, h = b = 0.5 (L / h = 20), 10 x 1 x 1 bricks (aspect ratio 2), nu = 0: clamp at x = 0,
  // tip shear P. Reference: Euler-Bernoulli P L^3 / (3 E I) plus Timoshenko shear P L / (k G A), k
  // = 5/6.
  const double l = 10, h = 0.5, e = 1e7, p = 10.0;
  const int ne = 10;  // element aspect ratio 2
  auto tip_deflection = [&](Hex8Formulation f, bool tip_moment) {
    Mesh mesh;
    Material m;
    m.youngs_modulus = e;
    m.poissons_ratio = 0.0;
    const Index mat = mesh.add_material(m);
    std::vector<std::array<Index, 4>> sections;
    for (int i = 0; i <= ne; ++i) {
      const double x = l * i / ne;
      sections.push_back({mesh.add_node(Vector3d(x, 0, 0)), mesh.add_node(Vector3d(x, h, 0)),
                          mesh.add_node(Vector3d(x, h, h)), mesh.add_node(Vector3d(x, 0, h))});
    }
    for (int i = 0; i < ne; ++i) {
      const auto& a = sections[i];
      const auto& b = sections[i + 1];
      mesh.add_hex8({a[0], b[0], b[1], a[1], a[3], b[3], b[2], a[2]}, mat, f);
    }
    BoundaryConditions bc;
    for (Index n : sections.front()) bc.pin(n);
    auto model = assemble(mesh, bc);
    REQUIRE(model.ok());
    auto solver = StaticSolver::factorize(mesh, *model);
    REQUIRE(solver.ok());
    std::vector<NodalLoad> loads;
    const auto& tip = sections.back();
    if (tip_moment) {  // couple: +x at y = h, -x at y = 0, moment p h... per pair of nodes
      for (int k : {1, 2}) loads.push_back({tip[k], 0, -p / 2});
      for (int k : {0, 3}) loads.push_back({tip[k], 0, p / 2});
    } else {
      for (Index n : tip) loads.push_back({n, 1, p / 4});
    }
    auto f_all = load_vector(model->dofs, loads);
    REQUIRE(f_all.ok());
    const VectorXd u = solver->solve(*f_all);
    double v = 0;
    for (Index n : tip) v += u(model->dofs.dof(n, 1)) / 4;
    return v;
  };
  const double inertia = h * h * h * h / 12, area = h * h, g = e / 2;
  const double eb = p * l * l * l / (3 * e * inertia);
  const double shear = p * l / (5.0 / 6.0 * g * area);
  const double im = tip_deflection(Hex8Formulation::incompatible_modes, false);
  const double full = tip_deflection(Hex8Formulation::full_integration, false);
  MESSAGE("tip shear: theory " << eb + shear << ", incompatible modes " << im
                               << ", full integration " << full);
  CHECK(im == doctest::Approx(eb + shear).epsilon(0.02));
  CHECK(full < 0.5 * (eb + shear));  // shear locking
  // Pure bending (tip couple M = p h): incompatible modes reproduce it exactly on rectangles.
  const double moment = p * h;
  const double exact = moment * l * l / (2 * e * inertia);
  const double im_m = tip_deflection(Hex8Formulation::incompatible_modes, true);
  const double full_m = tip_deflection(Hex8Formulation::full_integration, true);
  MESSAGE("tip moment: theory " << exact << ", incompatible modes " << im_m << ", full " << full_m);
  CHECK(im_m == doctest::Approx(exact).epsilon(1e-9));
  // The trilinear brick's parasitic shear stiffens pure bending by exactly 1 + a^2 / 2 for
  // element aspect ratio a = 2 and nu = 0 (the same factor as the bilinear quad: Cook, Malkus,
  // Plesha, Witt, Concepts and Applications of FEA, 4th ed., sec. 6.13).
  const double aspect = (l / ne) / h;
  CHECK(full_m == doctest::Approx(exact / (1 + aspect * aspect / 2)).epsilon(1e-9));
}

TEST_CASE("rigid link (RBE2): rigid motion of the master gives zero strain") {
  // A 3 x 1 x 1 block of bricks hangs from a master node through an RBE2 on its x = 0 face;
  // the master gets a finite-looking small rigid motion, nothing else is loaded.
  Mesh mesh;
  const Index mat = mesh.add_material(steel());
  std::vector<std::array<Index, 4>> sec;
  for (int i = 0; i <= 3; ++i)
    sec.push_back({mesh.add_node(Vector3d(i, 0, 0)), mesh.add_node(Vector3d(i, 1, 0)),
                   mesh.add_node(Vector3d(i, 1, 1)), mesh.add_node(Vector3d(i, 0, 1))});
  for (int i = 0; i < 3; ++i)
    mesh.add_hex8({sec[i][0], sec[i + 1][0], sec[i + 1][1], sec[i][1], sec[i][3], sec[i + 1][3],
                   sec[i + 1][2], sec[i][2]},
                  mat);
  const Index master = mesh.add_node(Vector3d(-0.5, 0.5, 0.5));
  mesh.add_rigid_link(master, {sec[0].begin(), sec[0].end()});
  BoundaryConditions bc;
  const double motion[6] = {1e-3, -2e-3, 0.5e-3, 1e-3, 2e-3, -1.5e-3};
  for (int c = 0; c < 6; ++c) bc.fix(master, c, motion[c]);
  auto model = assemble(mesh, bc);
  REQUIRE(model.ok());
  auto solver = StaticSolver::factorize(mesh, *model);
  REQUIRE(solver.ok());
  const VectorXd u = solver->solve(VectorXd::Zero(model->dofs.size()));
  const Vector3d t(motion[0], motion[1], motion[2]), r(motion[3], motion[4], motion[5]);
  for (Index n = 0; n < mesh.num_nodes(); ++n) {
    const Vector3d expected = t + r.cross(Vector3d(mesh.node(n) - mesh.node(master)));
    Vector3d got;
    for (int c = 0; c < 3; ++c) got(c) = u(model->dofs.dof(n, c));
    CHECK((got - expected).norm() < 1e-15);
  }
  for (std::size_t e = 0; e < mesh.hexes().size(); ++e) {
    const auto& h = mesh.hexes()[e];
    Vector24d ue;
    for (int a = 0; a < 8; ++a)
      for (int c = 0; c < 3; ++c) ue(3 * a + c) = u(model->dofs.dof(h.nodes[a], c));
    auto s = hex8_stress_operator(hex8_coordinates(mesh, h), mesh.material(0), h.formulation,
                                  Vector3d(0.3, -0.2, 0.1), static_cast<Index>(e));
    REQUIRE(s.ok());
    // Linearized rigid rotation: zero strain exactly (stress relative to E * |motion|).
    CHECK((*s * ue).norm() < 1e-12 * 210e9 * 2e-3);
  }
}

TEST_CASE("bad brick and link input gets a clear error") {
  Mesh mesh;
  const Index mat = mesh.add_material(steel());
  std::array<Index, 8> n{};
  for (int a = 0; a < 8; ++a)
    n[a] = mesh.add_node(Vector3d(hex8::node_xi[a][0], hex8::node_xi[a][1], hex8::node_xi[a][2]));
  SUBCASE("inverted brick") {
    mesh.add_hex8({n[4], n[5], n[6], n[7], n[0], n[1], n[2], n[3]}, mat);
    auto r = assemble(mesh);
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().code == ErrorCode::degenerate_element);
    CHECK(r.error().message.find("hex8 element 0: Jacobian determinant") != std::string::npos);
  }
  SUBCASE("flat brick") {
    std::array<Index, 8> flat{};
    for (int a = 0; a < 8; ++a)
      flat[a] = mesh.add_node(Vector3d(hex8::node_xi[a][0], hex8::node_xi[a][1], 0.0));
    mesh.add_hex8(flat, mat);
    auto r = assemble(mesh);
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().code == ErrorCode::degenerate_element);
  }
  SUBCASE("rigid link loop") {
    mesh.add_hex8(n, mat);
    const Index m1 = mesh.add_node(Vector3d(5, 0, 0)), m2 = mesh.add_node(Vector3d(6, 0, 0));
    mesh.add_rigid_link(m1, {m2});
    mesh.add_rigid_link(m2, {m1});
    auto r = assemble(mesh);
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().message.find("loop of rigid links") != std::string::npos);
  }
  SUBCASE("node slaved to two links") {
    mesh.add_hex8(n, mat);
    const Index m1 = mesh.add_node(Vector3d(5, 0, 0)), m2 = mesh.add_node(Vector3d(6, 0, 0));
    mesh.add_rigid_link(m1, {n[0]});
    mesh.add_rigid_link(m2, {n[0]});
    auto r = assemble(mesh);
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().message.find("node 0 is a slave of rigid links 0 and 1") != std::string::npos);
  }
  SUBCASE("prescribed slave DOF") {
    mesh.add_hex8(n, mat);
    const Index m1 = mesh.add_node(Vector3d(5, 0, 0));
    mesh.add_rigid_link(m1, {n[0]});
    BoundaryConditions bc;
    bc.fix(n[0], 1);
    auto r = assemble(mesh, bc);
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().message.find("rigid link 0 drives") != std::string::npos);
  }
  SUBCASE("unsupported brick: all six rigid motions free") {
    mesh.add_hex8(n, mat);
    auto model = assemble(mesh);
    REQUIRE(model.ok());
    auto s = StaticSolver::factorize(mesh, *model);
    REQUIRE_FALSE(s.ok());
    for (const char* motion : {"translation along x", "translation along y", "translation along z",
                               "rotation about x", "rotation about y", "rotation about z"})
      CHECK(s.error().message.find(motion) != std::string::npos);
  }
}

}  // namespace test_hex8
