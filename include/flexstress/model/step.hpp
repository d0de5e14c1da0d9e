// step(): one time step of the implicit integrator (model/implicit_step.hpp), taken in pieces
// when it has to be. A step whose Newton iteration diverges or stalls, or whose local error
// estimate exceeds ImplicitSettings::local_error_tolerance, is taken again in halves, and a
// failing half in halves again, down to step / 2^max_step_halvings; the step still ends at
// t + step, so a fixed-step caller keeps its clock. The state at the start is kept in storage
// made with the Data: a split step allocates nothing.
#pragma once

#include <algorithm>
#include <cmath>

#include "flexstress/core/status.hpp"
#include "flexstress/model/data.hpp"
#include "flexstress/model/implicit_step.hpp"
#include "flexstress/model/model.hpp"

namespace flexstress {

namespace detail {

/// A failed step that a smaller step may pass: Newton diverged or did not converge.
inline bool may_pass_in_pieces(StepStatus s) {
  return s == StepStatus::newton_not_converged || s == StepStatus::step_too_large;
}

/// Calls f(live, saved) on each part of the state a split step saves at its start and restores
/// when a piece fails: coordinates, velocities, accelerations, multipliers and their history,
/// force-element states (same sizes: copies into the storage made with the Data).
template <class Scalar, class F>
void for_each_split_part(Data<Scalar>& d, F f) {
  auto& in = d.integrator;
  f(d.q, in.q_split);
  f(d.v, in.v_split);
  f(d.v_dot, in.vd_split);
  f(d.a, in.a_split);
  f(in.vd_prev, in.vd_prev_split);
  f(d.lambda, in.lambda_split);
  f(in.lambda_last, in.lambda_last_split);
  f(in.lambda_increment, in.lambda_increment_split);
  f(d.force_states, in.force_states_split);
}

template <class Scalar>
void save_split_start(Data<Scalar>& d) {
  for_each_split_part(
      d, [](const auto& live, auto& saved) { std::copy(live.begin(), live.end(), saved.begin()); });
}

template <class Scalar>
void restore_split_start(Data<Scalar>& d) {
  for_each_split_part(d, [](auto& live, const auto& saved) {
    std::copy(saved.begin(), saved.end(), live.begin());
  });
}

}  // namespace detail

/// One step of size d.settings.step. Never allocates or throws. A step whose Newton iteration
/// fails, or whose local error estimate exceeds settings.local_error_tolerance, is taken again
/// in pieces (settings.max_step_halvings): halves, and a failing half in halves, still ending
/// at t + step. On failure the state is left as it was before the step (except for the
/// constraint_violation of an unsplit step, which keeps the step; a piece's undoes the whole
/// step) and d.message says where.
template <class Scalar>
StepStatus step(const Model<Scalar>& model, Data<Scalar>& d) {
  const bool can_split = d.settings.max_step_halvings > 0;
  const StepStatus whole = detail::step_whole(model, d, can_split);
  if (!detail::may_pass_in_pieces(whole) || d.settings.max_step_halvings <= 0) return whole;
  auto& in = d.integrator;
  const Scalar h = d.settings.step, t_start = d.t;
  const bool had_previous = in.has_previous;
  const int had_converged = in.converged_multipliers;
  detail::save_split_start(d);
  ++d.statistics.split_steps;
  StepStatus result = StepStatus::ok;
  long pieces = 0;  // each counted as a step by step_whole; the caller took one
  int level = 1;
  Scalar done = Scalar(0);  // of h
  while (done < Scalar(1)) {
    // The piece: h / 2^level, or what is left of the step.
    const Scalar piece = std::min(std::ldexp(Scalar(1), -level), Scalar(1) - done);
    set_step_size(d, piece * h);
    // A predictor extrapolated over steps of another size would start Newton off.
    in.has_previous = false;
    in.converged_multipliers = std::min(in.converged_multipliers, 1);
    const StepStatus st =
        detail::step_whole(model, d, /*control_error=*/level < d.settings.max_step_halvings);
    if (st == StepStatus::ok || st == StepStatus::budget_reached) {
      ++d.statistics.substeps;
      ++pieces;
      if (st == StepStatus::budget_reached) result = st;
      done += piece;
      // Back to larger pieces once the smaller ones have reached a larger piece's boundary.
      while (level > 1 && std::ldexp(done, level - 1) == std::floor(std::ldexp(done, level - 1)))
        --level;
      continue;
    }
    if (detail::may_pass_in_pieces(st) && level < d.settings.max_step_halvings) {
      ++level;
      continue;
    }
    // Not even the smallest piece passes: the step fails as a whole; the message is the
    // smallest piece's.
    detail::restore_split_start(d);
    d.statistics.steps -= pieces;
    in.has_previous = had_previous;
    in.converged_multipliers = had_converged;
    d.t = t_start;
    set_step_size(d, h);
    return st;
  }
  set_step_size(d, h);
  d.t = t_start + h;
  d.statistics.steps -= pieces - 1;
  // The next step extrapolates from a whole step's history, which a split step does not leave.
  in.has_previous = false;
  in.converged_multipliers = std::min(in.converged_multipliers, 1);
  d.message.fill('\0');  // the step passed: why its whole failed is no failure to report
  return result;
}

}  // namespace flexstress
