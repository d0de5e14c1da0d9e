// Read-outs and runtime changes by handle, over (model, data). Read-outs read the state (and,
// for marker frames and reactions, evaluate what they need into the data's workspace); runtime
// changes are counted in Data::revision, and the next step restarts from the state as
// initialize() does (a joint switched on is assembled and the velocities projected: a perfectly
// plastic capture that keeps momentum).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <type_traits>

#include <Eigen/Core>

#include "flexstress/core/euler_parameters.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/model/data.hpp"
#include "flexstress/model/model.hpp"
#include "flexstress/model/pipeline.hpp"

namespace flexstress {

/// A frame in the global frame: origin and axes (columns).
template <class Scalar>
struct Frame {
  Vec3<Scalar> origin = Vec3<Scalar>::Zero();
  Mat3<Scalar> axes = Mat3<Scalar>::Identity();
};

/// Position R of a body's frame (global).
template <class Scalar>
Vec3<Scalar> body_position(const Model<Scalar>& m, const Data<Scalar>& d, BodyId b) {
  return d.q.template segment<3>(m.body(b).q_offset);
}
/// Orientation of a body's frame (Euler parameters, scalar first).
template <class Scalar>
EulerParameters<Scalar> body_orientation(const Model<Scalar>& m, const Data<Scalar>& d, BodyId b) {
  return d.q.template segment<4>(m.body(b).q_offset + 3);
}
/// Velocity R_dot of a body's frame origin (global).
template <class Scalar>
Vec3<Scalar> body_velocity(const Model<Scalar>& m, const Data<Scalar>& d, BodyId b) {
  return d.v.template segment<3>(m.body(b).v_offset);
}
/// Angular velocity of a body (body frame).
template <class Scalar>
Vec3<Scalar> body_angular_velocity(const Model<Scalar>& m, const Data<Scalar>& d, BodyId b) {
  return d.v.template segment<3>(m.body(b).v_offset + 3);
}
/// A read-only view into a Data's vector (no copy, no allocation; valid while the Data is).
template <class Scalar>
using DataSegment = Eigen::VectorBlock<const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>>;

/// Modal coordinates of a flexible body (empty for a rigid one), as a view.
template <class Scalar>
DataSegment<Scalar> modal_coordinates(const Model<Scalar>& m, const Data<Scalar>& d, BodyId b) {
  return d.q.segment(m.body(b).q_offset + 7, m.body(b).modes);
}

/// A marker evaluated in full (origin and axes with their rates) at d's coordinates, whatever
/// parts the step evaluates; allocation-free.
template <class Scalar>
MarkerState<Scalar> marker_state(const Model<Scalar>& m, const Data<Scalar>& d, MarkerId id) {
  const auto& mk = m.marker(id);
  if (mk.body < 0) return d.markers[static_cast<std::size_t>(mk.slot)];
  const auto& b = m.bodies()[static_cast<std::size_t>(mk.body)];
  const Mat3<Scalar> a = rotation_matrix<Scalar>(d.q.template segment<4>(b.q_offset + 3));
  MarkerState<Scalar> state;
  b.kernels->marker(b.holder.get(), mk.local, d.q.data() + b.q_offset, d.v.data() + b.v_offset, a,
                    d.anchors[static_cast<std::size_t>(mk.slot)], state);
  return state;
}

namespace detail {
/// The frame of evaluated vectors: their global values, or their body-frame ones (`local`).
template <class Scalar>
Frame<Scalar> frame_of(const MarkerState<Scalar>& state, bool local) {
  const auto pick = [&](const VectorEval<Scalar>& e) { return local ? e.local : e.value; };
  Frame<Scalar> f;
  f.origin = pick(state.origin);
  f.axes << pick(state.x), pick(state.y), pick(state.z);
  return f;
}
}  // namespace detail

/// A marker's frame at the current state (global; on a flexible body it follows its node).
template <class Scalar>
Frame<Scalar> marker_frame(const Model<Scalar>& m, const Data<Scalar>& d, MarkerId id) {
  return detail::frame_of(marker_state(m, d, id), false);
}

/// A marker's frame in its body's frame, deformation included: origin u = c + Psi p and axes
/// c_k + Psi_k p (linear in the modal coordinates; the elastic part is u minus its value at
/// p = 0). On the ground, the ground frame's.
template <class Scalar>
Frame<Scalar> marker_frame_in_body(const Model<Scalar>& m, const Data<Scalar>& d, MarkerId id) {
  return detail::frame_of(marker_state(m, d, id), true);
}

/// Force and moment a joint applies to the body of its marker j, at marker j's origin, in the
/// joint frame (marker i's axes): from the multipliers, -B_j^T lambda (M v_dot + B^T lambda =
/// Q). Valid after initialize() or a step.
template <class Scalar>
struct Reaction {
  Vec3<Scalar> force = Vec3<Scalar>::Zero();
  Vec3<Scalar> moment = Vec3<Scalar>::Zero();
};
namespace detail {
/// B_rigid^T lambda over a joint's rows on one body, row by row: a dynamic-size product would
/// evaluate into a heap temporary.
template <class Scalar, class Lambda>
Eigen::Matrix<Scalar, 6, 1> rigid_columns_times(const ConstRowBlock<Scalar>& rows,
                                                const Lambda& lambda) {
  Eigen::Matrix<Scalar, 6, 1> g = Eigen::Matrix<Scalar, 6, 1>::Zero();
  for (Eigen::Index r = 0; r < rows.rows(); ++r)
    g += lambda(r) * rows.row(r).template head<6>().transpose();
  return g;
}
}  // namespace detail

template <class Scalar>
Reaction<Scalar> joint_reaction(const Model<Scalar>& m, const Data<Scalar>& d, JointId id) {
  const auto& j = m.joint(id);
  const Frame<Scalar> fi = marker_frame(m, d, MarkerId{j.marker_i});
  const Frame<Scalar> fj = marker_frame(m, d, MarkerId{j.marker_j});
  Vec3<Scalar> force = Vec3<Scalar>::Zero(), moment = Vec3<Scalar>::Zero();
  const auto lambda = d.lambda.segment(j.row, j.equations);
  if (j.body_j >= 0) {
    const auto& b = m.bodies()[static_cast<std::size_t>(j.body_j)];
    const detail::ConstRowBlock<Scalar> rows(d.jacobian.data() + j.jac_j, j.equations, b.nv);
    const Eigen::Matrix<Scalar, 6, 1> g = -detail::rigid_columns_times(rows, lambda);
    force = g.template head<3>();
    // Moment about the frame origin (body axes) to the global moment about marker j's origin.
    const Mat3<Scalar> a = rotation_matrix<Scalar>(d.q.template segment<4>(b.q_offset + 3));
    const Vec3<Scalar> r = fj.origin - d.q.template segment<3>(b.q_offset);
    moment = a * g.template tail<3>() - r.cross(force);
  } else if (j.body_i >= 0) {
    // Marker j on the ground: the reaction on the ground is minus that on body i.
    const auto& b = m.bodies()[static_cast<std::size_t>(j.body_i)];
    const detail::ConstRowBlock<Scalar> rows(d.jacobian.data() + j.jac_i, j.equations, b.nv);
    const Eigen::Matrix<Scalar, 6, 1> g = detail::rigid_columns_times(rows, lambda);
    force = g.template head<3>();
    const Mat3<Scalar> a = rotation_matrix<Scalar>(d.q.template segment<4>(b.q_offset + 3));
    const Vec3<Scalar> r = fj.origin - d.q.template segment<3>(b.q_offset);
    moment = a * g.template tail<3>() - r.cross(force);
  }
  Reaction<Scalar> out;
  out.force = fi.axes.transpose() * force;
  out.moment = fi.axes.transpose() * moment;
  return out;
}

/// Largest constraint violation |Phi| of the last evaluation (a step refreshes it at the state
/// it returns unless Settings::refresh_workspace is off).
template <class Scalar>
Scalar constraint_violation(const Model<Scalar>&, const Data<Scalar>& d) {
  return max_abs(d.phi);
}

/// Largest violation of the joints' velocity equations, |B v + Phi_t|, with the Jacobian of the
/// last evaluation (as constraint_violation). Index-3 steps keep Phi on the joints, not this:
/// a value that grows from step to step is drift, which ImplicitSettings::project_velocities
/// removes (docs/dynamics.md, the flexible slider crank).
template <class Scalar>
Scalar velocity_violation(const Model<Scalar>& model, const Data<Scalar>& d) {
  Scalar worst = Scalar(0);
  for (const auto& j : model.joints()) {
    std::array<Scalar, max_joint_equations> rows{};
    for (int side = 0; side < 2; ++side) {
      const int body = side == 0 ? j.body_i : j.body_j;
      if (body < 0) continue;
      const auto& b = model.bodies()[static_cast<std::size_t>(body)];
      b.kernels->rows_times(b.nv, d.jacobian.data() + (side == 0 ? j.jac_i : j.jac_j), j.equations,
                            d.v.data() + b.v_offset, rows.data());
    }
    for (int r = 0; r < j.equations; ++r)
      worst = std::max(worst, std::abs(rows[static_cast<std::size_t>(r)] + d.phi_t(j.row + r)));
  }
  return worst;
}

/// Energies at the state: kinetic, gravity potential, elastic (modes) and springs.
template <class Scalar>
struct Energy {
  Scalar kinetic = Scalar(0), gravity = Scalar(0), elastic = Scalar(0), springs = Scalar(0);
  Scalar total() const { return kinetic + gravity + elastic + springs; }
};

/// The mechanical energy of one body (kinetic, gravity, elastic; no springs), allocation-free.
template <class Scalar>
Energy<Scalar> body_energy(const Model<Scalar>& m, const Data<Scalar>& d, BodyId id) {
  const auto& b = m.body(id);
  const Mat3<Scalar> a = rotation_matrix<Scalar>(d.q.template segment<4>(b.q_offset + 3));
  Energy<Scalar> e;
  Scalar potential = Scalar(0), damping = Scalar(0);
  b.kernels->energies(b.holder.get(), d.q.data() + b.q_offset, d.v.data() + b.v_offset, a,
                      m.gravity(), &e.kinetic, &e.elastic, &potential, &damping);
  if (m.has_gravity()) e.gravity = potential;
  return e;
}

/// A force element's internal state (a hydraulic cylinder's chamber pressures, piston position
/// and valve flows) after the last accepted step.
template <class Scalar>
const HydraulicState<Scalar>& force_state(const Model<Scalar>&, const Data<Scalar>& d, ForceId id) {
  return d.force_states[static_cast<std::size_t>(id.index)];
}
template <class Scalar>
Energy<Scalar> energy(const Model<Scalar>& m, Data<Scalar>& d) {
  Energy<Scalar> e;
  update_kinematics(m, d);
  update_markers(m, d);
  const auto& bodies = m.bodies();
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    const auto& b = bodies[k];
    Scalar kinetic, elastic, potential, damping;
    b.kernels->energies(b.holder.get(), d.q.data() + b.q_offset, d.v.data() + b.v_offset,
                        d.rotation[k], m.gravity(), &kinetic, &elastic, &potential, &damping);
    e.kinetic += kinetic;
    e.elastic += elastic;
    if (m.has_gravity()) e.gravity += potential;
  }
  for (const auto& f : m.forces()) {
    if (f.kind != ForceKind::spring_damper) continue;
    const auto& mi =
        d.markers[static_cast<std::size_t>(m.markers()[static_cast<std::size_t>(f.marker_i)].slot)];
    const auto& mj =
        d.markers[static_cast<std::size_t>(m.markers()[static_cast<std::size_t>(f.marker_j)].slot)];
    const Scalar l = (mj.origin.value - mi.origin.value).norm();
    e.springs +=
        Scalar(0.5) * f.params.stiffness * (l - f.params.rest_length) * (l - f.params.rest_length) +
        f.params.preload * l;
  }
  return e;
}

