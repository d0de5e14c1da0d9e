// The stages of an evaluation over (model, data), in the order a step runs them:
// kinematics (rotations) -> markers -> constraints (Phi, B, rates) -> dynamics (mass blocks,
// applied forces); and the block operations the integrator builds on (M x, B x, B^T x,
// B^T B, the modal stiffness and damping). Each body's work goes through the kernels compiled
// for its mode count (model/body_kernels.hpp); nothing here allocates.
#pragma once

#include <algorithm>
#include <cmath>

#include <Eigen/Core>

#include "flexstress/core/euler_parameters.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/model/data.hpp"
#include "flexstress/model/joint_rows.hpp"
#include "flexstress/model/model.hpp"

namespace flexstress {

namespace detail {

/// A body's mass block (column-major, nv x nv).
template <class Scalar>
using ConstColBlock = Eigen::Map<const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>>;
/// A joint's rows on one body (row-major, rows x nv): the body kernels' block operations run
/// along contiguous rows of the body's fixed size.
template <class Scalar>
using ConstRowBlock =
    Eigen::Map<const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>;

}  // namespace detail

/// Stage 1: each body's rotation matrix A(theta).
template <class Scalar>
void update_kinematics(const Model<Scalar>& model, Data<Scalar>& d) {
  const auto& bodies = model.bodies();
  for (std::size_t b = 0; b < bodies.size(); ++b)
    d.rotation[b] = rotation_matrix<Scalar>(d.q.template segment<4>(bodies[b].q_offset + 3));
}

/// The ground frame at d.t and its markers (a model whose ground moves). A ground marker's
/// "convective" part is its whole acceleration: the ground has no unknown velocities.
template <class Scalar>
void update_ground(const Model<Scalar>& model, Data<Scalar>& d) {
  const GroundMotion& gm = model.ground_motion();
  if (!gm.moving) return;
  const auto law = [&](int k) { return law_value(d, k, d.t); };
  const MotionValue<Scalar> x = law(gm.x), y = law(gm.y), z = law(gm.z), angle = law(gm.angle);
  auto& g = d.ground;
  const Vec3<Scalar>& axis = model.ground_axis();
  g.position = Vec3<Scalar>(x.value, y.value, z.value);
  g.velocity = Vec3<Scalar>(x.rate, y.rate, z.rate);
  g.acceleration = Vec3<Scalar>(x.acceleration, y.acceleration, z.acceleration);
  g.rotation = rotation_matrix<Scalar>(from_axis_angle<Scalar>(axis, angle.value));
  g.omega = axis * angle.rate;
  g.alpha = axis * angle.acceleration;
  const auto& slots = model.ground_marker_slots();
  for (std::size_t k = 0; k < slots.size(); ++k) {
    const MarkerState<Scalar>& rest = model.ground_markers()[k];  // values: the local frame
    MarkerState<Scalar>& m = d.markers[static_cast<std::size_t>(slots[k])];
    m.rotation = g.rotation;
    const auto move = [&](const VectorEval<Scalar>& local, VectorEval<Scalar>& e, bool point) {
      const Vec3<Scalar> turned = g.rotation * local.local;
      e.local = local.local;
      e.value = point ? Vec3<Scalar>(g.position + turned) : turned;
      e.velocity = g.omega.cross(turned);
      e.convective = g.alpha.cross(turned) + g.omega.cross(Vec3<Scalar>(g.omega.cross(turned)));
      if (point) {
        e.velocity += g.velocity;
        e.convective += g.acceleration;
      }
    };
    move(rest.origin, m.origin, true);
    move(rest.x, m.x, false);
    move(rest.y, m.y, false);
    move(rest.z, m.z, false);
  }
}

/// Stage 2: the markers joints and forces read (call update_kinematics first). Without rates
/// only positions and axes are evaluated (a Newton iterate needs Phi and B), except on markers
/// of force elements, whose damping reads velocities.
template <class Scalar>
void update_markers(const Model<Scalar>& model, Data<Scalar>& d, bool rates = true) {
  update_ground(model, d);
  const auto& bodies = model.bodies();
  const unsigned* parts = model.slot_parts().data();
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const auto& body = bodies[b];
    if (body.num_markers == 0) continue;
    body.kernels->markers(body.holder.get(), d.q.data() + body.q_offset, d.v.data() + body.v_offset,
                          d.rotation[b], rates, parts + body.first_slot,
                          d.anchors.data() + body.first_slot, d.markers.data() + body.first_slot);
  }
}

