// Builds the crane boom of Rantalainen et al. (2013) as a beam in code and prints its natural
// frequencies next to the analytic Euler-Bernoulli values (validation sheet: clamped-free and
// free-free beta_n L).
#include <cmath>
#include <cstdio>

#include <flexstress/flexstress.hpp>

int main() {
  using namespace flexstress;
  using namespace flexstress::fe;
  const double length = 4.5;
  const BeamSection section = rectangular_hollow_section(0.15, 0.10, 0.004);  // Table 2
  const Material mat = steel();

  Mesh mesh;
  BeamLineSpec spec;
  spec.end = Vector3d(length, 0, 0);
  spec.num_elements = 20;
  spec.material = mesh.add_material(mat);
  spec.section = mesh.add_section(section);
  const BeamLine line = add_beam_line(mesh, spec);

  // Clamp the root and keep the beam in its vertical (x-y) plane, as beam theory assumes.
  BoundaryConditions bc;
  bc.clamp(line.nodes.front());
  for (std::size_t i = 1; i < line.nodes.size(); ++i)
    bc.fix(line.nodes[i], 0).fix(line.nodes[i], 2).fix(line.nodes[i], 3).fix(line.nodes[i], 4);
  MassOptions mass;
  mass.beam_rotary_inertia = false;  // as the analytic values assume
  auto model = assemble(mesh, bc, mass);
  if (!model) {
    std::fprintf(stderr, "error: %s\n", model.error().what().c_str());
    return 1;
  }
  EigenOptions eig;
  eig.num_modes = 4;
  auto modes = solve_eigen(model->stiffness, model->mass, eig);
  if (!modes) {
    std::fprintf(stderr, "error: %s\n", modes.error().what().c_str());
    return 1;
  }
  const double beta_l[] = {1.875104, 4.694091, 7.854757, 10.995541};
  const double pi = 3.14159265358979323846;
  std::printf("flexstress %s: RHS 150x100x4 cantilever, L = %.2f m, 20 beam elements\n",
              version_string, length);
  std::printf("%6s %14s %14s %10s\n", "mode", "FE [Hz]", "analytic [Hz]", "error [%]");
  for (int i = 0; i < 4; ++i) {
    const double omega = beta_l[i] * beta_l[i] / (length * length) *
                         std::sqrt(mat.youngs_modulus * section.iz / (mat.density * section.area));
    const double exact = omega / (2 * pi), fe = modes->frequencies_hz()(i);
    std::printf("%6d %14.4f %14.4f %10.5f\n", i + 1, fe, exact, 100.0 * (fe / exact - 1.0));
  }
  return 0;
}