/// A flexible body's modal velocities p_dot (empty for a rigid body), as a view.
template <class Scalar>
DataSegment<Scalar> modal_velocities(const Model<Scalar>& m, const Data<Scalar>& d, BodyId id) {
  const auto& b = m.body(id);
  return d.v.segment(b.v_offset + 6, b.modes);
}

/// Linear momentum and angular momentum about the global origin (global).
template <class Scalar>
struct Momentum {
  Vec3<Scalar> linear = Vec3<Scalar>::Zero();
  Vec3<Scalar> angular = Vec3<Scalar>::Zero();
};
/// The momentum of one body, or of all bodies (`body` left out).
template <class Scalar>
Momentum<Scalar> momentum(const Model<Scalar>& m, const Data<Scalar>& d, BodyId body = BodyId{-1}) {
  Momentum<Scalar> total;
  for (std::size_t k = 0; k < m.bodies().size(); ++k) {
    if (body.index >= 0 && static_cast<int>(k) != body.index) continue;
    const auto& b = m.bodies()[k];
    const Mat3<Scalar> a = rotation_matrix<Scalar>(d.q.template segment<4>(b.q_offset + 3));
    Vec3<Scalar> linear, angular;
    b.kernels->momentum(b.holder.get(), d.q.data() + b.q_offset, d.v.data() + b.v_offset, a,
                        &linear, &angular);
    total.linear += linear;
    total.angular += angular;
  }
  return total;
}

