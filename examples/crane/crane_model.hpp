// The paper's crane (Rantalainen et al. 2013, section 5), composed in code: a flexible boom on a
// support, a hydraulic cylinder and its piston rod, a payload, gravity, a prescribed stroke, and
// the welded detail D as a sub-model whose hot-spot stress comes per step from fused modal rows.
// Every number and every choice the paper leaves open is in docs/crane.md.
#pragma once

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <flexstress/dynamics/implicit_integrator.hpp>
#include <flexstress/dynamics/joints.hpp>
#include <flexstress/dynamics/motion_laws.hpp>
#include <flexstress/dynamics/scene.hpp>
#include <flexstress/dynamics/static_equilibrium.hpp>
#include <flexstress/fe/beam_line.hpp>
#include <flexstress/fe/rhs_attachment_mesh.hpp>
#include <flexstress/reduction/modal_body_data.hpp>
#include <flexstress/stress/fused_stress.hpp>
#include <flexstress/stress/host_point.hpp>
#include <flexstress/stress/stress_outputs.hpp>
#include <flexstress/stress/sub_model.hpp>

namespace crane {

using namespace flexstress;

/// Parameters of the crane (SI units). Defaults: the paper's Tables 1 and 2 and DESIGN choices.
struct CraneSpec {
  double boom_length = 4.5;
  int boom_elements = 19;  ///< 20 nodes, plus nodes at B, the sub-model ends and the payload
  double payload_mass = 100.0;
  double payload_x = 2.5;
  double cylinder_mass = 20.0, rod_mass = 10.0;
  double cylinder_length = 0.6, rod_length = 0.6;  ///< slender bodies along their axis
  Vector3d a{0, 0, 0}, b{0.32, -0.125, 0}, c{0, -0.925, 0};
  double b_node_x = 0.32;  ///< B hangs 0.125 m below this boom node (rigid offset)
  double damping_ratio = 0.02;
  int fixed_interface_modes = 4;  ///< 6 static + 4 = 10 deformation modes
  double submodel_density = 1.0;  ///< 1792 bricks
  double submodel_x0 = 0.5, submodel_x1 = 0.8;
  double wall = 0.004;
};

/// N boom modes; StorageLimit chooses fixed-size (default) or dynamic storage (0).
template <int N, int StorageLimit = fixed_storage_limit>
using CraneScene = Scene<double, Bodies<FFRFBody<N>, RigidBody, RigidBody>,
                         Joints<Revolute<ground, 0>, Universal<ground, 1>, Spherical<0, 2>,
                                Prismatic<1, 2>, PrismaticDriver<1, 2, TableLaw>>,
                         Effects<Gravity, QuadraticVelocity, ModalDamping>, ForceElements<>,
                         FixedGround<double>, StorageLimit>;

/// The boom as a beam model with the payload as a point mass, and its reduction.
struct Boom {
  fe::Mesh mesh;
  fe::BeamLine line;
  reduction::ModalBodyData data;
  Index node_a = -1, node_b = -1, node_x0 = -1, node_x1 = -1;
};

inline Result<Boom> make_boom(const CraneSpec& spec, int modes) {
  Boom boom;
  fe::BeamLineSpec line;
  line.end = Vector3d(spec.boom_length, 0, 0);
  line.num_elements = spec.boom_elements;
  line.extra_positions = {spec.b_node_x, spec.submodel_x0, spec.submodel_x1, spec.payload_x};
  line.material = boom.mesh.add_material(fe::steel());
  line.section = boom.mesh.add_section(fe::rectangular_hollow_section(0.150, 0.100, spec.wall));
  line.orientation = Vector3d::UnitY();  // section height along y: vertical bending is strong
  boom.line = fe::add_beam_line(boom.mesh, line);
  boom.node_a = boom.line.node_at(0.0);
  boom.node_b = boom.line.node_at(spec.b_node_x);
  boom.node_x0 = boom.line.node_at(spec.submodel_x0);
  boom.node_x1 = boom.line.node_at(spec.submodel_x1);
  if (spec.payload_mass > 0)
    boom.mesh.add_point_mass(boom.line.node_at(spec.payload_x), spec.payload_mass);
  reduction::ReductionSpec rs;
  rs.interface = {{boom.node_a}, {boom.node_b}};
  rs.dynamic_modes.count = spec.fixed_interface_modes;
  rs.keep_modes = modes;
  rs.damping_ratio = spec.damping_ratio;
  auto data = reduction::reduce(boom.mesh, rs);
  if (!data) return data.error();
  boom.data = std::move(*data);
  return boom;
}

/// The synthetic work cycle (documented in docs/crane.md): stroke offsets from the initial
/// cylinder length at times t. Lift 0.20 m, hold with two operator corrections, lower.
inline void synthetic_cycle(std::vector<double>& t, std::vector<double>& ds) {
  t = {0.0, 0.5, 1.5, 2.5, 3.5, 4.0, 4.6, 5.2, 5.8, 6.5, 7.5, 8.5, 9.5, 10.0, 11.0};
  ds = {0.0, 0.0, 0.04, 0.13, 0.20, 0.20, 0.185, 0.185, 0.195, 0.195, 0.12, 0.03, 0.0, 0.0, 0.0};
}

template <int N, int StorageLimit = fixed_storage_limit>
struct Crane {
  using SceneT = CraneScene<N, StorageLimit>;
  CraneSpec spec;
  Boom boom;
  SceneT scene;
  typename SceneT::State initial;
  fe::RhsAttachmentMesh detail;
  std::optional<stress::SubModel> sub;
  stress::StressOutputs outputs;
  std::optional<stress::FusedStress<N>> fused;
  Index hot_spot_row = -1, paper_hot_spot_row = -1, gauge_04t = -1, gauge_10t = -1,
        nominal_row = -1;
  Index toe_line_first = -1, toe_line_count = 0;
};

/// Builds the crane with stroke table (t, stroke offset), puts it in static equilibrium at
/// t = 0 and precomputes the sub-model. Fails with the first error.
template <int N, int StorageLimit = fixed_storage_limit>
Result<Crane<N, StorageLimit>> make_crane(const CraneSpec& spec, const std::vector<double>& t,
                                          const std::vector<double>& stroke_offset) {
  Crane<N, StorageLimit> cr;
  cr.spec = spec;
  auto boom = make_boom(spec, N);
  if (!boom) return boom.error();
  cr.boom = std::move(*boom);
  auto body = FFRFBody<N>::from_modal_data(cr.boom.data);
  if (!body) return body.error();
  auto& sc = cr.scene;
  sc.template body<0>() = *body;
  // Cylinder (1) and rod (2): slender rigid bodies, frames with z along C -> B, origins at C and
  // B; centres of mass half a length inside.
  const double lc = spec.cylinder_length, lr = spec.rod_length;
  const double ic = spec.cylinder_mass * lc * lc / 12, ir = spec.rod_mass * lr * lr / 12;
  sc.template body<1>() = RigidBody::rigid(spec.cylinder_mass, Vector3d(0, 0, lc / 2),
                                           Vector3d(ic, ic, 1e-3 * ic).asDiagonal());
  sc.template body<2>() = RigidBody::rigid(spec.rod_mass, Vector3d(0, 0, -lr / 2),
                                           Vector3d(ir, ir, 1e-3 * ir).asDiagonal());
  const Vector3d cb = (spec.b - spec.c).normalized();
  const Matrix3d frame = frame_with_z_axis<double>(cb);
  const Matrix3d planar = Matrix3d::Identity();  // revolute axes along global z
  const Matrix3d to_local = frame.transpose();
  auto& s = cr.initial;
  s.template coordinates<1>().position = spec.c;
  s.template coordinates<1>().theta = from_rotation_matrix<double>(frame);
  s.template coordinates<2>().position = spec.b;
  s.template coordinates<2>().theta = from_rotation_matrix<double>(frame);
  // A: boom on the support. C: cylinder on the support (universal: the revolute about z plus
  // the in-plane cross axis, so the loop is not over-constrained). B: rod on the boom
  // (spherical), 0.125 m below the boom node at 0.32 m.
  sc.template joint<0>().marker_i = fixed_marker<double>(spec.a, planar);
  sc.template joint<0>().marker_j =
      make_marker(sc.template body<0>(), cr.boom.node_a, Vector3d::Zero(), planar);
  sc.template joint<1>().marker_i = fixed_marker<double>(spec.c, planar);
  const Matrix3d cross = frame_with_z_axis<double>(Vector3d(cb.y(), -cb.x(), 0));
  sc.template joint<1>().marker_j =
      make_marker(sc.template body<1>(), -1, Vector3d::Zero(), Matrix3d(to_local * cross));
  sc.template joint<2>().marker_i = make_marker(sc.template body<0>(), cr.boom.node_b,
                                                Vector3d(spec.b - Vector3d(spec.b_node_x, 0, 0)));
  sc.template joint<2>().marker_j = make_marker(sc.template body<2>(), -1, Vector3d::Zero());
  sc.template joint<3>().marker_i = make_marker(sc.template body<1>(), -1, Vector3d::Zero());
  sc.template joint<3>().marker_j = make_marker(sc.template body<2>(), -1, Vector3d::Zero());
  sc.template joint<4>().marker_i = make_marker(sc.template body<1>(), -1, Vector3d::Zero());
  sc.template joint<4>().marker_j = make_marker(sc.template body<2>(), -1, Vector3d::Zero());
  std::vector<double> stroke(stroke_offset);
  for (double& v : stroke) v += (spec.b - spec.c).norm();
  auto law = TableLaw<double>::create(t, stroke);
  if (!law) return law.error();
  sc.template joint<4>().params.law = *law;
  if (Status st = solve_static_equilibrium(sc, s); !st) return st.error();

  // Detail D: the RHS segment with the welded rib, tied to the boom nodes at its ends.
  fe::RhsAttachmentSpec ds;
  ds.density = spec.submodel_density;
  ds.x0 = spec.submodel_x0;
  ds.x1 = spec.submodel_x1;
  ds.wall = spec.wall;
  auto detail = fe::make_rhs_attachment_mesh(ds);
  if (!detail) return detail.error();
  cr.detail = std::move(*detail);
  auto sub =
      stress::SubModel::build(cr.detail.mesh, {{Vector3d(ds.x0, 0, 0), cr.detail.end_section_x0},
                                               {Vector3d(ds.x1, 0, 0), cr.detail.end_section_x1}});
  if (!sub) return sub.error();
  cr.sub.emplace(std::move(*sub));
  // Outputs: the hot spot at the toe's centre (IIW type a, linear), the paper's two strain
  // gauges (0.4 t and 1.0 t from the toe, 1 mm grids), a nominal stress read-out on the bottom
  // flange under D (away from the rib), and the hot spot along the whole toe line.
  const double y_top = cr.detail.flange_surface_y, toe = cr.detail.weld_toe_x;
  stress::HotSpotLocation hs;
  hs.toe = Vector3d(toe, y_top, 0);
  hs.away = Vector3d::UnitX();
  hs.thickness = spec.wall;
  auto hot = cr.outputs.add_hot_spot(hs, "hot spot (IIW a, 0.4t/1.0t)");
  if (!hot) return hot.error();
  cr.hot_spot_row = *hot;
  // The paper's own read-out points, 4 mm and 10 mm from the toe, extrapolated linearly.
  stress::HotSpotLocation paper = hs;
  paper.rule = stress::HotSpotRule::user_points;
  paper.user_distances = {0.004, 0.010};
  auto paper_hot = cr.outputs.add_hot_spot(paper, "hot spot (paper, 4/10 mm)");
  if (!paper_hot) return paper_hot.error();
  cr.paper_hot_spot_row = *paper_hot;
  auto g1 = cr.outputs.add_strain_gauge(Vector3d(toe + 0.4 * spec.wall, y_top, 0),
                                        Vector3d::UnitX(), 0.001, "gauge 0.4t");
  auto g2 = cr.outputs.add_strain_gauge(Vector3d(toe + 1.0 * spec.wall, y_top, 0),
                                        Vector3d::UnitX(), 0.001, "gauge 1.0t");
  if (!g1) return g1.error();
  if (!g2) return g2.error();
  cr.gauge_04t = *g1;
  cr.gauge_10t = *g2;
  cr.nominal_row = cr.outputs.add_normal_stress(Vector3d(0.5 * (ds.x0 + ds.x1), -y_top, 0),
                                                Vector3d::UnitX(), "bottom flange sigma_xx");
  cr.toe_line_first = cr.outputs.num_outputs();
  for (Index n : cr.detail.weld_toe_nodes) {
    stress::HotSpotLocation h = hs;
    h.toe = cr.detail.mesh.node(n);
    auto r = cr.outputs.add_hot_spot(h);
    if (!r) return r.error();
    ++cr.toe_line_count;
  }
  auto rows = cr.outputs.rows(*cr.sub);
  if (!rows) return rows.error();
  auto phi = stress::boundary_modes(cr.boom.data, {stress::HostPoint::at_node(cr.boom.node_x0),
                                                   stress::HostPoint::at_node(cr.boom.node_x1)});
  if (!phi) return phi.error();
  auto fused = stress::FusedStress<N>::build(*rows, *phi);
  if (!fused) return fused.error();
  cr.fused.emplace(std::move(*fused));
  return cr;
}

/// Boom angle about z (rad) from the boom's frame.
inline double boom_angle(const Vec4<double>& theta) {
  const Matrix3d r = rotation_matrix(theta);
  return std::atan2(r(1, 0), r(0, 0));
}

}  // namespace crane
