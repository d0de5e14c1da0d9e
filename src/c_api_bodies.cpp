// The C interface (flexstress/flexstress.h): modal body files made from C. A flexible body
// needs a modal body file, and its reduction is C++ (reduction/modal_body_data.hpp); a straight
// uniform beam, the body most mechanisms need, is made here from its section and material, so
// that a C program (or a language that calls C) can build a flexible mechanism on its own.
#include <sstream>
#include <string>
#include <vector>

#include "c_api_internal.hpp"
#include "flexstress/fe/beam_line.hpp"
#include "flexstress/reduction/modal_body_data.hpp"

using namespace flexstress_c_api;

namespace {

// Text of the values given, as C++ streams write them (1, 0.5, 2e-05).
template <class... Parts>
std::string text(const Parts&... parts) {
  std::ostringstream out;
  (out << ... << parts);
  return out.str();
}

// More elements than a beam body needs by far (the file holds every node's mode shapes).
constexpr int kMaxElements = 100000;

// The first thing wrong with a beam's description, or an empty string.
std::string beam_problem(const fs_beam_body& beam) {
  const auto positive = [](double x) { return std::isfinite(x) && x > 0.0; };
  if (!positive(beam.length)) return text("length ", beam.length, " must be positive");
  if (beam.elements < 1 || beam.elements > kMaxElements)
    return text("elements ", beam.elements, " must be from 1 to ", kMaxElements);
  const fsx::Vector3d y(beam.orientation[0], beam.orientation[1], beam.orientation[2]);
  if (!y.allFinite()) return "the orientation is not finite";
  if (!y.isZero(0.0) && y.tail<2>().norm() <= 1e-9 * y.norm())
    return "the orientation (the section's y) lies along the beam's x";
  if (beam.interface_count < 1 || beam.interface_at == nullptr)
    return "it needs at least one interface position (interface_at, interface_count)";
  for (int k = 0; k < beam.interface_count; ++k) {
    const double s = beam.interface_at[k];
    if (!std::isfinite(s) || s < 0.0 || s > beam.length)
      return text("interface position ", k, " (", s, " m) is outside the beam [0, ", beam.length,
                  "]");
  }
  if (beam.fixed_interface_modes < 0)
    return text("fixed_interface_modes ", beam.fixed_interface_modes, " must not be negative");
  if (!std::isfinite(beam.damping_ratio) || beam.damping_ratio < 0.0 || beam.damping_ratio >= 1.0)
    return text("damping_ratio ", beam.damping_ratio, " must be in [0, 1)");
  return std::string();
}

}  // namespace

extern "C" {

int fs_save_beam_modal_body(const fs_beam_body* beam, const char* path) {
  return guarded("fs_save_beam_modal_body", [&] {
    if (!beam || !path) return null_argument("fs_save_beam_modal_body");
    const std::string where = std::string("fs_save_beam_modal_body: beam for '") + path + "'";
    if (const std::string why = beam_problem(*beam); !why.empty())
      return fail(FS_ERROR_INVALID_ARGUMENT, where + ": " + why);
    fsx::fe::Mesh mesh;
    fsx::fe::BeamSection section;
    section.area = beam->area;
    section.iy = beam->iy;
    section.iz = beam->iz;
    section.torsion_constant = beam->torsion_constant;
    fsx::fe::Material material;
    material.youngs_modulus = beam->youngs_modulus;
    material.poissons_ratio = beam->poissons_ratio;
    material.density = beam->density;
    fsx::fe::BeamLineSpec spec;
    spec.end = fsx::Vector3d(beam->length, 0, 0);
    spec.num_elements = beam->elements;
    spec.extra_positions.assign(beam->interface_at, beam->interface_at + beam->interface_count);
    // A position within a thousandth of an element of a node is that node: a sliver of an
    // element there would be about 1e9 times stiffer in bending than its neighbours.
    spec.merge_tolerance = 1e-3 / beam->elements;
    spec.material = mesh.add_material(material);
    spec.section = mesh.add_section(section);
    spec.orientation = vec3(beam->orientation);
    const fsx::fe::BeamLine line = fsx::fe::add_beam_line(mesh, spec);
    fsx::reduction::ReductionSpec rs;
    for (int k = 0; k < beam->interface_count; ++k) {
      const fsx::Index node = line.node_at(beam->interface_at[k]);
      const bool repeated = std::any_of(rs.interface.begin(), rs.interface.end(),
                                        [&](const auto& i) { return i.node == node; });
      if (repeated)
        return fail(FS_ERROR_INVALID_ARGUMENT,
                    where + text(": interface position ", k, " (", beam->interface_at[k],
                                 " m) falls on the node of an earlier one"));
      rs.interface.push_back({node});
    }
    rs.dynamic_modes.count = beam->fixed_interface_modes;
    rs.damping_ratio = beam->damping_ratio;
    // reduce() checks the material and the section (naming them) and the modes asked for.
    auto data = fsx::reduction::reduce(mesh, rs);
    if (!data) return fail(status_of(data.error().code), where + ": " + data.error().what());
    if (const fsx::Status s = fsx::reduction::save_modal_body(*data, path); !s)
      return fail(status_of(s.error().code), where + ": " + s.error().what());
    return static_cast<int>(FS_OK);
  });
}

}  // extern "C"