/// Stage 3: constraint values, Jacobian blocks, phi_t and conv at d.t (markers up to date;
/// without rates, as update_markers, conv is left out). An inactive joint's rows read 0 = 0.
template <class Scalar>
void update_constraints(const Model<Scalar>& model, Data<Scalar>& d, bool rates = true) {
  JointRows<Scalar>& rows = d.joint_rows;
  const auto& joints = model.joints();
  const auto& bodies = model.bodies();
  const auto& markers = model.markers();
  const bool ground_moves = model.ground_motion().moving;
  Scalar* const phi = d.phi.data();
  Scalar* const phi_t = d.phi_t.data();
  Scalar* const conv = d.conv.data();
  Scalar* const jacobian = d.jacobian.data();
  for (std::size_t k = 0; k < joints.size(); ++k) {
    const auto& j = joints[k];
    const int n = j.equations;
    const auto* bi = j.body_i >= 0 ? &bodies[static_cast<std::size_t>(j.body_i)] : nullptr;
    const auto* bj = j.body_j >= 0 ? &bodies[static_cast<std::size_t>(j.body_j)] : nullptr;
    if (!d.joint_active[k]) {
      std::fill_n(phi + j.row, n, Scalar(0));
      std::fill_n(phi_t + j.row, n, Scalar(0));
      std::fill_n(conv + j.row, n, Scalar(0));
      if (bi) std::fill_n(jacobian + j.jac_i, n * bi->nv, Scalar(0));
      if (bj) std::fill_n(jacobian + j.jac_j, n * bj->nv, Scalar(0));
      continue;
    }
    const auto& mi = markers[static_cast<std::size_t>(j.marker_i)];
    const auto& mj = markers[static_cast<std::size_t>(j.marker_j)];
    const MotionValue<Scalar> law = j.law >= 0 ? law_value(d, j.law, d.t) : MotionValue<Scalar>();
    evaluate_joint_rows(j.kind, d.markers[static_cast<std::size_t>(mi.slot)],
                        d.markers[static_cast<std::size_t>(mj.slot)], j.length, law, rows, rates);
    std::copy_n(rows.phi.begin(), n, phi + j.row);
    std::copy_n(rows.phi_t.begin(), n, phi_t + j.row);
    std::copy_n(rows.conv.begin(), n, conv + j.row);
    if (ground_moves && (!bi || !bj)) {
      // A moving ground's side: its rows times the ground's twist [R_dot; w (ground frame)].
      Eigen::Matrix<Scalar, 6, 1> twist;
      twist << d.ground.velocity, d.ground.rotation.transpose() * d.ground.omega;
      const auto& ground_side = bi ? rows.j : rows.i;
      for (int r = 0; r < n; ++r)
        phi_t[j.row + r] += ground_side[static_cast<std::size_t>(r)].rigid.dot(twist);
    }
    if (bi)
      bi->kernels->jacobian_rows(bi->holder.get(), mi.local, joint_parts_i(j.kind), rows.i.data(),
                                 n, jacobian + j.jac_i);
    if (bj)
      bj->kernels->jacobian_rows(bj->holder.get(), mj.local, joint_parts_j(j.kind), rows.j.data(),
                                 n, jacobian + j.jac_j);
  }
}