/// What a driver exerts along its coordinate: the force (prismatic, N) pushing marker j along
/// +z_i, or the moment (revolute, N m) turning it about z_i, from the multiplier of its
/// equation (M v_dot = Q - B^T lambda). Zero for a joint that is not a driver.
template <class Scalar>
Scalar driver_effort(const Model<Scalar>& m, const Data<Scalar>& d, JointId id) {
  const auto& j = m.joint(id);
  return is_driver(j.kind) ? -d.lambda(j.row) : Scalar(0);
}

/// What a driver prescribes at d.t: its current law's value, rate and acceleration (an input
/// law's as interpolated within the step). Zero for a joint that is not a driver.
template <class Scalar>
MotionValue<Scalar> driver_motion(const Model<Scalar>& m, const Data<Scalar>& d, JointId id) {
  const auto& j = m.joint(id);
  return j.law >= 0 ? law_value(d, j.law, d.t) : MotionValue<Scalar>();
}

/// A joint's own coordinate and its rate at the state, from its markers as they are.
template <class Scalar>
struct JointCoordinate {
  bool defined = false;  ///< only revolute and prismatic joints and their drivers have one
  Scalar value = Scalar(0), rate = Scalar(0);
};

/// A revolute joint's (or revolute driver's) angle from x_i to x_j about z_i, in (-pi, pi], or
/// a prismatic joint's (or prismatic driver's) stroke (r_j - r_i) . z_i, with its rate: for a
/// flexible body's marker the node's own turning or travel, elastic wobble included (a
/// driver's law is what the coordinate is held to).
template <class Scalar>
JointCoordinate<Scalar> joint_coordinate(const Model<Scalar>& m, const Data<Scalar>& d,
                                         JointId id) {
  const auto& j = m.joint(id);
  JointCoordinate<Scalar> c;
  const bool turning = j.kind == JointKind::revolute || j.kind == JointKind::revolute_driver;
  const bool sliding = j.kind == JointKind::prismatic || j.kind == JointKind::prismatic_driver;
  if (!turning && !sliding) return c;
  const MarkerState<Scalar> mi = marker_state(m, d, MarkerId{j.marker_i});
  const MarkerState<Scalar> mj = marker_state(m, d, MarkerId{j.marker_j});
  c.defined = true;
  if (turning) {  // theta = atan2(y_i . x_j, x_i . x_j)
    const Scalar a = mi.x.value.dot(mj.x.value), b = mi.y.value.dot(mj.x.value);
    const Scalar a_dot = mi.x.velocity.dot(mj.x.value) + mi.x.value.dot(mj.x.velocity);
    const Scalar b_dot = mi.y.velocity.dot(mj.x.value) + mi.y.value.dot(mj.x.velocity);
    using std::atan2;
    c.value = atan2(b, a);
    c.rate = (a * b_dot - b * a_dot) / (a * a + b * b);
  } else {
    const Vec3<Scalar> r = mj.origin.value - mi.origin.value;
    c.value = r.dot(mi.z.value);
    c.rate = Vec3<Scalar>(mj.origin.velocity - mi.origin.velocity).dot(mi.z.value) +
             r.dot(mi.z.velocity);
  }
  return c;
}

