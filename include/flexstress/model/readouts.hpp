// Read-outs and runtime changes by handle, over (model, data). Read-outs read the state (and,
// for marker frames and reactions, evaluate what they need into the data's workspace); runtime
// changes are counted in Data::revision, and the next step restarts from the state as
// initialize() does (a joint switched on is assembled and the velocities projected: a perfectly
// plastic capture that keeps momentum).
#pragma once

#include <string>

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
/// Modal coordinates of a flexible body (empty for a rigid one).
template <class Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, 1> modal_coordinates(const Model<Scalar>& m,
                                                           const Data<Scalar>& d, BodyId b) {
  return d.q.segment(m.body(b).q_offset + 7, m.body(b).modes);
}

/// A marker's frame at the current state (global; on a flexible body it follows its node).
template <class Scalar>
Frame<Scalar> marker_frame(const Model<Scalar>& m, const Data<Scalar>& d, MarkerId id) {
  const auto& mk = m.marker(id);
  MarkerState<Scalar> state;
  if (mk.body < 0) {
    state = d.markers[static_cast<std::size_t>(mk.slot)];
  } else {
    const auto& b = m.bodies()[static_cast<std::size_t>(mk.body)];
    // Evaluate all of the body's markers in full, into a local copy of the parts: read-outs
    // are outside the step and may use the stack freely.
    std::vector<unsigned> parts(static_cast<std::size_t>(b.num_markers), 0u);
    std::vector<MarkerState<Scalar>> out(static_cast<std::size_t>(b.num_markers));
    parts[static_cast<std::size_t>(mk.local)] = MarkerParts::all;
    const Mat3<Scalar> a = rotation_matrix<Scalar>(d.q.template segment<4>(b.q_offset + 3));
    b.kernels->markers(b.holder.get(), d.q.data() + b.q_offset, d.v.data() + b.v_offset, a, true,
                       parts.data(), out.data());
    state = out[static_cast<std::size_t>(mk.local)];
  }
  Frame<Scalar> f;
  f.origin = state.origin.value;
  f.axes.col(0) = state.x.value;
  f.axes.col(1) = state.y.value;
  f.axes.col(2) = state.z.value;
  return f;
}

/// Force and moment a joint applies to the body of its marker j, at marker j's origin, in the
/// joint frame (marker i's axes): from the multipliers, -B_j^T lambda (M v_dot + B^T lambda =
/// Q). Valid after initialize() or a step.
template <class Scalar>
struct Reaction {
  Vec3<Scalar> force = Vec3<Scalar>::Zero();
  Vec3<Scalar> moment = Vec3<Scalar>::Zero();
};
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
    const Eigen::Matrix<Scalar, 6, 1> g = -(rows.leftCols(6).transpose() * lambda);
    force = g.template head<3>();
    // Moment about the frame origin (body axes) to the global moment about marker j's origin.
    const Mat3<Scalar> a = rotation_matrix<Scalar>(d.q.template segment<4>(b.q_offset + 3));
    const Vec3<Scalar> r = fj.origin - d.q.template segment<3>(b.q_offset);
    moment = a * g.template tail<3>() - r.cross(force);
  } else if (j.body_i >= 0) {
    // Marker j on the ground: the reaction on the ground is minus that on body i.
    const auto& b = m.bodies()[static_cast<std::size_t>(j.body_i)];
    const detail::ConstRowBlock<Scalar> rows(d.jacobian.data() + j.jac_i, j.equations, b.nv);
    const Eigen::Matrix<Scalar, 6, 1> g = rows.leftCols(6).transpose() * lambda;
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

/// Energies at the state: kinetic, gravity potential, elastic (modes) and springs.
template <class Scalar>
struct Energy {
  Scalar kinetic = Scalar(0), gravity = Scalar(0), elastic = Scalar(0), springs = Scalar(0);
  Scalar total() const { return kinetic + gravity + elastic + springs; }
};
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

/// Sets an input's value, rate and acceleration for the next step (a driver's law that reads
/// it). Returns invalid_input, changing nothing, for a value that is not finite.
template <class Scalar>
StepStatus set_input(const Model<Scalar>&, Data<Scalar>& d, InputId id, Scalar value,
                     Scalar rate = Scalar(0), Scalar acceleration = Scalar(0)) {
  if (!std::isfinite(double(value)) || !std::isfinite(double(rate)) ||
      !std::isfinite(double(acceleration)))
    return StepStatus::invalid_input;
  d.inputs[static_cast<std::size_t>(id.index)] = {value, rate, acceleration};
  d.input_set[static_cast<std::size_t>(id.index)] = 1;
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
  d.laws[static_cast<std::size_t>(j.law)] = std::move(law);
  ++d.revision;  // the next step restarts from the state with the new law's rates
  return Status::success();
}

}  // namespace flexstress
