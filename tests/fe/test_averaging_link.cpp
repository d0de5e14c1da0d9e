// Averaging links (RBE3). References: the definition itself, the weighted least-squares rigid
// fit of the face (solved here independently by QR of the stacked equations), the static
// equivalence of the face forces it implies (MSC Nastran Quick Reference Guide, RBE3: the
// reference load is distributed as forces of a rigid-body fit, equal shares for equal weights
// and a force through the centroid), and Timoshenko beam theory for a brick cantilever.
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include <Eigen/QR>

#include <flexstress/core/skew.hpp>
#include <flexstress/fe/assembly.hpp>
#include <flexstress/fe/box_mesh.hpp>
#include <flexstress/fe/static_solver.hpp>
#include <flexstress/reduction/interface.hpp>

namespace test_averaging_link {

using namespace flexstress;
using namespace flexstress::fe;

namespace {

// A brick cantilever 1.0 x 0.1 x 0.1 along x (nx x 2 x 2 bricks), its two end faces.
struct Bar {
  Mesh mesh;
  BoxMesh box;
  std::vector<Index> root, tip;
  explicit Bar(int nx = 12) {
    BoxMeshSpec spec;
    spec.origin = Vector3d(0, -0.05, -0.05);
    spec.size = Vector3d(1.0, 0.1, 0.1);
    spec.divisions = {nx, 2, 2};
    spec.material = mesh.add_material(steel());
    box = *add_box_mesh(mesh, spec);
    for (int k = 0; k <= 2; ++k)
      for (int j = 0; j <= 2; ++j) {
        root.push_back(box.node(0, j, k));
        tip.push_back(box.node(nx, j, k));
      }
  }
};

// Weighted least-squares rigid fit of face displacements: min sum w_i |u_i - a - theta x r_i|^2,
// by QR of the stacked, weighted equations (a different algorithm from the library's normal
// equations).
Vec6<double> rigid_fit(const std::vector<Vector3d>& r, const std::vector<Vector3d>& u,
                       const std::vector<double>& w) {
  const Index n = static_cast<Index>(r.size());
  MatrixXd a(3 * n, 6);
  VectorXd b(3 * n);
  for (Index i = 0; i < n; ++i) {
    const double s = std::sqrt(w[static_cast<std::size_t>(i)]);
    a.block<3, 3>(3 * i, 0) = s * Matrix3d::Identity();
    a.block<3, 3>(3 * i, 3) = -s * skew(r[static_cast<std::size_t>(i)]);
    b.segment<3>(3 * i) = s * u[static_cast<std::size_t>(i)];
  }
  return a.colPivHouseholderQr().solve(b);
}

}  // namespace

TEST_CASE(
    "an averaging link's reference follows the weighted least-squares rigid fit of its face") {
  Bar bar(2);
  std::vector<double> weights;
  for (std::size_t i = 0; i < bar.tip.size(); ++i) weights.push_back(0.5 + 0.25 * double(i % 4));
  const Index ref = bar.mesh.add_node(Vector3d(1.1, 0.02, -0.01));  // off the face, on purpose
  bar.mesh.add_averaging_link(ref, bar.tip, weights);
  auto model = assemble(bar.mesh);
  REQUIRE(model.ok());
  const auto& dofs = model->dofs;
  const auto& ct = model->constraints;
  CHECK(dofs.num_node_dofs(ref) == 6);
  CHECK(ct.num_free() == dofs.size() - 6);  // six face DOFs depend on the others

  // Any free values: the face moves as it likes, the reference is its fit.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  VectorXd u_free(ct.num_free());
  for (Index i = 0; i < u_free.size(); ++i) u_free(i) = uniform(rng);
  const VectorXd u = ct.expand(u_free);
  std::vector<Vector3d> r, uf;
  for (Index f : bar.tip) {
    r.push_back(bar.mesh.node(f) - bar.mesh.node(ref));
    uf.push_back(u.segment<3>(dofs.dof(f, 0)));
  }
  const Vec6<double> fit = rigid_fit(r, uf, weights);
  const Vec6<double> u_ref = u.segment<6>(dofs.dof(ref, 0));
  MESSAGE("reference DOFs against the least-squares fit: " << (u_ref - fit).norm());
  CHECK((u_ref - fit).norm() < 1e-12 * fit.norm());

  // A rigid motion of the reference moves a rigid face rigidly: the dependent DOFs agree.
  const Vector3d a(0.3, -0.2, 0.1), theta(0.05, -0.02, 0.04);
  VectorXd rigid_all(dofs.size());
  for (Index n = 0; n < bar.mesh.num_nodes(); ++n) {
    if (dofs.num_node_dofs(n) == 0) continue;
    rigid_all.segment<3>(dofs.dof(n, 0)) =
        a + theta.cross(Vector3d(bar.mesh.node(n) - bar.mesh.node(ref)));
    if (dofs.has_rotations(n)) rigid_all.segment<3>(dofs.dof(n, 3)) = theta;
  }
  VectorXd rigid_free(ct.num_free());
  for (Index i = 0; i < ct.num_free(); ++i)
    rigid_free(i) = rigid_all(ct.free_dofs()[std::size_t(i)]);
  CHECK((ct.expand(rigid_free) - rigid_all).cwiseAbs().maxCoeff() < 1e-13);
}

TEST_CASE("a force at the reference reaches the face in equal shares; the face is not stiffened") {
  // Cantilever pinned at every root node, tip load P along -y at the tip face's centroid:
  // through an averaging link, through a rigid link, and as equal nodal forces P/9 on the nine
  // tip nodes without any link.
  const double p = 1000.0;
  enum class Tip { averaging, rigid, nodal_forces };
  struct TipSolution {
    Vec6<double> reference;  ///< the link's reference DOFs, or the fit of the loaded face
    VectorXd face_forces;    ///< the bricks' internal forces at the tip-face nodes
  };
  auto solve = [&](Tip tip) {
    Bar bar;
    const Vector3d centroid = reduction::face_centroid(bar.mesh, bar.tip);
    Index ref = -1;
    if (tip == Tip::averaging) ref = reduction::add_averaging_spider(bar.mesh, bar.tip);
    if (tip == Tip::rigid) ref = reduction::add_rigid_spider(bar.mesh, bar.tip);
    BoundaryConditions bc;
    for (Index n : bar.root) bc.pin(n);
    auto model = assemble(bar.mesh, bc);
    REQUIRE(model.ok());
    auto solver = StaticSolver::factorize(bar.mesh, *model);
    REQUIRE(solver.ok());
    std::vector<NodalLoad> loads;
    if (ref >= 0)
      loads.push_back({ref, 1, -p});
    else
      for (Index n : bar.tip) loads.push_back({n, 1, -p / 9});
    auto f = load_vector(model->dofs, loads);
    REQUIRE(f.ok());
    const VectorXd u = solver->solve(*f);
    const VectorXd internal = model->stiffness_all * u;
    TipSolution r;
    r.face_forces.resize(3 * static_cast<Index>(bar.tip.size()));
    std::vector<Vector3d> offsets, displacements;
    for (std::size_t i = 0; i < bar.tip.size(); ++i) {
      const Index d = model->dofs.dof(bar.tip[i], 0);
      r.face_forces.segment<3>(3 * static_cast<Index>(i)) = internal.segment<3>(d);
      offsets.push_back(bar.mesh.node(bar.tip[i]) - centroid);
      displacements.push_back(u.segment<3>(d));
    }
    r.reference = ref >= 0 ? Vec6<double>(u.segment<6>(model->dofs.dof(ref, 0)))
                           : rigid_fit(offsets, displacements, std::vector<double>(9, 1.0));
    return r;
  };
  const TipSolution averaging = solve(Tip::averaging), rigid = solve(Tip::rigid),
                    nodal = solve(Tip::nodal_forces);

  // Equal shares: each of the 9 face nodes carries -P/9 along y and nothing else.
  VectorXd expected = VectorXd::Zero(averaging.face_forces.size());
  for (Index i = 0; i < expected.size() / 3; ++i) expected(3 * i + 1) = -p / 9;
  MESSAGE("face forces, largest deviation from -P/9 each: averaging link "
          << (averaging.face_forces - expected).cwiseAbs().maxCoeff() << " N, rigid link "
          << (rigid.face_forces - expected).cwiseAbs().maxCoeff() << " N");
  CHECK((averaging.face_forces - expected).cwiseAbs().maxCoeff() < 1e-9 * p);
  CHECK((rigid.face_forces - expected).cwiseAbs().maxCoeff() > 1e-3 * p);  // the test can tell
  // So the averaging link's reference moves exactly as the least-squares fit of a face loaded by
  // those nodal forces without any link (all six DOFs).
  MESSAGE("reference DOFs against the fit of the nodally loaded face: "
          << (averaging.reference - nodal.reference).norm() << " of " << nodal.reference.norm());
  CHECK((averaging.reference - nodal.reference).norm() < 1e-9 * nodal.reference.norm());

  // Beam theory, for scale: Timoshenko, P L^3 / (3 E I) + P L / (k G A), k = 5/6. The pinned
  // root also holds the Poisson contraction there, so the brick bar is a little stiffer than the
  // beam (2.0 % here, with either link); the rigid link stiffens the tip face a little more.
  const Material steel_ = steel();
  const double h = 0.1, area = h * h, i_z = h * h * h * h / 12.0;
  const double theory =
      p / (3 * steel_.youngs_modulus * i_z) + p / (5.0 / 6.0 * steel_.shear_modulus() * area);
  const double v_averaging = -averaging.reference(1), v_rigid = -rigid.reference(1);
  MESSAGE("tip deflection: averaging link " << v_averaging << " m, rigid link " << v_rigid
                                            << " m, Timoshenko " << theory << " m");
  CHECK(v_averaging > v_rigid);
  CHECK(v_averaging == doctest::Approx(theory).epsilon(0.03));
}

TEST_CASE("averaging links: bad input gets a clear error naming the link") {
  auto error_of = [](const std::function<void(Bar&)>& edit, const BoundaryConditions& bc = {}) {
    Bar bar(2);
    edit(bar);
    auto model = assemble(bar.mesh, bc);
    REQUIRE_FALSE(model.ok());
    MESSAGE(model.error().what());
    return model.error().message;
  };
  const auto contains = [](const std::string& s, const char* part) {
    return s.find(part) != std::string::npos;
  };
  // Three face nodes on one line: the rotation about that line is undefined.
  CHECK(contains(error_of([](Bar& b) {
                   b.mesh.add_averaging_link(b.mesh.add_node(Vector3d(2, 0, 0)),
                                             {b.tip[0], b.tip[1], b.tip[2]});
                 }),
                 "averaging link 0: its 3 face nodes do not define a rotation"));
  CHECK(contains(error_of([](Bar& b) {
                   b.mesh.add_averaging_link(b.mesh.add_node(Vector3d(2, 0, 0)), b.tip,
                                             std::vector<double>(b.tip.size(), -1.0));
                 }),
                 "averaging link 0: weight -1 of face node"));
  CHECK(contains(error_of([](Bar& b) {
                   b.mesh.add_averaging_link(b.mesh.add_node(Vector3d(2, 0, 0)), b.tip, {1.0});
                 }),
                 "averaging link 0 has 1 weights for 9 face nodes"));
  CHECK(contains(error_of([](Bar& b) { b.mesh.add_averaging_link(b.tip[0], b.tip); }),
                 "is both its reference and a face node"));
  CHECK(contains(error_of([](Bar& b) {
                   auto face = b.tip;
                   face.push_back(b.tip[3]);
                   b.mesh.add_averaging_link(b.mesh.add_node(Vector3d(2, 0, 0)), face);
                 }),
                 "lists face node"));
  CHECK(contains(error_of([](Bar& b) { b.mesh.add_averaging_link(99, b.tip); }),
                 "averaging link 0 has reference node 99, which does not exist"));
  // A face whose nodes are all held: nothing is left for the reference to follow.
  {
    BoundaryConditions bc;
    Bar probe(2);
    for (Index n : probe.root) bc.pin(n);
    CHECK(contains(
        error_of(
            [](Bar& b) { b.mesh.add_averaging_link(b.mesh.add_node(Vector3d(-1, 0, 0)), b.root); },
            bc),
        "too few of its face DOFs are free"));
  }
}

}  // namespace test_averaging_link
