// Writes the inputs of the C interface's tests (test_c_flexible_pendulum.c,
// test_c_spinning_beam.c): a hinged beam's modal body file and its geometric stiffness file,
// and its reference frequencies from the full FE model (the kernel, no reduction), which the
// C test must reproduce through the interface alone.
//
//   make_pendulum_files <dir>  ->  <dir>/beam.fsmodal, <dir>/beam.fsgeom,
//                                  <dir>/beam_reference.txt
//
// The beam: 2 m steel RHS 40 x 20 x 2 mm along x, 24 elements, reduced by Craig-Bampton with
// its x = 0 node as interface and 16 fixed-interface modes (tests/model/test_model_equilibrium).
#include <cstdio>
#include <string>

#include <flexstress/fe/assembly.hpp>
#include <flexstress/fe/beam_line.hpp>
#include <flexstress/fe/eigen_solver.hpp>
#include <flexstress/reduction/modal_body_data.hpp>
#include <flexstress/reduction/modal_body_io.hpp>
#include <flexstress/reduction/modal_geometric_stiffness.hpp>
#include <flexstress/reduction/modal_geometric_stiffness_io.hpp>

int main(int argc, char** argv) {
  using namespace flexstress;
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s <output dir>\n", argv[0]);
    return 2;
  }
  const std::string dir = argv[1];
  const fe::BeamSection section = fe::rectangular_hollow_section(0.04, 0.02, 0.002);
  const double length = 2.0;
  fe::Mesh mesh;
  fe::BeamLineSpec spec;
  spec.end = Vector3d(length, 0, 0);
  spec.num_elements = 24;
  spec.extra_positions = {0.0};
  spec.material = mesh.add_material(fe::steel());
  spec.section = mesh.add_section(section);
  const fe::BeamLine line = fe::add_beam_line(mesh, spec);
  const Index root = line.node_at(0.0), tip = line.nodes.back();
  reduction::ReductionSpec rs;
  rs.interface.push_back({root});
  rs.dynamic_modes.count = 16;
  auto data = reduction::reduce(mesh, rs);
  if (!data) {
    std::fprintf(stderr, "reduction: %s\n", data.error().what().c_str());
    return 1;
  }
  if (const Status s = reduction::save_modal_body(*data, dir + "/beam.fsmodal"); !s.ok()) {
    std::fprintf(stderr, "%s\n", s.error().what().c_str());
    return 1;
  }
  // Geometric stiffening: the stress of the inertial loads, reacted at the clamped root.
  auto geometric =
      reduction::modal_geometric_stiffness(mesh, *data, reduction::clamp_interface_nodes(*data));
  if (!geometric) {
    std::fprintf(stderr, "geometric stiffness: %s\n", geometric.error().what().c_str());
    return 1;
  }
  if (const Status s = reduction::save_geometric_stiffness(*geometric, *data, dir + "/beam.fsgeom");
      !s.ok()) {
    std::fprintf(stderr, "%s\n", s.error().what().c_str());
    return 1;
  }
  // Pinned-free about z: the root's translations and its rotations about x and y held.
  fe::BoundaryConditions bc;
  bc.pin(root).fix(root, 3).fix(root, 4);
  auto full = fe::assemble(mesh, bc);
  if (!full) {
    std::fprintf(stderr, "assembly: %s\n", full.error().what().c_str());
    return 1;
  }
  fe::EigenOptions eo;
  eo.num_modes = 6;
  auto ref = fe::solve_eigen(full->stiffness, full->mass, eo);
  if (!ref) {
    std::fprintf(stderr, "eigen: %s\n", ref.error().what().c_str());
    return 1;
  }
  const VectorXd hz = ref->frequencies_hz();
  const std::string path = dir + "/beam_reference.txt";
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) {
    std::fprintf(stderr, "cannot write %s\n", path.c_str());
    return 1;
  }
  // Plain text the C test reads with fscanf: nodes, mass, length, frequencies.
  std::fprintf(f, "root_node %ld\ntip_node %ld\nnum_nodes %ld\nmass %.17g\nlength %.17g\n",
               static_cast<long>(root), static_cast<long>(tip), static_cast<long>(mesh.num_nodes()),
               data->mass(), length);
  std::fprintf(f, "frequencies %ld", static_cast<long>(hz.size()));
  for (Index i = 0; i < hz.size(); ++i) std::fprintf(f, " %.17g", hz(i));
  std::fprintf(f, "\n");
  // The root element's other node and what M c / I needs: E, the section's Iz (bending in the
  // x-y plane) and its half height along y.
  std::fprintf(f, "next_node %ld youngs_modulus %.17g iz %.17g half_height %.17g\n",
               static_cast<long>(line.nodes[1]), mesh.material(spec.material).youngs_modulus,
               section.iz, section.half_height_y);
  std::fclose(f);
  std::printf("wrote %s/beam.fsmodal, beam.fsgeom and %s (first FE frequencies %g, %g, %g Hz)\n",
              dir.c_str(), path.c_str(), hz(0), hz(1), hz(2));
  return 0;
}
