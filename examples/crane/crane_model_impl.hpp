// The crane's assembly (crane_model.hpp): its parts, the welded detail's outputs and the two
// drives, on what precompute_crane made. Included by crane_model.cpp (double) and
// crane_model_float.cpp (float, for the accuracy study) only, so that the programs that build a
// crane do not each compile it.
#pragma once

#include "crane_model.hpp"

namespace crane {

namespace assembly {

/// Handles of the parts both drives share.
struct Parts {
  BodyId boom, cylinder, rod;
  JointId a, b;
  MarkerId cylinder_origin, rod_origin;
};

/// Bodies, markers and the four joints of the crane (A, C, B and the cylinder's slide), in the
/// order the step's matrices follow: boom, cylinder, rod; and the effects `o` asks for. The boom's
/// geometric stiffness comes from precompute_crane (Precomputed::boom_stiffening).
template <class Scalar>
Status add_crane_parts(ModelBuilder<Scalar>& b, const CraneSpec& spec, const Boom& boom,
                       const CraneOptions& o, Parts& p,
                       const reduction::ModalGeometricStiffness* boom_stiffening = nullptr) {
  using V3 = Vec3<Scalar>;
  using M3 = Mat3<Scalar>;
  p.boom = b.add_flexible_body("boom", boom.data, o.modes);
  if (!o.modal_damping) b.set_damping_ratio(p.boom, Scalar(0));
  if (o.geometric_stiffening) {
    if (boom_stiffening == nullptr)
      return make_error(ErrorCode::invalid_argument,
                        "crane: geometric stiffening needs the boom's geometric stiffness "
                        "(precompute_crane)");
    b.add_geometric_stiffening(p.boom, *boom_stiffening);
  }
  // Cylinder and rod on the support and the boom (parts_layout says where).
  const PartsLayout l = parts_layout(spec);
  p.cylinder = b.add_rigid_body("cylinder", Scalar(l.cylinder_mass), l.cylinder_com.cast<Scalar>(),
                                l.cylinder_inertia.cast<Scalar>());
  p.rod = b.add_rigid_body("rod", Scalar(l.rod_mass), l.rod_com.cast<Scalar>(),
                           l.rod_inertia.cast<Scalar>());
  const EulerParameters<Scalar> along_cb = l.orientation.cast<Scalar>();
  b.set_initial_pose(p.cylinder, l.cylinder_position.cast<Scalar>(), along_cb);
  b.set_initial_pose(p.rod, l.rod_position.cast<Scalar>(), along_cb);
  // A: boom on the support (revolute about z). C: cylinder on the support (universal: the
  // revolute about z plus the in-plane cross axis, so the loop is not over-constrained). B: rod
  // on the boom (spherical), 0.125 m below the boom node at 0.32 m.
  const M3 planar = M3::Identity();
  p.a =
      b.add_joint("A", JointKind::revolute,
                  b.add_marker("A on support", b.ground(), -1, l.support_a.cast<Scalar>(), planar),
                  b.add_marker("A on boom", p.boom, boom.node_a, V3::Zero(), planar));
  b.add_joint(
      "C", JointKind::universal,
      b.add_marker("C on support", b.ground(), -1, l.support_c.cast<Scalar>(), planar),
      b.add_marker("C on cylinder", p.cylinder, -1, V3::Zero(), l.cylinder_c_axes.cast<Scalar>()));
  p.b = b.add_joint("B", JointKind::spherical,
                    b.add_marker("B on boom", p.boom, boom.node_b, l.boom_b_offset.cast<Scalar>()),
                    b.add_marker("B on rod", p.rod, -1));
  p.cylinder_origin = b.add_marker("cylinder axis", p.cylinder, -1);
  p.rod_origin = b.add_marker("rod axis", p.rod, -1);
  b.add_joint("slide", JointKind::prismatic, p.cylinder_origin, p.rod_origin);
  if (o.gravity) b.set_gravity(l.gravity.cast<Scalar>());
  if (!o.quadratic_velocity) b.approximate_without_quadratic_velocity();
  return Status::success();
}

/// The detail's outputs on the boom, its hot spot's damage meter and, when `inertia` has rows,
/// the detail's own weight and inertia in them (Precomputed::detail_inertia).
template <class Scalar>
Status add_detail_outputs(ModelBuilder<Scalar>& b, const Detail& d, BodyId boom,
                          const MatrixXd& inertia, OutputRange& outputs, MeterId& meter) {
  outputs = b.add_stress_outputs("detail D", boom, d.fused, d.names);
  if (inertia.rows() > 0) b.add_output_inertia(outputs, inertia);
  auto empty = make_damage_meter<Scalar>();
  if (!empty) return empty.error();
  meter = b.add_damage_meter("hot spot (MPa)", outputs[int(d.hot_spot)], *empty,
                             Scalar(MeterSpec().scale));
  return Status::success();
}

}  // namespace assembly

// make_crane (crane_model.hpp says what it builds).
template <class Scalar>
Result<BasicCrane<Scalar>> make_crane(const CraneSpec& spec, const CraneOptions& options,
                                      const std::vector<double>& t, const std::vector<double>& ds) {
  BasicCrane<Scalar> cr;
  cr.spec = spec;
  cr.options = options;
  if (options.modes < 1 || options.modes > max_runtime_modes)
    return make_error(ErrorCode::invalid_argument, "crane: ", options.modes,
                      " boom modes; from 1 to ", max_runtime_modes);
  auto pre = precompute_crane(spec, options);
  if (!pre) return pre.error();
  cr.boom = std::move(pre->boom);
  cr.detail = std::move(pre->detail);
  const reduction::ModalGeometricStiffness* stiffening =
      pre->boom_stiffening ? &*pre->boom_stiffening : nullptr;
  cr.initial_length = (spec.b - spec.c).norm();

  // The stroke-driven crane: the driver slides the rod along the cylinder's z by the table.
  // The hydraulic crane starts from its equilibrium held at the initial stroke.
  const std::vector<double> t_held = {0.0, 1.0}, ds_held = {0.0, 0.0};
  const auto& t_drive = options.hydraulic ? t_held : t;
  const auto& ds_drive = options.hydraulic ? ds_held : ds;
  std::vector<double> stroke(ds_drive);
  for (double& v : stroke) v += cr.initial_length;
  auto law = TableLaw<Scalar>::create(t_drive, stroke);
  if (!law) return law.error();
  ModelBuilder<Scalar> driven;
  assembly::Parts parts;
  if (Status st = assembly::add_crane_parts(driven, spec, cr.boom, options, parts, stiffening); !st)
    return st.error();
  const JointId driver =
      driven.add_driver("stroke", JointKind::prismatic_driver, parts.cylinder_origin,
                        parts.rod_origin, MotionLaw<Scalar>::from_table(std::move(*law)));
  OutputRange outputs;
  MeterId meter;
  if (Status st = assembly::add_detail_outputs(driven, cr.detail, parts.boom, pre->detail_inertia,
                                               outputs, meter);
      !st)
    return st.error();
  auto driven_model = driven.finalize();
  if (!driven_model) return driven_model.error();
  Data<Scalar> at_rest(*driven_model);
  if (Status st = solve_static_equilibrium(*driven_model, at_rest); !st) return st.error();
  cr.boom_body = parts.boom;
  cr.cylinder = parts.cylinder;
  cr.rod = parts.rod;
  cr.joint_a = parts.a;
  cr.joint_b = parts.b;
  cr.outputs = outputs;
  cr.hot_spot_meter = meter;
  if (!options.hydraulic) {
    cr.model = std::move(*driven_model);
    cr.initial = std::move(at_rest);
    cr.stroke_driver = driver;
    return cr;
  }

  // The hydraulic crane: the cylinder takes over with the cap-side pressure balancing the
  // driver's force at rest, and its valve follows a command cycle made from the stroke cycle
  // by load-flow feedforward at the load at rest. Open loop, like an operator's lever: the
  // stroke follows the plan only roughly.
  const auto& hs = spec.hydraulics;
  const double pi = 3.14159265358979323846, l0 = cr.initial_length;
  const double a1 = pi / 4 * hs.bore * hs.bore, a2 = a1 - pi / 4 * hs.rod * hs.rod;
  const double gain = hs.rated_flow / std::sqrt(hs.rated_drop);
  // The force the driver holds the rod out with.
  const double force = double(driver_effort(*driven_model, at_rest, driver));
  const double p2 = hs.rod_side_pressure, p1 = (force + p2 * a2) / a1;
  if (!(p1 > hs.tank && p1 < hs.supply))
    return make_error(ErrorCode::invalid_argument, "hydraulic crane: holding the load takes ",
                      p1 / 1e5, " bar on the cap side, outside tank (", hs.tank / 1e5,
                      " bar) to supply (", hs.supply / 1e5, " bar)");
  auto plan = TableLaw<double>::create(t, ds);
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
    tc.push_back(tk);
    uc.push_back(std::clamp(rate * std::sqrt(cubes / margin) / gain, -1.0, 1.0));
  }
  auto command = TableLaw<Scalar>::create(tc, uc);
  if (!command) return command.error();
  HydraulicParams<Scalar> hp;
  hp.bore_area = Scalar(a1);
  hp.annulus_area = Scalar(a2);
  hp.stroke = Scalar(hs.stroke);
  hp.length_retracted = Scalar(l0 - hs.initial_position);
  hp.dead_volume_cap = hp.dead_volume_rod = Scalar(hs.dead_volume);
  hp.bulk_modulus = Scalar(hs.bulk_modulus);
  hp.supply_pressure = Scalar(hs.supply);
  hp.tank_pressure = Scalar(hs.tank);
  hp.flow_gain = Scalar(gain);
  ModelBuilder<Scalar> valved;
  assembly::Parts same;
  if (Status st = assembly::add_crane_parts(valved, spec, cr.boom, options, same, stiffening); !st)
    return st.error();
  cr.hydraulic_cylinder = valved.add_hydraulic_cylinder(
      "cylinder", same.cylinder_origin, same.rod_origin, hp,
      MotionLaw<Scalar>::from_table(std::move(*command)), Scalar(p1), Scalar(p2));
  if (Status st = assembly::add_detail_outputs(valved, cr.detail, same.boom, pre->detail_inertia,
                                               outputs, meter);
      !st)
    return st.error();
  auto valved_model = valved.finalize();
  if (!valved_model) return valved_model.error();
  cr.model = std::move(*valved_model);
  cr.initial = Data<Scalar>(cr.model);
  cr.initial.q = at_rest.q;  // the same bodies in the same order
  cr.initial.t = at_rest.t;
  return cr;
}

}  // namespace crane
