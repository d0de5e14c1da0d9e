// Making the crane's boom (boom_model.hpp): the beam model with the payload and its
// Craig-Bampton (or Craig-Chang) reduction. Includes the FE and reduction headers; the crane's
// units reach it through precompute_crane (crane_precompute.hpp), the boom's own tests directly.
#pragma once

#include <algorithm>
#include <utility>

#include <flexstress/fe/beam_section.hpp>
#include <flexstress/fe/material.hpp>
#include <flexstress/reduction/modal_body_data.hpp>

#include "boom_model.hpp"

namespace crane {

inline Result<Boom> make_boom(const CraneSpec& spec, int modes) {
  Boom boom;
  fe::BeamLineSpec line;
  line.end = Vector3d(spec.boom_length, 0, 0);
  line.num_elements = spec.boom_elements;
  line.extra_positions = {spec.b_node_x, spec.payload_x};
  if (!spec.attach_between_nodes) {
    line.extra_positions.push_back(spec.submodel_x0);
    line.extra_positions.push_back(spec.submodel_x1);
  }
  line.material = boom.mesh.add_material(fe::steel());
  line.section = boom.mesh.add_section(fe::rectangular_hollow_section(0.150, 0.100, spec.wall));
  line.orientation = Vector3d::UnitY();  // section height along y: vertical bending is strong
  boom.line = fe::add_beam_line(boom.mesh, line);
  boom.node_a = boom.line.node_at(0.0);
  boom.node_b = boom.line.node_at(spec.b_node_x);
  if (!spec.attach_between_nodes) {
    boom.node_x0 = boom.line.node_at(spec.submodel_x0);
    boom.node_x1 = boom.line.node_at(spec.submodel_x1);
  }
  if (spec.payload_mass > 0)
    boom.mesh.add_point_mass(boom.line.node_at(spec.payload_x), spec.payload_mass);
  reduction::ReductionSpec rs;
  rs.method = spec.boom_reduction;
  rs.interface = {{boom.node_a}, {boom.node_b}};
  // Craig-Bampton: 6 static modes plus fixed-interface modes, enough for `modes`. Craig-Chang:
  // as many free-free modes, besides the 12 attachment modes.
  rs.dynamic_modes.count = std::max(spec.fixed_interface_modes, modes - 6);
  rs.keep_modes = modes;
  rs.damping_ratio = spec.damping_ratio;
  auto data = reduction::reduce(boom.mesh, rs);
  if (!data) return data.error();
  boom.data = std::move(*data);
  return boom;
}

}  // namespace crane