/// Adds the generalized force of a force f at the origin of `marker` (on a body) and a moment
/// m on its frame (both global): Q += J_origin^T f + 1/2 sum_k J_k^T (m x e_k). The moment's
/// form follows from w = 1/2 sum_k e_k x e_k' for the marker's axes e_k, so its virtual power
/// m . w is exact for a rigid frame and follows a flexible node's rotation.
template <class Scalar>
void add_marker_load(const Model<Scalar>& model, Data<Scalar>& d, int marker, const Vec3<Scalar>& f,
                     const Vec3<Scalar>* moment = nullptr) {
  const auto& mk = model.markers()[static_cast<std::size_t>(marker)];
  if (mk.body < 0) return;
  const auto& b = model.bodies()[static_cast<std::size_t>(mk.body)];
  const MarkerState<Scalar>& state = d.markers[static_cast<std::size_t>(mk.slot)];
  RowSide<Scalar> side;
  side.add_origin(state, f);
  unsigned parts = MarkerParts::origin;
  if (moment != nullptr) {
    for (int a = 0; a < 3; ++a)
      side.add_axis(state, a, Vec3<Scalar>(moment->cross(state.axis(a).value)), Scalar(0.5));
    parts = MarkerParts::all;
  }
  b.kernels->jacobian_rows(b.holder.get(), mk.local, parts, &side, 1, d.row_scratch.data());
  d.force.segment(b.v_offset, b.nv) += d.row_scratch.head(b.nv);
}

/// A point load's force and moment at d.t from its callback (markers up to date).
template <class Scalar>
void point_load(const Model<Scalar>& model, const Data<Scalar>& d, int k, Vec3<Scalar>& force,
                Vec3<Scalar>& moment) {
  const auto& f = model.forces()[static_cast<std::size_t>(k)];
  const auto& m = d.markers[static_cast<std::size_t>(
      model.markers()[static_cast<std::size_t>(f.marker_i)].slot)];
  double position[3], velocity[3], out_force[3] = {0, 0, 0}, out_moment[3] = {0, 0, 0};
  for (int c = 0; c < 3; ++c) {
    position[c] = double(m.origin.value(c));
    velocity[c] = double(m.origin.velocity(c));
  }
  f.load(double(d.t), position, velocity, out_force, out_moment, f.user);
  for (int c = 0; c < 3; ++c) {
    force(c) = Scalar(out_force[c]);
    moment(c) = Scalar(out_moment[c]);
  }
}

/// The evaluated markers of force element k.
template <class Scalar>
const MarkerState<Scalar>& force_marker(const Model<Scalar>& model, const Data<Scalar>& d, int k,
                                        bool j_side) {
  const auto& f = model.forces()[static_cast<std::size_t>(k)];
  const int m = j_side ? f.marker_j : f.marker_i;
  return d.markers[static_cast<std::size_t>(model.markers()[static_cast<std::size_t>(m)].slot)];
}

/// A hydraulic cylinder's valve command u at d.t.
template <class Scalar>
Scalar valve_command(const Model<Scalar>& model, const Data<Scalar>& d, int k) {
  const auto& f = model.forces()[static_cast<std::size_t>(k)];
  return law_value(d, f.law, d.t).value;
}

/// The force of element k on its marker j's origin (global; marker i gets the opposite).
/// Spring-damper: tension k (L - L0) + c L_dot + preload along the line; hydraulic cylinder:
/// the chamber pressures at d.t and the piston position (dynamics/hydraulic_cylinder.hpp).
template <class Scalar>
Vec3<Scalar> force_element_force(const Model<Scalar>& model, const Data<Scalar>& d, int k) {
  const auto& f = model.forces()[static_cast<std::size_t>(k)];
  const auto& mi = force_marker(model, d, k, false);
  const auto& mj = force_marker(model, d, k, true);
  if (f.kind == ForceKind::hydraulic_cylinder)
    return hydraulics::force<Scalar>(f.hydraulic, d.force_states[static_cast<std::size_t>(k)], d.t,
                                     valve_command(model, d, k), mi.origin.value, mj.origin.value);
  const Vec3<Scalar> dist = mj.origin.value - mi.origin.value;
  const Scalar length = dist.norm();
  if (!(length > Scalar(0))) return Vec3<Scalar>::Zero();
  const Vec3<Scalar> n = dist / length;
  const Scalar rate = n.dot(Vec3<Scalar>(mj.origin.velocity - mi.origin.velocity));
  const auto& p = f.params;
  const Scalar tension = p.stiffness * (length - p.rest_length) + p.damping * rate + p.preload;
  return -tension * n;
}