/// A joint's equations at the last evaluation (evaluate() or a step): Phi, Phi_t, the
/// convective term (the time derivative of B v + Phi_t without B v_dot) and its rows of B
/// (equations x the model's velocities; zero outside its two bodies).
template <class Scalar>
struct JointEquations {
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> phi, phi_t, conv;
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> jacobian;
};
template <class Scalar>
JointEquations<Scalar> joint_equations(const Model<Scalar>& m, const Data<Scalar>& d, JointId id) {
  const auto& j = m.joint(id);
  JointEquations<Scalar> e;
  e.phi = d.phi.segment(j.row, j.equations);
  e.phi_t = d.phi_t.segment(j.row, j.equations);
  e.conv = d.conv.segment(j.row, j.equations);
  e.jacobian.setZero(j.equations, m.num_velocities());
  const int side_body[2] = {j.body_i, j.body_j};
  const int side_block[2] = {j.jac_i, j.jac_j};
  for (int side = 0; side < 2; ++side) {
    if (side_body[side] < 0) continue;
    const auto& b = m.bodies()[static_cast<std::size_t>(side_body[side])];
    e.jacobian.middleCols(b.v_offset, b.nv) =
        detail::ConstRowBlock<Scalar>(d.jacobian.data() + side_block[side], j.equations, b.nv);
  }
  return e;
}

