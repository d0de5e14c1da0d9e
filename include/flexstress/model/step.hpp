// step(): one time step of the implicit integrator (model/implicit_step.hpp), taken in pieces
// when it has to be. A step whose Newton iteration diverges or stalls, or whose local error
// estimate exceeds ImplicitSettings::local_error_tolerance, is taken again in halves, and a
// failing half in halves again, down to step / 2^max_step_halvings; the step still ends at
// t + step, so a fixed-step caller keeps its clock, and the next step starts with the pieces
// that passed. The state at the start is kept in storage
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

/// Sets the integrator's constants for pieces of size `piece`. Each piece starts from a fresh
/// matrix: pieces are taken where the motion outruns one (Andrews' squeezer: 50 instead of 70
/// iterations per step, reusing it); a run of equal pieces keeps its predictor's history.
template <class Scalar>
void use_piece(Data<Scalar>& d, Scalar piece) {
  auto& in = d.integrator;
  in.have_factorization = false;
  if (in.h == piece) return;
  set_step_parameters(d, piece);
  // A predictor extrapolated over steps of another size would start Newton off.
  in.has_previous = false;
  in.converged_multipliers = std::min(in.converged_multipliers, 1);
}

/// Whether pieces twice as large would likely pass the local error control: the estimate
/// grows as h^2 to h^3, so with a margin eight times the last one must be within tolerance.
template <class Scalar>
bool coarser_would_pass(const Data<Scalar>& d) {
  const Scalar tolerance = d.settings.local_error_tolerance;
  return tolerance <= Scalar(0) || Scalar(8) * d.integrator.last_error_estimate <= tolerance;
}

}  // namespace detail

/// One step of size d.settings.step. Never allocates or throws. A step whose Newton iteration
/// fails, or whose local error estimate exceeds settings.local_error_tolerance, is taken again
/// in pieces (settings.max_step_halvings): halves, and a failing half in halves, still ending
/// at t + step. The next step starts with pieces of the size that passed, and goes back to
/// larger ones after two pieces in a row passed with an estimate eight times below the
/// tolerance (a step-size controller whose sizes divide the caller's step, so that a fixed-step
/// caller keeps its clock). On failure the state is left as it was before the step (except for
/// the constraint_violation of an unsplit step, which keeps the step; a piece's undoes the
/// whole step) and d.message says where.
template <class Scalar>
StepStatus step(const Model<Scalar>& model, Data<Scalar>& d) {
  auto& in = d.integrator;
  // Input laws run over the step's span; a step taken (also one kept with a violated joint)
  // ends it, a step undone keeps it for the retry.
  begin_input_span(d, d.settings.step);
  // A runtime change (a joint switched): restart from the state as it is (with the inputs'
  // values now); this also starts again from whole steps. The reason a restart failed stays in
  // d.message.
  if (!in.initialized || d.revision != in.revision) {
    if (!initialize(model, d).ok()) return StepStatus::constraint_violation;
  }
  const int finest = d.settings.max_step_halvings;
  int level = std::min(in.piece_level, finest);
  if (level == 0) {
    // The step as set (also directly in d.settings); a whole step reuses the matrix.
    if (in.h != d.settings.step) detail::use_piece(d, d.settings.step);
    const Scalar t_n = d.t;
    const StepStatus whole = detail::step_whole(model, d, finest > 0);
    if (!detail::may_pass_in_pieces(whole) || finest <= 0) {
      if (d.t != t_n) end_input_span(d);
      return whole;
    }
    level = 1;
  }
  const Scalar h = d.settings.step, h_start = in.h, t_start = d.t;
  const Scalar boost_start = in.penalty_boost;
  const int boost_age_start = in.boost_age;
  const bool had_previous = in.has_previous;
  const int had_converged = in.converged_multipliers, had_level = in.piece_level;
  detail::save_split_start(d);
  ++d.statistics.split_steps;
  StepStatus result = StepStatus::ok;
  long pieces = 0;          // each counted as a step by step_whole; the caller took one
  int passed = 0;           // pieces passed in a row at this level
  Scalar done = Scalar(0);  // of h
  while (done < Scalar(1)) {
    // Pieces of h / 2^level; the level changes only at a larger piece's boundary, so the last
    // piece ends at h exactly.
    const Scalar piece = std::ldexp(Scalar(1), -level);
    detail::use_piece(d, piece * h);
    const StepStatus st = detail::step_whole(model, d, /*control_error=*/level < finest);
    if (st == StepStatus::ok || st == StepStatus::budget_reached) {
      ++d.statistics.substeps;
      ++pieces;
      ++passed;
      if (st == StepStatus::budget_reached) result = st;
      done += piece;
      if (level > 1 && passed >= 2 && detail::coarser_would_pass(d) &&
          std::ldexp(done, level - 1) == std::floor(std::ldexp(done, level - 1))) {
        --level;
        passed = 0;
      }
      continue;
    }
    if (detail::may_pass_in_pieces(st) && level < finest) {
      ++level;
      passed = 0;
      continue;
    }
    // Not even the smallest piece passes: the step fails as a whole; the message is the
    // smallest piece's.
    detail::restore_split_start(d);
    d.statistics.steps -= pieces;
    detail::set_step_parameters(d, h_start);
    in.has_previous = had_previous;
    in.converged_multipliers = had_converged;
    in.piece_level = had_level;
    in.penalty_boost = boost_start;
    in.boost_age = boost_age_start;
    d.t = t_start;
    return st;
  }
  d.t = t_start + h;
  d.statistics.steps -= pieces - 1;
  // The next step starts with this step's last pieces, or twice as large ones when they
  // passed easily (the whole step again from pieces of a half).
  in.piece_level = passed >= 2 && detail::coarser_would_pass(d) ? level - 1 : level;
  if (in.piece_level == 0) detail::use_piece(d, h);
  d.message.fill('\0');  // the step passed: why a larger piece failed is no failure to report
  end_input_span(d);
  return result;
}

}  // namespace flexstress