/// Starts (at initialize) or commits (after an accepted step) the internal states of the force
/// elements at d's state (markers up to date).
template <class Scalar>
void update_force_states(const Model<Scalar>& model, Data<Scalar>& d, bool start) {
  for (std::size_t k = 0; k < model.forces().size(); ++k) {
    const auto& f = model.forces()[k];
    if (f.kind != ForceKind::hydraulic_cylinder) continue;
    const int id = static_cast<int>(k);
    const Scalar u = valve_command(model, d, id);
    const Vec3<Scalar>& ri = force_marker(model, d, id, false).origin.value;
    const Vec3<Scalar>& rj = force_marker(model, d, id, true).origin.value;
    if (start)
      hydraulics::start<Scalar>(f.hydraulic, d.force_states[k], d.t, u, ri, rj);
    else
      hydraulics::commit<Scalar>(f.hydraulic, d.force_states[k], d.t, u, ri, rj);
  }
}

/// Stage 4: mass blocks and the applied generalized force (body effects, then force elements).
template <class Scalar>
void update_dynamics(const Model<Scalar>& model, Data<Scalar>& d) {
  const auto& bodies = model.bodies();
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const auto& body = bodies[b];
    body.kernels->dynamics(
        body.holder.get(), d.q.data() + body.q_offset, d.v.data() + body.v_offset,
        d.v_dot.data() + body.v_offset, d.rotation[b], body.effects, model.gravity(),
        d.mass.data() + body.mass_offset, d.force.data() + body.v_offset,
        body.geometric_offset >= 0 ? d.geometric.data() + body.geometric_offset : nullptr);
  }
  for (std::size_t k = 0; k < model.forces().size(); ++k) {
    const auto& f = model.forces()[k];
    if (f.kind == ForceKind::point_load) {
      Vec3<Scalar> force, moment;
      point_load(model, d, static_cast<int>(k), force, moment);
      add_marker_load(model, d, f.marker_i, force, &moment);
      continue;
    }
    const Vec3<Scalar> on_j = force_element_force(model, d, static_cast<int>(k));
    add_marker_load(model, d, f.marker_j, on_j);
    add_marker_load(model, d, f.marker_i, Vec3<Scalar>(-on_j));
  }
}

/// All stages at d.t (rates: as in update_markers).
template <class Scalar>
void evaluate(const Model<Scalar>& model, Data<Scalar>& d, bool rates = true) {
  update_kinematics(model, d);
  update_markers(model, d, rates);
  update_constraints(model, d, rates);
  update_dynamics(model, d);
}

// ---- block operations ----------------------------------------------------------------------

/// y += M x with the block-diagonal mass matrix of the last update_dynamics.
template <class Scalar, class X, class Y>
void add_mass_times(const Model<Scalar>& model, const Data<Scalar>& d, const X& x, Y& y) {
  for (const auto& b : model.bodies())
    b.kernels->mass_times(b.nv, d.mass.data() + b.mass_offset, x.data() + b.v_offset,
                          y.data() + b.v_offset);
}

/// Starts an iteration matrix s (nv x nv): the mass blocks on the diagonal, zeros on the blocks
/// the joints couple. Entries outside the block pattern are zero since the Data was made and
/// nothing writes them, so s is not cleared whole (for a chain of bodies the pattern is a small
/// part of nv^2).
template <class Scalar, class S>
void start_iteration_matrix(const Model<Scalar>& model, const Data<Scalar>& d, S& s) {
  const auto& bodies = model.bodies();
  for (const auto& [i, j] : model.block_pattern().couplings) {
    const auto& bi = bodies[static_cast<std::size_t>(i)];
    const auto& bj = bodies[static_cast<std::size_t>(j)];
    s.block(bi.v_offset, bj.v_offset, bi.nv, bj.nv).setZero();
    s.block(bj.v_offset, bi.v_offset, bj.nv, bi.nv).setZero();
  }
  for (const auto& b : bodies)
    s.block(b.v_offset, b.v_offset, b.nv, b.nv) =
        detail::ConstColBlock<Scalar>(d.mass.data() + b.mass_offset, b.nv, b.nv);
}

/// s *= factor on the body blocks (the rest of a started iteration matrix is zero).
template <class Scalar, class S>
void scale_body_blocks(const Model<Scalar>& model, S& s, Scalar factor) {
  for (const auto& b : model.bodies()) s.block(b.v_offset, b.v_offset, b.nv, b.nv) *= factor;
}

