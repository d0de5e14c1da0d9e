// libFuzzer target: the matrix import readers (Abaqus *MATRIX GENERATE output and *NODE
// blocks, Nastran GRID and DMIG bulk data) and add_labeled_model on arbitrary text. Whatever
// the input, they must return (no crash, no sanitizer report, no hang); a reader that fails
// leaves the model untouched and names the source; an import that fails leaves the mesh
// untouched; one that succeeds gives a mesh that validates, numbers its DOFs and assembles.
// The input is read as Nastran bulk data, and as Abaqus text split at form feeds into the
// input file, the stiffness and the mass files. Seeds: fuzz/seeds/matrix_import (the bushing
// in Abaqus form) and tests/fe/matrix_import (its files, and the bushing in Nastran form).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include <flexstress/fe/abaqus_matrix_reader.hpp>
#include <flexstress/fe/assembly.hpp>
#include <flexstress/fe/nastran_dmig_reader.hpp>

namespace {

void require(bool condition) {
  if (!condition) __builtin_trap();
}

struct Sizes {
  std::size_t coordinates, stiffness, mass;
  explicit Sizes(const flexstress::fe::LabeledModel& m)
      : coordinates(m.coordinates.size()), stiffness(m.stiffness.size()), mass(m.mass.size()) {}
  bool operator==(const Sizes& o) const {
    return coordinates == o.coordinates && stiffness == o.stiffness && mass == o.mass;
  }
};

// A reader's result: on failure nothing changed and the message names the source.
void check_read(const flexstress::Status& st, const flexstress::fe::LabeledModel& model,
                const Sizes& before, std::string_view name) {
  if (st.ok()) return;
  require(Sizes(model) == before);
  const std::string& message = st.error().message;
  require(message.compare(0, name.size(), name) == 0);
}

void check_import(const flexstress::fe::LabeledModel& model) {
  using namespace flexstress;
  if (model.stiffness.empty() || model.mass.empty()) return;
  fe::Mesh mesh;
  auto imported = fe::add_labeled_model(mesh, model);
  if (!imported) {
    require(mesh.num_nodes() == 0 && mesh.matrix_elements().empty());
    return;
  }
  require(mesh.validate().ok());
  require(static_cast<Index>(imported->node_labels.size()) == mesh.num_nodes());
  for (long long label : imported->node_labels) require(imported->node(label) >= 0);
  auto dofs = fe::DofMap::build(mesh);
  require(dofs.ok());
  require(dofs->size() == 3 * mesh.num_nodes());
  auto k = fe::assemble_stiffness(mesh, *dofs);
  auto m = fe::assemble_mass(mesh, *dofs);
  require(k.ok() && m.ok() && k->rows() == dofs->size() && m->rows() == dofs->size());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace flexstress;
  const std::string_view text(reinterpret_cast<const char*>(data), size);

  fe::LabeledModel nastran;
  const Sizes empty(nastran);
  check_read(fe::read_nastran_bulk(text, "KAAX", "MAAX", nastran, "fuzz.bdf"), nastran, empty,
             "fuzz.bdf");
  check_import(nastran);

  const std::size_t first = text.find('\f');
  const std::size_t second = first == std::string_view::npos ? first : text.find('\f', first + 1);
  if (second == std::string_view::npos) return 0;
  fe::LabeledModel abaqus;
  Sizes before(abaqus);
  check_read(fe::read_abaqus_nodes(text.substr(0, first), abaqus, "fuzz.inp"), abaqus, before,
             "fuzz.inp");
  before = Sizes(abaqus);
  check_read(fe::read_abaqus_matrix(text.substr(first + 1, second - first - 1),
                                    fe::ImportedMatrix::stiffness, abaqus, "fuzz_STIF1.mtx"),
             abaqus, before, "fuzz_STIF1.mtx");
  before = Sizes(abaqus);
  check_read(fe::read_abaqus_matrix(text.substr(second + 1), fe::ImportedMatrix::mass, abaqus,
                                    "fuzz_MASS1.mtx"),
             abaqus, before, "fuzz_MASS1.mtx");
  check_import(abaqus);
  return 0;
}
