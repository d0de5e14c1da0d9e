// Why a step failed, in words that name the part: the body and coordinate whose residual or
// state is worst, the joint whose constraint is most violated, and how fast the fastest body
// turns per step (a step too large for the motion). Written into Data::message with snprintf
// into its fixed storage, so a failing step still allocates nothing.
#pragma once

#include <cmath>
#include <cstdio>

#include <Eigen/Core>

#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/model/data.hpp"
#include "flexstress/model/joint_rows.hpp"
#include "flexstress/model/model.hpp"
#include "flexstress/model/pipeline.hpp"

namespace flexstress::detail {

/// The body that velocity index i belongs to, or -1.
template <class Scalar>
int body_of_velocity(const Model<Scalar>& model, Index i) {
  const auto& bodies = model.bodies();
  for (std::size_t b = 0; b < bodies.size(); ++b)
    if (i >= bodies[b].v_offset && i < bodies[b].v_offset + bodies[b].nv)
      return static_cast<int>(b);
  return -1;
}

/// "translation y", "rotation x", "mode 3" for coordinate `local` of a body's velocity block.
inline void name_body_coordinate(Index local, char* out, std::size_t size) {
  static const char* const axis[3] = {"x", "y", "z"};
  if (local < 3)
    std::snprintf(out, size, "translation %s", axis[local]);
  else if (local < 6)
    std::snprintf(out, size, "rotation %s", axis[local - 3]);
  else
    std::snprintf(out, size, "mode %d", static_cast<int>(local - 6) + 1);
}

/// The body turning fastest (|w| at the start of the step) and its turn per step, w h.
template <class Scalar>
int fastest_turning_body(const Model<Scalar>& model, const Eigen::Matrix<Scalar, -1, 1>& v,
                         Scalar h, Scalar& turn_per_step) {
  int fastest = -1;
  turn_per_step = Scalar(0);
  const auto& bodies = model.bodies();
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const Scalar turn = v.template segment<3>(bodies[b].v_offset + 3).norm() * h;
    if (fastest < 0 || turn > turn_per_step) {
      fastest = static_cast<int>(b);
      turn_per_step = turn;
    }
  }
  return fastest;
}

/// The most violated constraint row of d.phi (-1 without constraints).
template <class Scalar>
Index worst_constraint_row(const Data<Scalar>& d, Scalar& violation) {
  violation = Scalar(0);
  Index worst = -1;
  for (Index r = 0; r < d.phi.size(); ++r)
    if (!(std::abs(d.phi(r)) <= violation)) {  // NaN counts as worst
      violation = std::abs(d.phi(r));
      worst = r;
    }
  return worst;
}

/// Writes why the step from time t_n failed after `iterations` Newton iterations (`size` the
/// last correction, `tolerance` its limit); the Data still holds the failed iterate.
/// A converged step undone for its local error estimate (local_error_tolerance): the estimate
/// and where it is largest.
template <class Scalar>
void explain_local_error(const Model<Scalar>& model, Data<Scalar>& d, Scalar t_n, Scalar estimate,
                         Index worst) {
  char part[96] = "";
  const int body = body_of_velocity(model, worst);
  if (body >= 0) {
    char coordinate[32];
    const auto& b = model.bodies()[static_cast<std::size_t>(body)];
    name_body_coordinate(worst - b.v_offset, coordinate, sizeof coordinate);
    std::snprintf(part, sizeof part, " in body '%s' (%s)", b.name.c_str(), coordinate);
  }
  std::snprintf(d.message.data(), d.message.size(),
                "step from t = %g of %g s: local error estimate %.3g above the tolerance %.3g%s",
                static_cast<double>(t_n), static_cast<double>(d.integrator.h),
                static_cast<double>(estimate),
                static_cast<double>(d.settings.local_error_tolerance), part);
}

/// A step that converged (or was kept at the Newton budget) but left a joint violated beyond
/// settings.violation_limit (kept, as constraint_violation says): which joint, by how much, in
/// positions or velocities.
template <class Scalar>
void explain_violation(const Model<Scalar>& model, Data<Scalar>& d,
                       const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& rows, const char* what,
                       bool at_budget) {
  Index row = 0;
  const Scalar v = rows.size() > 0 ? rows.cwiseAbs().maxCoeff(&row) : Scalar(0);
  const int k = rows.size() > 0 ? model.joint_of_row(static_cast<int>(row)) : -1;
  std::snprintf(d.message.data(), d.message.size(),
                "step to t = %g: %s, but joint '%s' is off by %.3g in %s (limit %.3g)",
                static_cast<double>(d.t),
                at_budget ? "kept at the Newton budget (not converged)" : "converged",
                k >= 0 ? model.joints()[static_cast<std::size_t>(k)].name.c_str() : "?",
                static_cast<double>(v), what, static_cast<double>(d.settings.violation_limit));
}

/// The first active joint whose law is not finite at t (its value, rate or acceleration: a
/// callback or an input gone NaN), or -1. Only on a failed step's path.
template <class Scalar>
int nonfinite_law(const Model<Scalar>& model, const Data<Scalar>& d, Scalar t) {
  for (std::size_t k = 0; k < model.joints().size(); ++k) {
    const auto& j = model.joints()[k];
    if (j.law < 0 || !d.joint_active[k]) continue;
    const MotionValue<Scalar> v = law_value(d, j.law, t);
    if (!std::isfinite(v.value) || !std::isfinite(v.rate) || !std::isfinite(v.acceleration))
      return static_cast<int>(k);
  }
  return -1;
}

