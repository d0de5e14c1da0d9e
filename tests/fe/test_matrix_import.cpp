// Import of stiffness and mass matrices assembled by other FE programs: Abaqus's *MATRIX
// GENERATE text output with the *NODE block of its input file, and Nastran DMIG bulk data with
// GRID cards. References: the formats as their manuals describe them (the hand-written files in
// tests/fe/matrix_import follow them), the two-mass oscillator (w^2 = k / m with one end held),
// and flexstress's own brick assembly of the same body written out in both formats: the
// imported body must reduce to the same modal body, and its mass is rho V.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include <flexstress/fe/abaqus_matrix_reader.hpp>
#include <flexstress/fe/assembly.hpp>
#include <flexstress/fe/box_mesh.hpp>
#include <flexstress/fe/eigen_solver.hpp>
#include <flexstress/fe/nastran_dmig_reader.hpp>
#include <flexstress/fe/static_solver.hpp>
#include <flexstress/reduction/modal_body_data.hpp>

namespace test_matrix_import {

using namespace flexstress;
using namespace flexstress::fe;

const std::string dir = FLEXSTRESS_TEST_SOURCE_DIR "/fe/matrix_import/";

// The bushing (bushing.inp): k = 2e6 N/m in every direction between nodes 101 and 205, 5 kg at
// each. Held at 101, node 205 is a 5 kg mass on a 2e6 N/m spring: w^2 = k / m = 4e5 in x, y, z,
// and a load F moves it F / k.
void check_bushing(const LabeledModel& model) {
  Mesh mesh;
  auto imported = add_labeled_model(mesh, model);
  REQUIRE_MESSAGE(imported.ok(), imported.error().what());
  REQUIRE(mesh.num_nodes() == 2);
  const Index a = imported->node(101), b = imported->node(205);
  CHECK(a == 0);
  CHECK(b == 1);
  CHECK(imported->node(999) == -1);
  CHECK((mesh.node(b) - Vector3d(0.5, 0, 0)).norm() == 0.0);
  BoundaryConditions bc;
  bc.pin(a);
  auto assembled = assemble(mesh, bc);
  REQUIRE_MESSAGE(assembled.ok(), assembled.error().what());
  auto solver = StaticSolver::factorize(mesh, *assembled);
  REQUIRE(solver.ok());
  VectorXd f = VectorXd::Zero(assembled->dofs.size());
  f.segment<3>(assembled->dofs.dof(b, 0)) = Vector3d(100, -200, 300);
  const VectorXd u = solver->solve(f);
  CHECK((u.segment<3>(assembled->dofs.dof(b, 0)) - Vector3d(100, -200, 300) / 2e6).norm() < 1e-18);
  EigenOptions eig;
  eig.num_modes = 3;
  auto modes = solve_eigen(assembled->stiffness, assembled->mass, eig);
  REQUIRE(modes.ok());
  for (int i = 0; i < 3; ++i) CHECK(modes->eigenvalues(i) == doctest::Approx(4e5).epsilon(1e-12));
}

TEST_CASE("hand-written Abaqus matrix files and *NODE block: the bushing") {
  LabeledModel model;
  REQUIRE(read_abaqus_nodes_file(dir + "bushing.inp", model).ok());
  REQUIRE(
      read_abaqus_matrix_file(dir + "bushing_STIF1.mtx", ImportedMatrix::stiffness, model).ok());
  REQUIRE(read_abaqus_matrix_file(dir + "bushing_MASS1.mtx", ImportedMatrix::mass, model).ok());
  CHECK(model.coordinates.size() == 2);
  CHECK(model.stiffness.size() == 9);
  CHECK(model.mass.size() == 6);
  check_bushing(model);
}

TEST_CASE("hand-written Nastran bulk data (small and free field, continuations): the bushing") {
  LabeledModel model;
  const Status st = read_nastran_bulk_file(dir + "bushing.bdf", "kaax", "MAAX", model);
  REQUIRE_MESSAGE(st.ok(), st.error().what());
  CHECK(model.coordinates.size() == 2);
  CHECK(model.stiffness.size() == 9);
  CHECK(model.mass.size() == 6);
  check_bushing(model);
}

namespace {

// A steel cantilever of bricks (0.6 x 0.06 x 0.04 m, 12 x 2 x 2 hex8) assembled by flexstress.
struct Bar {
  Mesh mesh;
  BoxMesh box;
};
Bar make_bar() {
  Bar bar;
  BoxMeshSpec spec;
  spec.size = Vector3d(0.6, 0.06, 0.04);
  spec.divisions = {12, 2, 2};
  spec.material = bar.mesh.add_material(steel());
  auto box = add_box_mesh(bar.mesh, spec);
  REQUIRE(box.ok());
  bar.box = *box;
  return bar;
}

// Node labels as another program would number them: 1000 + 7 * index.
long long label_of(Index node) {
  return 1000 + 7 * node;
}

// The bar's all-DOF matrices written as Abaqus does (lower triangle) and as Nastran DMIG
// free-field cards (upper triangle by columns), with 17 significant digits.
struct Written {
  std::string inp, stiffness_mtx, mass_mtx, bdf;
};
Written write_bar(const Mesh& mesh) {
  auto assembled = assemble(mesh);
  REQUIRE(assembled.ok());
  const DofMap& dofs = assembled->dofs;
  Written w;
  std::ostringstream inp, bdf;
  inp.precision(17);
  bdf.precision(17);
  inp << "*Node\n";
  bdf << "BEGIN BULK\n";
  for (Index n = 0; n < mesh.num_nodes(); ++n) {
    const Vector3d& x = mesh.node(n);
    inp << label_of(n) << ", " << x.x() << ", " << x.y() << ", " << x.z() << "\n";
    bdf << "GRID," << label_of(n) << ",," << x.x() << "," << x.y() << "," << x.z() << "\n";
  }
  const auto write = [&](const SparseMatrixd& a, const char* name, std::string& mtx) {
    std::ostringstream out;
    out.precision(17);
    bdf << "DMIG," << name << ",0,6,2,,,," << a.cols() << "\n";
    for (Index col = 0; col < a.outerSize(); ++col) {
      // One DMIG card per column, its entries on continuation lines of four fields each.
      bdf << "DMIG," << name << "," << label_of(dofs.node_of(col)) << ","
          << dofs.component_of(col) + 1 << ",\n";
      for (SparseMatrixd::InnerIterator it(a, col); it; ++it) {
        const Index row = it.row();
        if (row < col) continue;  // one triangle
        const long long nr = label_of(dofs.node_of(row)), nc = label_of(dofs.node_of(col));
        const int cr = dofs.component_of(row) + 1, cc = dofs.component_of(col) + 1;
        out << nr << ", " << cr << ", " << nc << ", " << cc << ", " << it.value() << "\n";
        bdf << "+," << nr << "," << cr << "," << it.value() << ",\n";
      }
    }
    mtx = out.str();
  };
  write(assembled->stiffness_all, "KAAX", w.stiffness_mtx);
  write(assembled->mass_all, "MAAX", w.mass_mtx);
  bdf << "ENDDATA\n";
  w.inp = inp.str();
  w.bdf = bdf.str();
  return w;
}

// Craig-Bampton with the root face tied to an interface node by a rigid link, 4 fixed-interface
// modes: the same reduction for the native and the imported bar.
Result<reduction::ModalBodyData> reduce_bar(Mesh& mesh, const std::vector<Index>& root_face) {
  const Index hub = mesh.add_node(Vector3d(0, 0.03, 0.02));
  mesh.add_rigid_link(hub, root_face);
  reduction::ReductionSpec spec;
  spec.interface = {reduction::InterfaceNode{hub}};
  spec.dynamic_modes.count = 4;
  return reduction::reduce(mesh, spec);
}

std::vector<Index> root_face(const BoxMesh& box) {
  std::vector<Index> face;
  for (int k = 0; k <= 2; ++k)
    for (int j = 0; j <= 2; ++j) face.push_back(box.node(0, j, k));
  return face;
}

}  // namespace

TEST_CASE("a brick body written in both formats imports to the same modal body") {
  Bar bar = make_bar();
  const Written written = write_bar(bar.mesh);
  const std::vector<Index> face = root_face(bar.box);
  auto native = reduce_bar(bar.mesh, face);
  REQUIRE_MESSAGE(native.ok(), native.error().what());
  // Steel, 7850 kg/m^3: rho V.
  CHECK(native->mass() == doctest::Approx(7850 * 0.6 * 0.06 * 0.04).epsilon(1e-12));
  // Its first free-free bending mode (about y, the 0.04 m depth) against Euler-Bernoulli:
  // f = (4.7300)^2 / (2 pi L^2) sqrt(E I / (rho A)).
  const Material& steel_material = bar.mesh.material(0);
  const double ei = steel_material.youngs_modulus * 0.06 * std::pow(0.04, 3) / 12;
  const double beam_theory = std::pow(4.730040745, 2) / (2 * M_PI * 0.36) *
                             std::sqrt(ei / (steel_material.density * 0.06 * 0.04));
  CHECK(std::sqrt(native->eigenvalues(0)) / (2 * M_PI) ==
        doctest::Approx(beam_theory).epsilon(0.01));

  for (const char* format : {"Abaqus", "Nastran"}) {
    CAPTURE(format);
    LabeledModel model;
    if (std::string(format) == "Abaqus") {
      REQUIRE(read_abaqus_nodes(written.inp, model, "bar.inp").ok());
      REQUIRE(read_abaqus_matrix(written.stiffness_mtx, ImportedMatrix::stiffness, model,
                                 "bar_STIF1.mtx")
                  .ok());
      REQUIRE(
          read_abaqus_matrix(written.mass_mtx, ImportedMatrix::mass, model, "bar_MASS1.mtx").ok());
    } else {
      const Status st = read_nastran_bulk(written.bdf, "KAAX", "MAAX", model, "bar.bdf");
      REQUIRE_MESSAGE(st.ok(), st.error().what());
    }
    Mesh mesh;
    auto imported = add_labeled_model(mesh, model);
    REQUIRE_MESSAGE(imported.ok(), imported.error().what());
    CHECK(mesh.num_nodes() == bar.box.node(12, 2, 2) + 1);
    std::vector<Index> imported_face;
    for (Index n : face) imported_face.push_back(imported->node(label_of(n)));
    auto body = reduce_bar(mesh, imported_face);
    REQUIRE_MESSAGE(body.ok(), body.error().what());
    REQUIRE(body->num_modes == native->num_modes);
    CHECK(body->mass() == doctest::Approx(native->mass()).epsilon(1e-13));
    CHECK((body->center_of_mass() - native->center_of_mass()).norm() < 1e-14);
    CHECK((body->inertia_about_origin() - native->inertia_about_origin()).norm() <
          1e-12 * native->inertia_about_origin().norm());
    double worst = 0;
    for (Index i = 0; i < native->num_modes; ++i) {
      CHECK(body->eigenvalues(i) == doctest::Approx(native->eigenvalues(i)).epsilon(1e-9));
      worst = std::max(worst, std::abs(body->eigenvalues(i) / native->eigenvalues(i) - 1));
    }
    MESSAGE(std::string(format) << ": " << body->num_modes << " modes, first "
                                << std::sqrt(native->eigenvalues(0)) / (2 * M_PI)
                                << " Hz, eigenvalues within " << worst << ", mass " << body->mass()
                                << " kg (native " << native->mass() << ")");
    // Every second moment of the modes (the FFRF mass matrix's building blocks), sign-free.
    for (Index a = 1; a <= native->num_modes; ++a)
      CHECK(body->inertia.lambda(a, a).trace() ==
            doctest::Approx(native->inertia.lambda(a, a).trace()).epsilon(1e-8));
  }
}

TEST_CASE("bad matrix files: errors name the file, the line and what is wrong") {
  const auto abaqus = [](const std::string& text) {
    LabeledModel model;
    return read_abaqus_matrix(text, ImportedMatrix::stiffness, model, "k.mtx");
  };
  const auto message = [](const Status& s) { return s.ok() ? std::string() : s.error().what(); };
  CHECK(
      message(abaqus("** header\n1, 1, 1, 1\n"))
          .find("k.mtx:2: expected 'row node, row DOF, column node, column DOF, value', got '1, 1, "
                "1, 1'") != std::string::npos);
  CHECK(message(abaqus("1, 7, 1, 1, 2.0\n")).find("k.mtx:1: DOF 7 is not an Abaqus DOF") !=
        std::string::npos);
  CHECK(message(abaqus("1, 1, 1, 1, 2.0x\n")).find("k.mtx:1: expected") != std::string::npos);
  CHECK(message(abaqus("** nothing\n")).find("k.mtx: no matrix entries") != std::string::npos);
  {
    LabeledModel model;
    CHECK(message(read_abaqus_nodes("*Node\n1, 0, 0, 0\n2, 1, 0\n1, 2, 0, 0\n", model, "a.inp"))
              .find("a.inp:4: node 1 is defined twice (first at line 2)") != std::string::npos);
    CHECK(message(read_abaqus_nodes("*Node\n1, 0, zero, 0\n", model, "a.inp"))
              .find("a.inp:2: expected a *NODE line 'label, x, y[, z]'") != std::string::npos);
    CHECK(model.coordinates.empty());  // all or nothing
  }
  const auto nastran = [](const std::string& text) {
    LabeledModel model;
    return read_nastran_bulk(text, "KAAX", "", model, "k.bdf");
  };
  CHECK(message(nastran("GRID*   1\n")).find("k.bdf:1: large-field card GRID* is not supported") !=
        std::string::npos);
  CHECK(message(nastran("GRID,1,2,0.,0.,0.\nDMIG,KAAX,0,6,2\n"))
            .find("k.bdf:1: GRID 1 is given in coordinate system 2") != std::string::npos);
  CHECK(message(nastran("DMIG,KAAX,0,6,3\n")).find("k.bdf:1: DMIG KAAX has TIN = 3") !=
        std::string::npos);
  CHECK(message(nastran("DMIG,KAAX,1,1,,1,1,1.0\n"))
            .find("k.bdf:1: DMIG KAAX column before its header card") != std::string::npos);
  CHECK(message(nastran("DMIG,KAAX,0,6,2\nDMIG,KAAX,1,1,,1,1,1.0,2.0\n"))
            .find("k.bdf:2: DMIG KAAX has an imaginary part") != std::string::npos);
  CHECK(message(nastran("DMIG,KAAX,0,6,2\nDMIG,KAAX,1,1,,1,1,1.0q\n"))
            .find("k.bdf:2: DMIG KAAX column (1, 1) entry 1: expected G, C, A") !=
        std::string::npos);
  CHECK(message(nastran("+,1,1\n")).find("k.bdf:1: a continuation line with no card before it") !=
        std::string::npos);
  CHECK(message(nastran("DMIG,MAAX,0,6,2\n")).find("k.bdf: no DMIG KAAX entries") !=
        std::string::npos);

  // The model: coordinates missing, rotations, entries twice or not symmetric. The mesh is
  // untouched on error.
  const auto entry = [](long long i, int di, long long j, int dj, double v, const char* where) {
    return LabeledEntry{i, di, j, dj, v, where};
  };
  LabeledModel model;
  model.coordinates[1] = Vector3d::Zero();
  model.coordinates[2] = Vector3d::UnitX();
  model.mass = {entry(1, 1, 1, 1, 1.0, "m:1")};
  Mesh mesh;
  model.stiffness = {entry(1, 1, 3, 1, 1.0, "k:1")};
  CHECK(message(add_labeled_model(mesh, model).status()).find("k:1: node 3 has no coordinates") !=
        std::string::npos);
  model.stiffness = {entry(1, 4, 1, 4, 1.0, "k:2")};
  CHECK(message(add_labeled_model(mesh, model).status())
            .find("k:2: stiffness entry at DOF 4: only translations (DOFs 1, 2, 3)") !=
        std::string::npos);
  model.stiffness = {entry(1, 1, 2, 1, 1.0, "k:3"), entry(1, 1, 2, 1, 1.0, "k:4")};
  CHECK(message(add_labeled_model(mesh, model).status())
            .find("k:4: stiffness entry (node 1 DOF 1, node 2 DOF 1) is given twice (first at "
                  "k:3)") != std::string::npos);
  model.stiffness = {entry(1, 1, 2, 1, 1.0, "k:5"), entry(2, 1, 1, 1, 1.5, "k:6")};
  CHECK(message(add_labeled_model(mesh, model).status()).find("k:6: stiffness is not symmetric") !=
        std::string::npos);
  CHECK(mesh.num_nodes() == 0);

  // A mass that is not of the solid form m_ab I: the inertia integrals refuse it.
  model.stiffness = {entry(1, 1, 1, 1, 1.0, "k:7")};
  model.mass = {entry(1, 1, 1, 1, 1.0, "m:2"), entry(1, 2, 1, 2, 1.0, "m:3"),
                entry(1, 3, 1, 3, 2.0, "m:4")};
  auto imported = add_labeled_model(mesh, model);
  REQUIRE(imported.ok());
  auto dofs = DofMap::build(mesh);
  REQUIRE(dofs.ok());
  auto integrals = reduction::inertia_integrals(mesh, *dofs, MatrixXd::Zero(dofs->size(), 0), {});
  CHECK(
      message(integrals.status()).find("matrix element 0: the mass of z differs from that of x") !=
      std::string::npos);
}

}  // namespace test_matrix_import
