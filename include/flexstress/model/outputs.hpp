// Stress outputs and damage meters of a model, evaluated after a step: one call computes every
// output of a Data (y = F p per output set, plus the sub-model's own inertia where declared)
// and feeds each meter its output. Never allocates.
#pragma once

#include <cstdint>
#include <cstdio>

#include <Eigen/Core>

#include "flexstress/core/status.hpp"
#include "flexstress/fatigue/damage.hpp"
#include "flexstress/model/data.hpp"
#include "flexstress/model/model.hpp"

namespace flexstress {

/// The 12 inertia coordinates of a body frame (stress/sub_model_inertia.hpp): frame-origin
/// acceleration minus gravity, angular acceleration and the products of the angular velocity,
/// all in the body frame.
template <class Scalar>
Eigen::Matrix<Scalar, 12, 1> body_inertia_coordinates(const Model<Scalar>& model,
                                                      const Data<Scalar>& d, int body) {
  const auto& b = model.bodies()[static_cast<std::size_t>(body)];
  const Mat3<Scalar> a = rotation_matrix<Scalar>(d.q.template segment<4>(b.q_offset + 3));
  const Vec3<Scalar> acc = a.transpose() * d.v_dot.template segment<3>(b.v_offset);
  const Vec3<Scalar> g =
      model.has_gravity() ? Vec3<Scalar>(a.transpose() * model.gravity()) : Vec3<Scalar>::Zero();
  const Vec3<Scalar> w = d.v.template segment<3>(b.v_offset + 3);
  const Vec3<Scalar> w_dot = d.v_dot.template segment<3>(b.v_offset + 3);
  Eigen::Matrix<Scalar, 12, 1> c;
  c.template head<3>() = acc - g;
  c.template segment<3>(3) = w_dot;
  c.template segment<3>(6) = w.cwiseProduct(w);
  c(9) = w.x() * w.y();
  c(10) = w.y() * w.z();
  c(11) = w.z() * w.x();
  return c;
}

/// Evaluates every output at d's state and (feed_meters) pushes each meter's output. Returns ok,
/// or the first meter's refusal (invalid_input for a non-finite value, capacity_exceeded
/// outside its class window), having evaluated all outputs and fed every meter; each meter
/// counts the samples it refused (meter_refused_samples), and d.message names the first
/// refusing meter and its sample.
template <class Scalar>
StepStatus evaluate_outputs(const Model<Scalar>& model, Data<Scalar>& d, bool feed_meters = true) {
  for (const auto& set : model.output_sets()) {
    const auto& b = model.bodies()[static_cast<std::size_t>(set.body)];
    auto y = d.outputs.segment(set.first, set.rows.rows());
    y.noalias() = set.rows * d.q.segment(b.q_offset + 7, b.modes);
    if (set.inertia.size() > 0)
      y.noalias() += set.inertia * body_inertia_coordinates(model, d, set.body);
  }
  StepStatus status = StepStatus::ok;
  if (!feed_meters) return status;
  for (std::size_t k = 0; k < model.meters().size(); ++k) {
    const auto& m = model.meters()[k];
    const Scalar sample = m.scale * d.outputs(m.output);
    const StepStatus s = d.meters[k].push(sample);
    if (s == StepStatus::ok) continue;
    ++d.meter_refused[k];
    if (status != StepStatus::ok) continue;
    status = s;
    const auto& grid = d.meters[k].counter().grid();
    std::snprintf(d.message.data(), d.message.size(),
                  "meter '%s' at t = %g: sample %g %s [%g, %g] (not counted)", m.name.c_str(),
                  static_cast<double>(d.t), static_cast<double>(sample),
                  s == StepStatus::capacity_exceeded ? "outside its class window"
                                                     : "not finite; its class window",
                  static_cast<double>(grid.lower()), static_cast<double>(grid.upper()));
  }
  return status;
}

/// An output's value at the last evaluate_outputs.
template <class Scalar>
Scalar output_value(const Data<Scalar>& d, OutputId id) {
  return d.outputs(id.index);
}

/// A meter's damage so far, its residue closed as `closure`.
template <class Scalar>
Scalar meter_damage(const Data<Scalar>& d, MeterId id,
                    fatigue::CycleClosure closure = fatigue::CycleClosure::repeating) {
  return d.meters[static_cast<std::size_t>(id.index)].damage(closure);
}

/// How many samples a meter refused so far (outside its class window, or not finite): its
/// damage leaves them out, so a count above zero means a window too narrow for the run.
template <class Scalar>
std::int64_t meter_refused_samples(const Data<Scalar>& d, MeterId id) {
  return d.meter_refused[static_cast<std::size_t>(id.index)];
}

}  // namespace flexstress
