// Sub-model inertia. References: statics of a cantilever under its own weight (the moment at
// x is q (L - x)^2 / 2 whatever the stiffness: statically determinate), Euler-Bernoulli bending
// stress M c / I; and the rigid-body kinematics a = a_O + alpha x x + omega x (omega x x)
// evaluated directly.
#include <cmath>
#include <optional>

#include <doctest/doctest.h>

#include <flexstress/fe/rhs_attachment_mesh.hpp>
#include <flexstress/stress/stress_outputs.hpp>
#include <flexstress/stress/sub_model.hpp>
#include <flexstress/stress/sub_model_inertia.hpp>

namespace test_sub_model_inertia {

using namespace flexstress;

namespace {

// A solid steel bar, L x h x b = 1.0 x 0.04 x 0.02 m (x, y, z), 40 x 4 x 2 bricks, its end
// x = 0 tied to one master (held: a cantilever).
struct Bar {
  static constexpr double L = 1.0, h = 0.04, b = 0.02;
  static constexpr int nx = 40, ny = 4, nz = 2;
  fe::Mesh mesh;
  std::vector<Index> root;
  Bar() {
    const Index mat = mesh.add_material(fe::steel());
    auto id = [](int i, int j, int k) { return Index(k + (nz + 1) * (j + (ny + 1) * i)); };
    for (int i = 0; i <= nx; ++i)
      for (int j = 0; j <= ny; ++j)
        for (int k = 0; k <= nz; ++k) {
          mesh.add_node(
              Vector3d(L * i / nx, h * (double(j) / ny - 0.5), b * (double(k) / nz - 0.5)));
          if (i == 0) root.push_back(id(i, j, k));
        }
    for (int i = 0; i < nx; ++i)
      for (int j = 0; j < ny; ++j)
        for (int k = 0; k < nz; ++k)
          mesh.add_hex8(
              {id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k), id(i, j, k + 1),
               id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)},
              mat);
  }
};

// The crane's detail: RHS 150x100x4 segment 0.5 to 0.8 m with its welded plate, both end
// sections tied to masters on the axis, density 0.6.
struct Detail {
  fe::RhsAttachmentMesh detail;
  std::optional<stress::SubModel> sub;
  Detail() {
    fe::RhsAttachmentSpec rs;
    rs.density = 0.6;
    auto d = fe::make_rhs_attachment_mesh(rs);
    REQUIRE(d.ok());
    detail = std::move(*d);
    auto s = stress::SubModel::build(detail.mesh, {{Vector3d(0.5, 0, 0), detail.end_section_x0},
                                                   {Vector3d(0.8, 0, 0), detail.end_section_x1}});
    REQUIRE(s.ok());
    sub.emplace(std::move(*s));
  }
};

}  // namespace

TEST_CASE("a cantilever's own weight, root held, gives the bending stress of statics") {
  Bar bar;
  auto sub = stress::SubModel::build(bar.mesh, {{Vector3d::Zero(), bar.root}});
  REQUIRE(sub.ok());
  const double g = 9.81, q = fe::steel().density * Bar::b * Bar::h * g;
  const double inertia = Bar::b * Bar::h * Bar::h * Bar::h / 12;
  stress::StressOutputs out;
  const double xs[] = {0.3125, 0.5125};  // brick centres, away from the root and the tip
  for (double x : xs) {
    out.add_normal_stress(Vector3d(x, -Bar::h / 2, 0.25 * Bar::b), Vector3d::UnitX());
    out.add_normal_stress(Vector3d(x, Bar::h / 2, 0.25 * Bar::b), Vector3d::UnitX());
  }
  auto inertia_rows = stress::SubModelInertia<>::build(*sub, out);
  REQUIRE(inertia_rows.ok());
  // At rest under gravity (0, -g, 0): the coordinates carry a_O - g = (0, g, 0).
  const auto coords = stress::inertia_coordinates<double>(Vector3d::Zero(), Vector3d(0, -g, 0),
                                                          Vector3d::Zero(), Vector3d::Zero());
  VectorXd y = VectorXd::Zero(4);
  inertia_rows->add_to(coords, y);
  for (int i = 0; i < 2; ++i) {
    const double moment = q * (Bar::L - xs[i]) * (Bar::L - xs[i]) / 2;  // hogging
    const double theory = moment * (Bar::h / 2) / inertia;              // top in tension
    MESSAGE("x = " << xs[i] << " m: bottom " << y(2 * i) / 1e3 << " kPa, top " << y(2 * i + 1) / 1e3
                   << " kPa; statics +-" << theory / 1e3 << " kPa");
    CHECK(y(2 * i) == doctest::Approx(-theory).epsilon(0.005));
    CHECK(y(2 * i + 1) == doctest::Approx(theory).epsilon(0.005));
  }
}

TEST_CASE(
    "the 12 inertia coordinates reproduce a direct solve for a rotating, accelerating frame") {
  Detail seg;  // at x = 0.5 to 0.8 m: alpha and omega act with lever arms
  const Vector3d a_o(0.3, -2.0, 0.7), gravity(0, -9.81, 0), omega(0.4, -1.1, 2.3),
      alpha(-3.0, 0.5, 1.7);
  const VectorXd direct = seg.sub->inertia_response([&](const Vector3d& x) {
    return Vector3d(a_o - gravity + alpha.cross(x) + omega.cross(omega.cross(x)));
  });
  const VectorXd combined =
      seg.sub->inertia_fields() * stress::inertia_coordinates<double>(a_o, gravity, omega, alpha);
  const double scale = direct.cwiseAbs().maxCoeff();
  MESSAGE("largest displacement " << scale << " m; difference " << (combined - direct).norm());
  CHECK(scale > 1e-8);
  CHECK((combined - direct).cwiseAbs().maxCoeff() <= 1e-10 * scale);
  // A rigid frame at rest without gravity loads nothing.
  const VectorXd none = seg.sub->inertia_response([](const Vector3d&) { return Vector3d::Zero(); });
  CHECK(none.cwiseAbs().maxCoeff() == 0.0);
}

}  // namespace test_sub_model_inertia
