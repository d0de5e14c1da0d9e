// The paper's crane as a compile-time scene (dynamics/scene.hpp), for the benchmarks and the
// accuracy study until they move to the runtime model of crane_model.hpp, which the crane
// program uses; both build the same machine.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <flexstress/dynamics/hydraulic_cylinder.hpp>
#include <flexstress/dynamics/implicit_integrator.hpp>
#include <flexstress/dynamics/joints.hpp>
#include <flexstress/dynamics/motion_laws.hpp>
#include <flexstress/dynamics/scene.hpp>
#include <flexstress/dynamics/static_equilibrium.hpp>
#include <flexstress/fe/beam_line.hpp>
#include <flexstress/fe/rhs_attachment_mesh.hpp>
#include <flexstress/reduction/modal_body_data.hpp>
#include <flexstress/reduction/modal_geometric_stiffness.hpp>
#include <flexstress/stress/fused_stress.hpp>
#include <flexstress/stress/host_point.hpp>
#include <flexstress/stress/section_force_modes.hpp>
#include <flexstress/stress/stress_outputs.hpp>
#include <flexstress/stress/sub_model.hpp>
#include <flexstress/stress/sub_model_inertia.hpp>

#include "boom_model.hpp"

namespace crane {

using namespace flexstress;

/// The crane's effects: gravity, the quadratic velocity terms and modal damping of the boom.
using CraneEffects = Effects<Gravity, QuadraticVelocity, ModalDamping>;
/// The same with the hydraulic drive instead of the prescribed stroke.
using CraneHydraulicEffects = Effects<Gravity, QuadraticVelocity, ModalDamping, HydraulicDrive>;

/// N boom modes; StorageLimit chooses fixed-size (default) or dynamic storage (0); Scalar and the
/// effect list are what the accuracy study varies (bench/accuracy_vs_time). Bodies: boom (0),
/// cylinder (1), rod (2). The stroke is prescribed by a driver (joint 4), or, with
/// HydraulicDrive, the cylinder is a force element fed by its valve.
template <int N, int StorageLimit = fixed_storage_limit, class Scalar = double,
          class EffectList = CraneEffects>
using CraneScene = std::conditional_t<
    EffectList::template has<HydraulicDrive>,
    Scene<Scalar, Bodies<FFRFBody<N, Scalar>, RigidBodyT<Scalar>, RigidBodyT<Scalar>>,
          Joints<Revolute<ground, 0>, Universal<ground, 1>, Spherical<0, 2>, Prismatic<1, 2>>,
          EffectList, ForceElements<HydraulicCylinder<1, 2, TableLaw>>, FixedGround<Scalar>,
          StorageLimit>,
    Scene<Scalar, Bodies<FFRFBody<N, Scalar>, RigidBodyT<Scalar>, RigidBodyT<Scalar>>,
          Joints<Revolute<ground, 0>, Universal<ground, 1>, Spherical<0, 2>, Prismatic<1, 2>,
                 PrismaticDriver<1, 2, TableLaw>>,
          EffectList, ForceElements<>, FixedGround<Scalar>, StorageLimit>>;

template <int N, int StorageLimit = fixed_storage_limit, class Scalar = double,
          class EffectList = CraneEffects>
struct Crane {
  using SceneT = CraneScene<N, StorageLimit, Scalar, EffectList>;
  CraneSpec spec;
  Boom boom;
  SceneT scene;
  typename SceneT::State initial;
  fe::RhsAttachmentMesh detail;
  std::optional<stress::SubModel> sub;
  stress::StressOutputs outputs;
  MatrixXd boundary_modes;  ///< Phi_b of the two sub-model ends (12 x modes of the reduction)
  std::optional<stress::FusedStress<N, Scalar>> fused;
  Index hot_spot_row = -1, paper_hot_spot_row = -1, gauge_04t = -1, gauge_10t = -1,
        nominal_row = -1;
  Index toe_line_first = -1, toe_line_count = 0;
};

/// The stroke-driven crane (make_crane without HydraulicDrive).
template <int N, int StorageLimit, class Scalar, class EffectList>
Result<Crane<N, StorageLimit, Scalar, EffectList>> make_stroke_crane(
    const CraneSpec& spec, const std::vector<double>& t, const std::vector<double>& stroke_offset) {
  using V3 = Vec3<Scalar>;
  using M3 = Mat3<Scalar>;
  Crane<N, StorageLimit, Scalar, EffectList> cr;
  cr.spec = spec;
  auto boom = make_boom(spec, N);
  if (!boom) return boom.error();
  cr.boom = std::move(*boom);
  auto body = FFRFBody<N, Scalar>::from_modal_data(cr.boom.data);
  if (!body) return body.error();
  if constexpr (EffectList::template has<GeometricStiffening>) {
    // The boom's inertial loads leave it through A and B: both clamped for the stress states
    // (docs/crane.md).
    auto g = reduction::modal_geometric_stiffness(cr.boom.mesh, cr.boom.data,
                                                  reduction::clamp_interface_nodes(cr.boom.data));
    if (!g) return g.error();
    if (Status st = body->set_geometric_stiffness(*g); !st) return st.error();
  }
  auto& sc = cr.scene;
  sc.template body<0>() = *body;
  // Cylinder (1) and rod (2): slender rigid bodies, frames with z along C -> B, origins at C and
  // B; centres of mass half a length inside.
  const double lc = spec.cylinder_length, lr = spec.rod_length;
  const double ic = spec.cylinder_mass * lc * lc / 12, ir = spec.rod_mass * lr * lr / 12;
  sc.template body<1>() = RigidBodyT<Scalar>::rigid(
      Scalar(spec.cylinder_mass), V3(0, 0, Scalar(lc / 2)),
      Vector3d(ic, ic, 1e-3 * ic).asDiagonal().toDenseMatrix().cast<Scalar>());
  sc.template body<2>() = RigidBodyT<Scalar>::rigid(
      Scalar(spec.rod_mass), V3(0, 0, Scalar(-lr / 2)),
      Vector3d(ir, ir, 1e-3 * ir).asDiagonal().toDenseMatrix().cast<Scalar>());
  const Vector3d cb = (spec.b - spec.c).normalized();
  const Matrix3d frame = frame_with_z_axis<double>(cb);
  const M3 planar = M3::Identity();  // revolute axes along global z
  const Matrix3d to_local = frame.transpose();
  auto& s = cr.initial;
  s.template coordinates<1>().position = spec.c.cast<Scalar>();
  s.template coordinates<1>().theta = from_rotation_matrix<double>(frame).cast<Scalar>();
  s.template coordinates<2>().position = spec.b.cast<Scalar>();
  s.template coordinates<2>().theta = from_rotation_matrix<double>(frame).cast<Scalar>();
  // A: boom on the support. C: cylinder on the support (universal: the revolute about z plus
  // the in-plane cross axis, so the loop is not over-constrained). B: rod on the boom
  // (spherical), 0.125 m below the boom node at 0.32 m.
  const V3 zero = V3::Zero();
  sc.template joint<0>().marker_i = fixed_marker<Scalar>(spec.a.cast<Scalar>(), planar);
  sc.template joint<0>().marker_j =
      make_marker(sc.template body<0>(), cr.boom.node_a, zero, planar);
  sc.template joint<1>().marker_i = fixed_marker<Scalar>(spec.c.cast<Scalar>(), planar);
  const Matrix3d cross = frame_with_z_axis<double>(Vector3d(cb.y(), -cb.x(), 0));
  sc.template joint<1>().marker_j =
      make_marker(sc.template body<1>(), -1, zero, M3((to_local * cross).cast<Scalar>()));
  sc.template joint<2>().marker_i =
      make_marker(sc.template body<0>(), cr.boom.node_b,
                  V3((spec.b - Vector3d(spec.b_node_x, 0, 0)).cast<Scalar>()));
  sc.template joint<2>().marker_j = make_marker(sc.template body<2>(), -1, zero);
  sc.template joint<3>().marker_i = make_marker(sc.template body<1>(), -1, zero);
  sc.template joint<3>().marker_j = make_marker(sc.template body<2>(), -1, zero);
  sc.template joint<4>().marker_i = make_marker(sc.template body<1>(), -1, zero);
  sc.template joint<4>().marker_j = make_marker(sc.template body<2>(), -1, zero);
  std::vector<double> stroke(stroke_offset);
  for (double& v : stroke) v += (spec.b - spec.c).norm();
  auto law = TableLaw<Scalar>::create(t, stroke);
  if (!law) return law.error();
  sc.template joint<4>().params.law = *law;
  if (Status st = solve_static_equilibrium(sc, s); !st) return st.error();

  // Detail D: the RHS segment with the welded rib, tied to the boom at its ends.
  fe::RhsAttachmentSpec ds;
  ds.density = spec.submodel_density;
  ds.x0 = spec.submodel_x0;
  ds.x1 = spec.submodel_x1;
  ds.max_element_length = spec.submodel_max_element_length;
  ds.wall = spec.wall;
  ds.formulation = spec.formulation;
  auto detail = fe::make_rhs_attachment_mesh(ds);
  if (!detail) return detail.error();
  cr.detail = std::move(*detail);
  const bool forced = spec.submodel_drive == stress::AttachmentDrive::force;
  if (forced && spec.attach_between_nodes)
    return make_error(ErrorCode::invalid_argument,
                      "crane: a force-driven sub-model end needs a boom node there "
                      "(attach_between_nodes is set)");
  auto sub = stress::SubModel::build(
      cr.detail.mesh, {{Vector3d(ds.x0, 0, 0), cr.detail.end_section_x0},
                       {Vector3d(ds.x1, 0, 0), cr.detail.end_section_x1, spec.submodel_drive}});
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
  auto phi = stress::boundary_modes(cr.boom.data,
                                    {host_point(cr.boom, spec.submodel_x0, spec.interpolation),
                                     host_point(cr.boom, spec.submodel_x1, spec.interpolation)});
  if (!phi) return phi.error();
  cr.boundary_modes = std::move(*phi);
  if (forced) {
    // The x1 end carries the force and moment of the boom element inside the segment there.
    Index inner = -1;
    const auto& beams = cr.boom.mesh.beams();
    for (std::size_t e = 0; e < beams.size(); ++e)
      for (int end = 0; end < 2; ++end)
        if (beams[e].nodes[std::size_t(end)] == cr.boom.node_x1 &&
            cr.boom.mesh.node(beams[e].nodes[std::size_t(1 - end)]).x() < spec.submodel_x1)
          inner = static_cast<Index>(e);
    auto f = stress::section_force_modes(cr.boom.mesh, cr.boom.data, inner, cr.boom.node_x1);
    if (!f) return f.error();
    cr.boundary_modes.bottomRows(6) = *f;
  }
  auto fused = stress::FusedStress<N, Scalar>::build(*rows, cr.boundary_modes);
  if (!fused) return fused.error();
  cr.fused.emplace(std::move(*fused));
  return cr;
}

/// EffectList without HydraulicDrive: the stroke-driven crane the hydraulic one starts from.
template <class List, class... Kept>
struct without_hydraulics;
template <class... Kept>
struct without_hydraulics<Effects<>, Kept...> {
  using type = Effects<Kept...>;
};
template <class E, class... Rest, class... Kept>
struct without_hydraulics<Effects<E, Rest...>, Kept...> {
  using type = typename std::conditional_t<std::is_same_v<E, HydraulicDrive>,
                                           without_hydraulics<Effects<Rest...>, Kept...>,
                                           without_hydraulics<Effects<Rest...>, Kept..., E>>::type;
};

/// The hydraulic crane. The stroke-driven crane held at its initial stroke gives the static
/// equilibrium and the cylinder force there (the driver's reaction); the cylinder then takes over
/// with the cap-side pressure balancing that force, and its valve follows a command cycle made
/// from the stroke cycle by load-flow feedforward at the load at rest (below; docs/crane.md).
/// Open loop, like an operator's lever: the stroke follows the plan only roughly.
template <int N, int StorageLimit, class Scalar, class EffectList>
Result<Crane<N, StorageLimit, Scalar, EffectList>> make_hydraulic_crane(
    const CraneSpec& spec, const std::vector<double>& t, const std::vector<double>& stroke_offset) {
  using Base = Crane<N, StorageLimit, Scalar, typename without_hydraulics<EffectList>::type>;
  auto made =
      make_stroke_crane<N, StorageLimit, Scalar, typename without_hydraulics<EffectList>::type>(
          spec, {0.0, 1.0}, {0.0, 0.0});
  if (!made) return made.error();
  Base& b = *made;
  Crane<N, StorageLimit, Scalar, EffectList> cr;
  cr.spec = spec;
  auto& sc = cr.scene;
  sc.bodies = b.scene.bodies;
  sc.gravity = b.scene.gravity;
  detail::for_each_index(
      [&](auto k) {
        constexpr int K = static_cast<int>(decltype(k)::value);
        sc.template joint<K>().marker_i = b.scene.template joint<K>().marker_i;
        sc.template joint<K>().marker_j = b.scene.template joint<K>().marker_j;
        sc.template joint<K>().params = b.scene.template joint<K>().params;
      },
      std::make_index_sequence<4>{});
  const auto& hs = spec.hydraulics;
  const double pi = 3.14159265358979323846, l0 = (spec.b - spec.c).norm();
  const double a1 = pi / 4 * hs.bore * hs.bore, a2 = a1 - pi / 4 * hs.rod * hs.rod;
  const double gain = hs.rated_flow / std::sqrt(hs.rated_drop);
  auto& cyl = sc.template force<0>();
  cyl.marker_i = b.scene.template joint<3>().marker_i;  // the cylinder's origin, at C
  cyl.marker_j = b.scene.template joint<3>().marker_j;  // the rod's origin, at B
  auto& hp = cyl.params;
  hp.bore_area = Scalar(a1);
  hp.annulus_area = Scalar(a2);
  hp.stroke = Scalar(hs.stroke);
  hp.length_retracted = Scalar(l0 - hs.initial_position);
  hp.dead_volume_cap = hp.dead_volume_rod = Scalar(hs.dead_volume);
  hp.bulk_modulus = Scalar(hs.bulk_modulus);
  hp.supply_pressure = Scalar(hs.supply);
  hp.tank_pressure = Scalar(hs.tank);
  hp.flow_gain = Scalar(gain);
  // The driver's reaction: M v_dot = Q - B^T lambda with the driver's row d phi / d r_rod = n
  // (the cylinder axis), so the cylinder pushes the rod out with F = -lambda.
  const double force = -double(b.initial.lambda(Base::SceneT::nc - 1));
  const double p2 = hs.rod_side_pressure, p1 = (force + p2 * a2) / a1;
  if (!(p1 > hs.tank && p1 < hs.supply))
    return make_error(ErrorCode::invalid_argument, "hydraulic crane: holding the load takes ",
                      p1 / 1e5, " bar on the cap side, outside tank (", hs.tank / 1e5,
                      " bar) to supply (", hs.supply / 1e5, " bar)");
  auto plan = TableLaw<double>::create(t, stroke_offset);
  if (!plan) return plan.error();
  // Steady flow through both valve edges at the load F (Merritt, ch. 5, for a differential
  // cylinder): extending p1 = ps - (A1 v / K u)^2, p2 = pt + (A2 v / K u)^2 and p1 A1 - p2 A2 = F
  // give (K u)^2 = (A1^3 + A2^3) v^2 / (ps A1 - pt A2 - F); retracting (supply to the rod side)
  // (K u)^2 = (A1^3 + A2^3) v^2 / (F - pt A1 + ps A2).
  const double cubes = a1 * a1 * a1 + a2 * a2 * a2;
  if (!(hs.supply * a1 - hs.tank * a2 - force > 0 && force - hs.tank * a1 + hs.supply * a2 > 0))
    return make_error(ErrorCode::invalid_argument, "hydraulic crane: the load ", force,
                      " N is beyond what the supply pressure can lift or lower");
  std::vector<double> tc, uc;
  for (double tk = t.front(); tk < t.back() + 0.5 * hs.command_interval;
       tk += hs.command_interval) {
    const double rate = (*plan)(tk).rate;
    const double margin =
        rate >= 0 ? hs.supply * a1 - hs.tank * a2 - force : force - hs.tank * a1 + hs.supply * a2;
    const double u = rate * std::sqrt(cubes / margin) / gain;
    tc.push_back(tk);
    uc.push_back(std::clamp(u, -1.0, 1.0));
  }
  auto command = TableLaw<Scalar>::create(tc, uc);
  if (!command) return command.error();
  hp.command = std::move(*command);
  cr.initial.q = b.initial.q;
  cr.initial.t = b.initial.t;
  std::get<0>(cr.initial.force_states).p1 = Scalar(p1);
  std::get<0>(cr.initial.force_states).p2 = Scalar(p2);
  cr.boom = std::move(b.boom);
  cr.detail = std::move(b.detail);
  cr.sub = std::move(b.sub);
  cr.outputs = std::move(b.outputs);
  cr.boundary_modes = std::move(b.boundary_modes);
  cr.fused = std::move(b.fused);
  cr.hot_spot_row = b.hot_spot_row;
  cr.paper_hot_spot_row = b.paper_hot_spot_row;
  cr.gauge_04t = b.gauge_04t;
  cr.gauge_10t = b.gauge_10t;
  cr.nominal_row = b.nominal_row;
  cr.toe_line_first = b.toe_line_first;
  cr.toe_line_count = b.toe_line_count;
  return cr;
}

/// Builds the crane with stroke table (t, stroke offset), puts it in static equilibrium at
/// t = 0 and precomputes the sub-model. Fails with the first error. With HydraulicDrive in the
/// effect list the stroke table becomes the valve's command cycle (make_hydraulic_crane).
template <int N, int StorageLimit = fixed_storage_limit, class Scalar = double,
          class EffectList = CraneEffects>
Result<Crane<N, StorageLimit, Scalar, EffectList>> make_crane(
    const CraneSpec& spec, const std::vector<double>& t, const std::vector<double>& stroke_offset) {
  if constexpr (EffectList::template has<HydraulicDrive>) {
    return make_hydraulic_crane<N, StorageLimit, Scalar, EffectList>(spec, t, stroke_offset);
  } else {
    return make_stroke_crane<N, StorageLimit, Scalar, EffectList>(spec, t, stroke_offset);
  }
}

/// The 12 inertia coordinates of the detail (stress/sub_model_inertia.hpp) from the boom frame's
/// acceleration, angular velocity and angular acceleration and gravity, in the boom frame.
template <class SceneT>
Eigen::Matrix<typename SceneT::scalar_type, 12, 1> boom_inertia_coordinates(
    const SceneT& scene, const typename SceneT::State& s) {
  using Scalar = typename SceneT::scalar_type;
  const Mat3<Scalar> a = rotation_matrix(s.template coordinates<0>().theta);
  return stress::inertia_coordinates<Scalar>(
      Vec3<Scalar>(a.transpose() * s.v_dot.template head<3>()),
      Vec3<Scalar>(a.transpose() * scene.gravity), Vec3<Scalar>(s.v.template segment<3>(3)),
      Vec3<Scalar>(s.v_dot.template segment<3>(3)));
}

/// Boom angle about z (rad) from the boom's frame.
template <class Scalar>
double boom_angle(const Vec4<Scalar>& theta) {
  const Mat3<Scalar> r = rotation_matrix(theta);
  return std::atan2(double(r(1, 0)), double(r(0, 0)));
}

}  // namespace crane
