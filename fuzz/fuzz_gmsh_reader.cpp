// libFuzzer target: the Gmsh reader on arbitrary text. Whatever the input, read_gmsh must
// return (no crash, no sanitizer report, no hang); on failure the mesh is untouched and the
// error names the source; on success the mesh is valid and every group refers to its nodes.
// Seeds: tests/fe/gmsh (a hand-written file and a Gmsh geometry).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include <flexstress/fe/gmsh_reader.hpp>

namespace {

void require(bool condition) {
  if (!condition) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace flexstress;
  fe::Mesh mesh;
  const Index material = mesh.add_material(fe::steel());
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto imported = fe::read_gmsh(text, mesh, material, "fuzz.msh");
  if (!imported) {
    require(imported.error().message.rfind("fuzz.msh", 0) == 0);
    require(mesh.num_nodes() == 0 && mesh.hexes().empty());
    return 0;
  }
  require(mesh.validate().ok());
  require(!mesh.hexes().empty());
  require(static_cast<Index>(imported->node_tags.size()) == mesh.num_nodes());
  require(imported->hex_tags.size() == mesh.hexes().size());
  for (const fe::GmshGroup& g : imported->groups) {
    for (Index n : g.nodes) require(n >= 0 && n < mesh.num_nodes());
    for (Index n : g.path) require(n >= 0 && n < mesh.num_nodes());
    for (Index h : g.hexes) require(h >= 0 && h < static_cast<Index>(mesh.hexes().size()));
  }
  return 0;
}