/// y += B^T x, joint by joint and body by body.
template <class Scalar, class X, class Y>
void add_jacobian_transpose_times(const Model<Scalar>& model, const Data<Scalar>& d, const X& x,
                                  Y& y) {
  for (const auto& k : model.jacobian_blocks())
    k.transpose_times(k.nv, d.jacobian.data() + k.jac, k.rows, x.data() + k.row,
                      y.data() + k.v_offset);
}

/// y = B x (y of num_constraints() entries).
template <class Scalar, class X, class Y>
void jacobian_times(const Model<Scalar>& model, const Data<Scalar>& d, const X& x, Y& y) {
  y.setZero();  // the joints' rows tile it; at once, not a call per joint
  for (const auto& k : model.jacobian_blocks())
    k.rows_times(k.nv, d.jacobian.data() + k.jac, k.rows, x.data() + k.v_offset, y.data() + k.row);
}

/// s += alpha B^T B, joint by joint: a joint's rows touch only its two bodies' columns. The
/// blocks below the diagonal are summed and those above it copied from them (B^T B is
/// symmetric), so the blocks the joints couple must hold nothing else on entry (as
/// start_iteration_matrix leaves them).
template <class Scalar, class S>
void add_constraint_gram(const Model<Scalar>& model, const Data<Scalar>& d, Scalar alpha, S& s) {
  const auto& bodies = model.bodies();
  const auto add = [&](const auto& j, int p, int q) {
    const int body[2] = {j.body_i, j.body_j};
    const int offset[2] = {j.jac_i, j.jac_j};
    const auto& bp = bodies[static_cast<std::size_t>(body[p])];
    const auto& bq = bodies[static_cast<std::size_t>(body[q])];
    bp.kernels->add_gram(bp.nv, d.jacobian.data() + offset[p], j.equations,
                         d.jacobian.data() + offset[q], bq.nv, alpha, &s(bp.v_offset, bq.v_offset),
                         static_cast<int>(s.outerStride()));
  };
  for (std::size_t k = 0; k < model.joints().size(); ++k) {
    if (!d.joint_active[k]) continue;
    const auto& j = model.joints()[k];
    if (j.body_i >= 0) add(j, 0, 0);
    if (j.body_j >= 0) add(j, 1, 1);
    if (j.body_i >= 0 && j.body_j >= 0) {
      const bool i_below = bodies[static_cast<std::size_t>(j.body_i)].v_offset >
                           bodies[static_cast<std::size_t>(j.body_j)].v_offset;
      add(j, i_below ? 0 : 1, i_below ? 1 : 0);
    }
  }
  for (const auto& [i, j] : model.block_pattern().couplings) {
    const auto& low = bodies[static_cast<std::size_t>(std::max(i, j))];
    const auto& high = bodies[static_cast<std::size_t>(std::min(i, j))];
    s.block(high.v_offset, low.v_offset, high.nv, low.nv) =
        s.block(low.v_offset, high.v_offset, low.nv, high.nv).transpose();
  }
}

/// s += k_factor (K + K_G) + c_factor D on the modal blocks (D where the body is damped, K_G
/// of the last update_dynamics where it is geometrically stiffened).
template <class Scalar, class S>
void add_modal_stiffness_damping(const Model<Scalar>& model, const Data<Scalar>& d, S& s,
                                 Scalar k_factor, Scalar c_factor) {
  for (const auto& b : model.bodies()) {
    if (b.modes == 0) continue;
    b.kernels->add_stiffness_damping(
        b.holder.get(), k_factor, c_factor, b.effects.modal_damping,
        b.geometric_offset >= 0 ? d.geometric.data() + b.geometric_offset : nullptr,
        &s(b.v_offset + 6, b.v_offset + 6), static_cast<int>(s.outerStride()));
  }
}

