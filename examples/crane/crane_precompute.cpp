// What the crane precomputes (crane_precompute.hpp, precompute_crane): the boom's reduction, the
// welded detail D's sub-model and its outputs, and what the options ask for besides. The one
// crane unit that parses the FE, reduction and stress headers.
#include "detail_model.hpp"

#include <memory>
#include <string>
#include <utility>

#include <flexstress/fe/vtk_writer.hpp>
#include <flexstress/reduction/modal_geometric_stiffness.hpp>
#include <flexstress/stress/section_force_modes.hpp>
#include <flexstress/stress/sub_model_inertia.hpp>

#include "boom_reduction.hpp"

namespace crane {

namespace {

/// The detail's sub-model, read-outs and fused rows (docs/crane.md).
Result<Detail> make_detail(const CraneSpec& spec, const Boom& boom, int modes) {
  auto made = std::make_shared<DetailModel>();
  DetailModel& m = *made;
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
  m.mesh = std::move(*mesh);
  const bool forced = spec.submodel_drive == stress::AttachmentDrive::force;
  if (forced && spec.attach_between_nodes)
    return make_error(ErrorCode::invalid_argument,
                      "crane: a force-driven sub-model end needs a boom node there "
                      "(attach_between_nodes is set)");
  auto sub = stress::SubModel::build(
      m.mesh.mesh, {{Vector3d(ds.x0, 0, 0), m.mesh.end_section_x0},
                    {Vector3d(ds.x1, 0, 0), m.mesh.end_section_x1, spec.submodel_drive}});
  if (!sub) return sub.error();
  m.sub.emplace(std::move(*sub));
  // Outputs: the hot spot at the toe's centre (IIW type a, linear), the paper's own read-out
  // points (4 and 10 mm), its two strain gauges (0.4 t and 1.0 t from the toe, 1 mm grids), a
  // nominal stress on the bottom flange under D, and the hot spot along the whole toe line.
  const double y_top = m.mesh.flange_surface_y, toe = m.mesh.weld_toe_x;
  stress::HotSpotLocation hs;
  hs.toe = Vector3d(toe, y_top, 0);
  hs.away = Vector3d::UnitX();
  hs.thickness = spec.wall;
  auto hot = m.outputs.add_hot_spot(hs, "hot spot (IIW a, 0.4t/1.0t)");
  if (!hot) return hot.error();
  d.hot_spot = *hot;
  stress::HotSpotLocation paper = hs;
  paper.rule = stress::HotSpotRule::user_points;
  paper.user_distances = {0.004, 0.010};
  auto paper_hot = m.outputs.add_hot_spot(paper, "hot spot (paper, 4/10 mm)");
  if (!paper_hot) return paper_hot.error();
  d.paper_hot_spot = *paper_hot;
  auto g1 = m.outputs.add_strain_gauge(Vector3d(toe + 0.4 * spec.wall, y_top, 0), Vector3d::UnitX(),
                                       0.001, "gauge 0.4t");
  auto g2 = m.outputs.add_strain_gauge(Vector3d(toe + 1.0 * spec.wall, y_top, 0), Vector3d::UnitX(),
                                       0.001, "gauge 1.0t");
  if (!g1) return g1.error();
  if (!g2) return g2.error();
  d.gauge_04t = *g1;
  d.gauge_10t = *g2;
  d.nominal = m.outputs.add_normal_stress(Vector3d(0.5 * (ds.x0 + ds.x1), -y_top, 0),
                                          Vector3d::UnitX(), "bottom flange sigma_xx");
  d.toe_line_first = m.outputs.num_outputs();
  for (Index n : m.mesh.weld_toe_nodes) {
    stress::HotSpotLocation h = hs;
    h.toe = m.mesh.mesh.node(n);
    auto r = m.outputs.add_hot_spot(h);
    if (!r) return r.error();
    ++d.toe_line_count;
  }
  auto rows = m.outputs.rows(*m.sub);
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
  for (Index i = 0; i < m.outputs.num_outputs(); ++i) {
    const std::string& label = m.outputs.label(i);
    d.names.push_back(label.empty() ? "output " + std::to_string(i) : label);
  }
  d.num_bricks = static_cast<Index>(m.mesh.mesh.hexes().size());
  d.model = std::move(made);
  return d;
}

}  // namespace

Result<Precomputed> precompute_crane(const CraneSpec& spec, const CraneOptions& options) {
  Precomputed p;
  auto boom = make_boom(spec, options.modes);
  if (!boom) return boom.error();
  p.boom = std::move(*boom);
  auto detail = make_detail(spec, p.boom, options.modes);
  if (!detail) return detail.error();
  p.detail = std::move(*detail);
  if (options.geometric_stiffening) {
    // The boom's inertial loads leave it through A and B: both clamped for the stress states
    // (docs/crane.md).
    auto g = reduction::modal_geometric_stiffness(p.boom.mesh, p.boom.data,
                                                  reduction::clamp_interface_nodes(p.boom.data));
    if (!g) return g.error();
    p.boom_stiffening = std::move(*g);
  }
  if (options.with_inertia) {
    const DetailModel& m = *p.detail.model;
    auto inertia = stress::SubModelInertia<>::build(*m.sub, m.outputs);
    if (!inertia) return inertia.error();
    p.detail_inertia = inertia->rows();
  }
  return p;
}

Status write_detail_vtu(const Detail& detail, const VectorXd& p, const std::string& path) {
  const stress::SubModel& sub = *detail.model->sub;
  const VectorXd u = sub.solve(detail.boundary_modes.leftCols(p.size()) * p);
  auto fields = fe::standard_fields(sub.mesh(), sub.model().dofs, u);
  if (!fields) return fields.error();
  return fe::write_vtu(path, sub.mesh(), *fields);
}

}  // namespace crane