// ---- runtime changes ------------------------------------------------------------------------

/// Switches a joint on or off (a payload hooked or released, a brake locked or freed). An
/// inactive joint's equations read 0 = 0; no size changes, nothing is allocated.
template <class Scalar>
void set_joint_active(const Model<Scalar>& m, Data<Scalar>& d, JointId j, bool active) {
  (void)m;
  d.joint_active[static_cast<std::size_t>(j.index)] = active ? 1 : 0;
  ++d.revision;
}
template <class Scalar>
bool joint_active(const Data<Scalar>& d, JointId j) {
  return d.joint_active[static_cast<std::size_t>(j.index)] != 0;
}

namespace detail {
/// T in a parameter that takes no part in deducing Scalar (so Vector3d::Zero() binds).
template <class T>
using Given = typename std::enable_if<true, T>::type;
}  // namespace detail

/// Moves a body's frame to a pose (global), e.g. before initialize(), which assembles the
/// joints from there. Returns an error for a pose that is not finite.
template <class Scalar>
Status set_body_pose(const Model<Scalar>& m, Data<Scalar>& d, BodyId id,
                     const detail::Given<Vec3<Scalar>>& position,
                     const detail::Given<EulerParameters<Scalar>>& orientation) {
  const auto& b = m.body(id);
  if (!position.allFinite() || !orientation.allFinite() || !(orientation.norm() > Scalar(0)))
    return make_error(ErrorCode::invalid_argument, m.describe_body(id.index),
                      ": pose not finite or orientation zero");
  d.q.template segment<3>(b.q_offset) = position;
  d.q.template segment<4>(b.q_offset + 3) = orientation.normalized();
  return Status::success();
}

/// Sets a body's velocity: its frame's linear velocity (global) and angular velocity (body
/// frame), e.g. before initialize(), which makes the velocities consistent with the joints.
template <class Scalar>
void set_body_velocity(const Model<Scalar>& m, Data<Scalar>& d, BodyId id,
                       const detail::Given<Vec3<Scalar>>& linear,
                       const detail::Given<Vec3<Scalar>>& angular_body) {
  const auto& b = m.body(id);
  d.v.template segment<3>(b.v_offset) = linear;
  d.v.template segment<3>(b.v_offset + 3) = angular_body;
}
/// Sets a flexible body's modal coordinates and their rates (sizes: its modes).
template <class Scalar>
Status set_modal_state(
    const Model<Scalar>& m, Data<Scalar>& d, BodyId id,
    const detail::Given<Eigen::Ref<const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>>>& p,
    const detail::Given<Eigen::Ref<const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>>>& p_dot) {
  const auto& b = m.body(id);
  if (p.size() != b.modes || p_dot.size() != b.modes)
    return make_error(ErrorCode::size_mismatch, m.describe_body(id.index), " has ", b.modes,
                      " modes; given ", p.size(), " coordinates and ", p_dot.size(), " rates");
  if (!p.allFinite() || !p_dot.allFinite())
    return make_error(ErrorCode::invalid_argument, m.describe_body(id.index),
                      ": modal state not finite");
  d.q.segment(b.q_offset + 7, b.modes) = p;
  d.v.segment(b.v_offset + 6, b.modes) = p_dot;
  return Status::success();
}