/// s += (k_factor k + c_factor c) r^T r for each spring-damper, r = n^T (J_j - J_i) over its
/// two bodies' velocities (J the markers' origin Jacobians, n the unit vector from i to j): the
/// tangent of its axial force, d(k (L - L0) + c L_dot) = k r dq + c r dv, with the change of
/// n and of J left out, as the tension's transverse stiffness is (it can be negative, and S
/// must stay positive definite; so are negative k and c). Without it a damper of c h of the
/// order of its bodies' masses makes Newton stall: a 1 kg block on a 1e4 N/m spring with
/// c = 1e4 N s/m took 213 iterations per 1 ms step. Hydraulic cylinders are left out (their
/// stiffness comes from the fluid state). Blocks below the diagonal only: add_constraint_gram
/// mirrors them (the builder adds the spring's body pair to the block pattern).
template <class Scalar, class S>
void add_force_element_tangent(const Model<Scalar>& model, Data<Scalar>& d, S& s, Scalar k_factor,
                               Scalar c_factor) {
  const auto& bodies = model.bodies();
  const int ld = static_cast<int>(s.outerStride());
  for (std::size_t k = 0; k < model.forces().size(); ++k) {
    const auto& f = model.forces()[k];
    if (f.kind != ForceKind::spring_damper) continue;
    const Scalar w = k_factor * std::max(Scalar(0), f.params.stiffness) +
                     c_factor * std::max(Scalar(0), f.params.damping);
    const int id = static_cast<int>(k);
    const Vec3<Scalar> dist = force_marker(model, d, id, true).origin.value -
                              force_marker(model, d, id, false).origin.value;
    const Scalar length = dist.norm();
    if (!(w > Scalar(0)) || !(length > Scalar(0))) continue;
    const Vec3<Scalar> n = dist / length;
    const int body[2] = {f.body_i, f.body_j};
    const int marker[2] = {f.marker_i, f.marker_j};
    Scalar* row[2] = {d.row_scratch.data(), d.row_scratch_j.data()};
    for (int side = 0; side < 2; ++side) {
      if (body[side] < 0) continue;
      const auto& mk = model.markers()[static_cast<std::size_t>(marker[side])];
      const auto& b = bodies[static_cast<std::size_t>(body[side])];
      RowSide<Scalar> rs;
      rs.set_origin(d.markers[static_cast<std::size_t>(mk.slot)], n);
      b.kernels->jacobian_rows(b.holder.get(), mk.local, MarkerParts::origin, &rs, 1, row[side]);
      b.kernels->add_gram(b.nv, row[side], 1, row[side], b.nv, w, &s(b.v_offset, b.v_offset), ld);
    }
    if (body[0] >= 0 && body[1] >= 0) {  // r_i = -n^T J_i: the coupling block is -w
      const int low = bodies[static_cast<std::size_t>(body[0])].v_offset >
                              bodies[static_cast<std::size_t>(body[1])].v_offset
                          ? 0
                          : 1;
      const auto& bl = bodies[static_cast<std::size_t>(body[low])];
      const auto& bh = bodies[static_cast<std::size_t>(body[1 - low])];
      bl.kernels->add_gram(bl.nv, row[low], 1, row[1 - low], bh.nv, -w,
                           &s(bl.v_offset, bh.v_offset), ld);
    }
  }
}

/// Moves the coordinates along a velocity-space increment dx (Lie-group update):
/// R += dx_R, theta = theta (x) exp(dx_w) renormalized, p += dx_p.
template <class Scalar, class Q, class X>
void integrate_coordinates(const Model<Scalar>& model, Q& q, const X& dx) {
  for (const auto& b : model.bodies()) {
    q.template segment<3>(b.q_offset) += dx.template segment<3>(b.v_offset);
    auto theta = q.template segment<4>(b.q_offset + 3);
    const EulerParameters<Scalar> turned = normalized<Scalar>(compose<Scalar>(
        EulerParameters<Scalar>(theta),
        exp_rotation<Scalar>(Vec3<Scalar>(dx.template segment<3>(b.v_offset + 3)))));
    theta = turned;
    if (b.modes > 0) q.segment(b.q_offset + 7, b.modes) += dx.segment(b.v_offset + 6, b.modes);
  }
}

/// The first body whose coordinates or velocities are not finite, or -1.
template <class Scalar>
int nonfinite_body(const Model<Scalar>& model, const Data<Scalar>& d) {
  const auto& bodies = model.bodies();
  for (std::size_t b = 0; b < bodies.size(); ++b)
    if (!d.q.segment(bodies[b].q_offset, 7 + bodies[b].modes).allFinite() ||
        !d.v.segment(bodies[b].v_offset, bodies[b].nv).allFinite())
      return static_cast<int>(b);
  return -1;
}

}  // namespace flexstress
