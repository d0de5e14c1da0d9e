// The welded detail D of the crane (crane_model_impl.hpp): a unit of its own, the heaviest part
// of the crane's assembly to compile.
#include "crane_model_impl.hpp"

namespace crane::assembly {

/// The detail's sub-model, read-outs and fused rows (docs/crane.md).
Result<Detail> make_detail(const CraneSpec& spec, const Boom& boom, int modes) {
  Detail d;
  fe::RhsAttachmentSpec ds;
  ds.density = spec.submodel_density;
  ds.x0 = spec.submodel_x0;
  ds.x1 = spec.submodel_x1;
  ds.max_element_length = spec.submodel_max_element_length;
  ds.wall = spec.wall;
  ds.formulation = spec.formulation;
  auto mesh = fe::make_rhs_attachment_mesh(ds);
  if (!mesh) return mesh.error();
  d.mesh = std::move(*mesh);
  const bool forced = spec.submodel_drive == stress::AttachmentDrive::force;
  if (forced && spec.attach_between_nodes)
    return make_error(ErrorCode::invalid_argument,
                      "crane: a force-driven sub-model end needs a boom node there "
                      "(attach_between_nodes is set)");
  auto sub = stress::SubModel::build(
      d.mesh.mesh, {{Vector3d(ds.x0, 0, 0), d.mesh.end_section_x0},
                    {Vector3d(ds.x1, 0, 0), d.mesh.end_section_x1, spec.submodel_drive}});
  if (!sub) return sub.error();
  d.sub.emplace(std::move(*sub));
  // Outputs: the hot spot at the toe's centre (IIW type a, linear), the paper's own read-out
  // points (4 and 10 mm), its two strain gauges (0.4 t and 1.0 t from the toe, 1 mm grids), a
  // nominal stress on the bottom flange under D, and the hot spot along the whole toe line.
  const double y_top = d.mesh.flange_surface_y, toe = d.mesh.weld_toe_x;
  stress::HotSpotLocation hs;
  hs.toe = Vector3d(toe, y_top, 0);
  hs.away = Vector3d::UnitX();
  hs.thickness = spec.wall;
  auto hot = d.outputs.add_hot_spot(hs, "hot spot (IIW a, 0.4t/1.0t)");
  if (!hot) return hot.error();
  d.hot_spot = *hot;
  stress::HotSpotLocation paper = hs;
  paper.rule = stress::HotSpotRule::user_points;
  paper.user_distances = {0.004, 0.010};
  auto paper_hot = d.outputs.add_hot_spot(paper, "hot spot (paper, 4/10 mm)");
  if (!paper_hot) return paper_hot.error();
  d.paper_hot_spot = *paper_hot;
  auto g1 = d.outputs.add_strain_gauge(Vector3d(toe + 0.4 * spec.wall, y_top, 0), Vector3d::UnitX(),
                                       0.001, "gauge 0.4t");
  auto g2 = d.outputs.add_strain_gauge(Vector3d(toe + 1.0 * spec.wall, y_top, 0), Vector3d::UnitX(),
                                       0.001, "gauge 1.0t");
  if (!g1) return g1.error();
  if (!g2) return g2.error();
  d.gauge_04t = *g1;
  d.gauge_10t = *g2;
  d.nominal = d.outputs.add_normal_stress(Vector3d(0.5 * (ds.x0 + ds.x1), -y_top, 0),
                                          Vector3d::UnitX(), "bottom flange sigma_xx");
  d.toe_line_first = d.outputs.num_outputs();
  for (Index n : d.mesh.weld_toe_nodes) {
    stress::HotSpotLocation h = hs;
    h.toe = d.mesh.mesh.node(n);
    auto r = d.outputs.add_hot_spot(h);
    if (!r) return r.error();
    ++d.toe_line_count;
  }
  auto rows = d.outputs.rows(*d.sub);
  if (!rows) return rows.error();
  auto phi =
      stress::boundary_modes(boom.data, {host_point(boom, spec.submodel_x0, spec.interpolation),
                                         host_point(boom, spec.submodel_x1, spec.interpolation)});
  if (!phi) return phi.error();
  d.boundary_modes = std::move(*phi);
  if (forced) {
    // The x1 end carries the force and moment of the boom element inside the segment there.
    Index inner = -1;
    const auto& beams = boom.mesh.beams();
    for (std::size_t e = 0; e < beams.size(); ++e)
      for (int end = 0; end < 2; ++end)
        if (beams[e].nodes[std::size_t(end)] == boom.node_x1 &&
            boom.mesh.node(beams[e].nodes[std::size_t(1 - end)]).x() < spec.submodel_x1)
          inner = static_cast<Index>(e);
    auto f = stress::section_force_modes(boom.mesh, boom.data, inner, boom.node_x1);
    if (!f) return f.error();
    d.boundary_modes.bottomRows(6) = *f;
  }
  if (d.boundary_modes.cols() < modes)
    return make_error(ErrorCode::size_mismatch, "crane: the boom has ", d.boundary_modes.cols(),
                      " modes, ", modes, " asked");
  d.fused = *rows * d.boundary_modes.leftCols(modes);
  for (Index i = 0; i < d.outputs.num_outputs(); ++i) {
    const std::string& label = d.outputs.label(i);
    d.names.push_back(label.empty() ? "output " + std::to_string(i) : label);
  }
  return d;
}

}  // namespace crane::assembly