template <class Scalar>
void explain_nonfinite_law(const Model<Scalar>& model, Data<Scalar>& d, int joint, Scalar t_n,
                           Scalar t) {
  const auto& j = model.joints()[static_cast<std::size_t>(joint)];
  const MotionValue<Scalar> v = law_value(d, j.law, t);
  std::snprintf(d.message.data(), d.message.size(),
                "step from t = %g: joint '%s' (%s): its law is not finite at t = %g (value %g, "
                "rate %g, acceleration %g)",
                static_cast<double>(t_n), j.name.c_str(), to_string(j.kind), static_cast<double>(t),
                static_cast<double>(v.value), static_cast<double>(v.rate),
                static_cast<double>(v.acceleration));
}

template <class Scalar>
void explain_step_failure(const Model<Scalar>& model, Data<Scalar>& d, StepStatus status,
                          Scalar t_n, int iterations, Scalar size, Scalar tolerance) {
  char part[160] = "";
  const Scalar h = d.integrator.h;
  Scalar turn = Scalar(0);
  const int fastest = fastest_turning_body(model, d.integrator.v_n, h, turn);
  char turning[192] = "";
  // A divergence where nothing turns fast is not the rotation's: say so rather than name a
  // body that barely moves as the reason.
  if (fastest >= 0 && (turn >= Scalar(1e-3) || status != StepStatus::step_too_large))
    std::snprintf(turning, sizeof turning, "; body '%s' turns by %.3g rad per step",
                  model.bodies()[static_cast<std::size_t>(fastest)].name.c_str(),
                  static_cast<double>(turn));
  else if (fastest >= 0)
    std::snprintf(turning, sizeof turning,
                  "; no body turns by more than %.3g rad per step (body '%s'): a stiff force or "
                  "mode rather than the rotation",
                  static_cast<double>(turn),
                  model.bodies()[static_cast<std::size_t>(fastest)].name.c_str());
  if (status == StepStatus::non_finite_state) {
    const int body = nonfinite_body(model, d);
    std::snprintf(d.message.data(), d.message.size(),
                  "step from t = %g: the state at its start is not finite (body '%s')",
                  static_cast<double>(t_n),
                  body >= 0 ? model.bodies()[static_cast<std::size_t>(body)].name.c_str() : "?");
    return;
  }
  // The worst entry of the last residual: a body and one of its coordinates.
  Index worst = 0;
  if (d.integrator.r.size() > 0) d.integrator.r.cwiseAbs().maxCoeff(&worst);
  const int body = body_of_velocity(model, worst);
  if (body >= 0) {
    char coordinate[32];
    const auto& b = model.bodies()[static_cast<std::size_t>(body)];
    name_body_coordinate(worst - b.v_offset, coordinate, sizeof coordinate);
    std::snprintf(part, sizeof part, "largest residual in body '%s' (%s)", b.name.c_str(),
                  coordinate);
  }
  Scalar violation = Scalar(0);
  const Index row = worst_constraint_row(d, violation);
  char joint[160] = "";
  if (row >= 0) {
    const int k = model.joint_of_row(static_cast<int>(row));
    const auto& j = model.joints()[static_cast<std::size_t>(k)];
    std::snprintf(joint, sizeof joint, ", largest violation %.3g in joint '%s' (%s)",
                  static_cast<double>(violation), j.name.c_str(), to_string(j.kind));
  }
  // The velocities the step started from against the joints, B v + Phi_t at the restored
  // state (evaluated again: the workspace then describes it): index-3 steps keep positions on
  // the joints, not velocities, and a drift there (a redundant loop's out-of-plane rates
  // growing from round-off) spoils the predictor until Newton fails; smaller steps do not cure
  // that, velocity projection does.
  update_kinematics(model, d);
  update_markers(model, d);
  update_constraints(model, d);
  jacobian_times(model, d, d.v, d.integrator.e);
  d.integrator.e += d.phi_t;
  Index drift_row = 0;
  const Scalar drift =
      d.integrator.e.size() > 0 ? d.integrator.e.cwiseAbs().maxCoeff(&drift_row) : Scalar(0);
  char drifting[192] = "";
  if (d.integrator.e.size() > 0) {
    const auto& j =
        model.joints()[static_cast<std::size_t>(model.joint_of_row(static_cast<int>(drift_row)))];
    std::snprintf(drifting, sizeof drifting, "; velocities off the joints by %.3g (joint '%s')",
                  static_cast<double>(drift), j.name.c_str());
  }
  if (status == StepStatus::step_too_large)
    std::snprintf(d.message.data(), d.message.size(),
                  "step from t = %g of %g s: too large for the motion, Newton diverged "
                  "(correction %.3g after %d iterations, growing with a fresh matrix)%s; %s%s%s",
                  static_cast<double>(t_n), static_cast<double>(h), static_cast<double>(size),
                  iterations, turning, part, joint, drifting);
  else
    std::snprintf(d.message.data(), d.message.size(),
                  "step from t = %g: Newton not converged in %d iterations (correction %.3g, "
                  "tolerance %.3g); %s%s%s%s",
                  static_cast<double>(t_n), iterations, static_cast<double>(size),
                  static_cast<double>(tolerance), part, joint, turning, drifting);
}

}  // namespace flexstress::detail