/// Moves marker j of a joint on its body so that it coincides with marker i at d's state
/// (origin and axes): the joint then holds the two bodies where they are, so switching it on
/// is a capture without a jump in positions. The moved marker is the Data's: it moves for
/// every part that uses it (give the joint its own marker j if others share it). Exact on a
/// rigid body j; on a flexible body j the moved point keeps its node's mode shapes. For joints
/// whose equations coincident frames meet (not distance joints or drivers). Counts as a
/// runtime change; nothing is allocated.
template <class Scalar>
Status anchor_joint_at(const Model<Scalar>& m, Data<Scalar>& d, JointId id) {
  const auto& j = m.joint(id);
  if (j.kind == JointKind::distance || is_driver(j.kind))
    return make_error(ErrorCode::invalid_argument, m.describe_joint(id.index),
                      ": coincident markers do not meet its equations; only joints that hold "
                      "frames together can be anchored");
  if (j.body_j < 0)
    return make_error(ErrorCode::invalid_argument, m.describe_joint(id.index),
                      ": its marker j is on the ground, which cannot move");
  const auto& mj = m.markers()[static_cast<std::size_t>(j.marker_j)];
  const auto& b = m.bodies()[static_cast<std::size_t>(j.body_j)];
  const MarkerState<Scalar> target = marker_state(m, d, MarkerId{j.marker_i});
  const Mat3<Scalar> a = rotation_matrix<Scalar>(d.q.template segment<4>(b.q_offset + 3));
  b.kernels->anchor(b.holder.get(), mj.local, d.q.data() + b.q_offset, a, target,
                    d.anchors[static_cast<std::size_t>(mj.slot)]);
  ++d.revision;
  return Status::success();
}

/// Sets an input's value, rate and acceleration (for a driver's law that reads it) at the end
/// of the next step, d.t + step; within the step the law follows the quintic from its values
/// at the start (input_value, model/data.hpp). initialize() takes the values as set as the
/// values at d.t (so does the first set_input of an input). Returns invalid_input, changing
/// nothing, for a value that is not finite.
template <class Scalar>
StepStatus set_input(const Model<Scalar>&, Data<Scalar>& d, InputId id, Scalar value,
                     Scalar rate = Scalar(0), Scalar acceleration = Scalar(0)) {
  if (!std::isfinite(double(value)) || !std::isfinite(double(rate)) ||
      !std::isfinite(double(acceleration)))
    return StepStatus::invalid_input;
  const auto k = static_cast<std::size_t>(id.index);
  d.inputs[k] = {value, rate, acceleration};
  if (!d.input_set[k]) d.inputs_start[k] = d.inputs[k];  // its value now, too, until a step
  d.input_set[k] = 1;
  return StepStatus::ok;
}

/// Gives a driver a new law (setup-time: a table law's copy allocates). Counts as a runtime
/// change: the next step restarts as initialize() does, consistent with the new law's rates.
template <class Scalar>
Status set_law(const Model<Scalar>& m, Data<Scalar>& d, JointId id, MotionLaw<Scalar> law) {
  const auto& j = m.joint(id);
  if (j.law < 0)
    return make_error(ErrorCode::invalid_argument, m.describe_joint(id.index),
                      " is not a driver: it has no law");
  if (const char* bad = law.check(static_cast<int>(m.inputs().size())))
    return make_error(ErrorCode::invalid_argument, m.describe_joint(id.index), ": ", bad);
  if (const std::string fast = law.check_step(d.settings.step); !fast.empty())
    return make_error(ErrorCode::invalid_argument, m.describe_joint(id.index), ": ", fast);
  d.laws[static_cast<std::size_t>(j.law)] = std::move(law);
  ++d.revision;  // the next step restarts from the state with the new law's rates
  return Status::success();
}

}  // namespace flexstress
