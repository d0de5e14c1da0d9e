// The implicit step over (model, data): Lie-group generalized-alpha with an index-3 augmented
// Lagrangian and velocity projection; step() (model/step.hpp) takes it in pieces when it has
// to. The measurements behind each setting are in dynamics/step_settings.hpp.
//
// Time discretization (Bruls & Cardona, J. Comput. Nonlinear Dyn. 5 (2010) 031002; Arnold,
// Bruls, Cardona, Multibody Syst. Dyn. 33 (2015)): with v_dot the true and a the algorithmic
// accelerations,
//   (1 - am) a_{n+1} + am a_n = (1 - af) v_dot_{n+1} + af v_dot_n,
//   v_{n+1} = v_n + h ((1 - g) a_n + g a_{n+1}),
//   q_{n+1} = q_n o exp(h dq),  dq = v_n + h ((1/2 - b) a_n + b a_{n+1}),
// where "o exp" moves R and p additively and theta = theta (x) exp(.) on the rotation group, so
// the velocities stay the body-frame w and second order is kept despite rotations (a textbook
// alpha method on q_dot = v with renormalized Euler parameters is only first order).
// Parameters from the spectral radius at infinity rho (Chung & Hulbert 1993):
// am = (2 rho - 1)/(rho + 1), af = rho/(rho + 1), g = 1/2 - am + af, b = (g + 1/2)^2 / 4;
// rho = 1 is the trapezoidal rule without numerical dissipation.
//
// Constraints (index 3, positions enforced exactly): augmented Lagrangian (Bayo, Garcia de Jalon,
// Serna 1988; Cuadrado et al., ALI3-P, Multibody Syst. Dyn. 4 (2000)):
//   M v_dot - Q + B^T (lambda* + alpha Phi) = 0,  lambda* += alpha Phi after each iteration.
// The Newton matrix S = M b' + D g' + K + alpha B^T B (b' = (1 - am)/(h^2 b (1 - af)),
// g' = g/(h b)) is symmetric positive definite even when B is rank-deficient (redundant joints
// such as a planar loop modelled in 3D, singular positions), so no KKT system is ever solved.
// Where ImplicitSettings::linearized_multipliers says, each correction dx also takes one Uzawa
// pass on the linearized constraints (lambda* += e, dx -= S^-1 B^T e, e = alpha (Phi + B dx)):
// the KKT step's multipliers, to the pass's contraction, so Newton contracts quadratically.
// Modified Newton: S is factorized once and reused across iterations and steps until the
// observed contraction rate says it is stale; it is factorized within its envelope in a body
// order that skips the zero blocks between bodies no joint joins (core/envelope_cholesky.hpp).
// A reused S is turned with the bodies (ImplicitSettings::corotate_factorization): with global
// R_dot and body-frame w and p_dot, a body's own blocks of M and B^T B are T S_0 T^T with T =
// diag(A, 1, 1), so rotating the R_dot parts of the residual and correction by the rotation since
// the factorization makes them exact again for any rigid rotation. With
// ImplicitSettings::project_velocities, after convergence the velocities are projected onto
// B v + Phi_t = 0 with the same factorization, a projection orthogonal in the metric S
// (dominated by M b'), which removes velocity drift; velocities that drifted on their own
// (velocity_drift_limit) are projected in the mass metric, factorized for it.
// d.lambda then holds the multipliers of the converged equations, lambda* + alpha Phi.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <Eigen/Core>

#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/model/data.hpp"
#include "flexstress/model/iteration_matrix.hpp"
#include "flexstress/model/model.hpp"
#include "flexstress/model/pipeline.hpp"
#include "flexstress/model/step_failure.hpp"

namespace flexstress {

/// Changes the step size of d (the next step refactorizes).
template <class Scalar>
void set_step_size(Data<Scalar>& d, Scalar h) {
  d.settings.step = h;
  detail::set_step_parameters(d, h);
  d.integrator.piece_level = 0;
}

/// Gives d other integrator settings, checked as finalize checks the model's; the next step
/// uses them (a changed step size or spectral radius refactorizes, the state is kept).
template <class Scalar>
Status set_settings(const Model<Scalar>&, Data<Scalar>& d, const ImplicitSettings<Scalar>& s) {
  if (Status checked = check_settings(s); !checked) return checked;
  d.settings = s;
  detail::set_step_parameters(d, s.step);
  d.integrator.piece_level = 0;
  return Status::success();
}

/// Consistent initial conditions at d.t: positions onto Phi = 0 (rigid coordinates first, so a
/// flexible body is turned, not bent, to meet a joint or driver; modal coordinates join,
/// weighted by their stiffness, only where deformation must close a loop),
/// velocities onto B v + Phi_t = 0, then accelerations and multipliers from the equations of
/// motion. Fails, naming the joint or body, if the joints cannot be assembled, a coordinate is
/// not finite or an input law reads an input never set.
template <class Scalar>
Status initialize(const Model<Scalar>& model, Data<Scalar>& d, int max_iterations = 100) {
  using detail::remember;
  auto& in = d.integrator;
  // Called by the user, the inputs as set are the values at d.t; called by step() (a restart
  // after a runtime change), the step under way keeps its start.
  if (!input_span_open(d)) end_input_span(d);
  detail::set_step_parameters(d, d.settings.step);
  in.piece_level = 0;
  for (std::size_t k = 0; k < model.joints().size(); ++k) {
    const auto& j = model.joints()[k];
    if (j.law < 0 || !d.joint_active[k]) continue;
    const auto& law = d.laws[static_cast<std::size_t>(j.law)];
    if (law.kind == MotionLawKind::input && !d.input_set[static_cast<std::size_t>(law.input.index)])
      return remember(d, make_error(ErrorCode::invalid_argument, model.describe_joint(int(k)),
                                    ": its law reads input '",
                                    model.inputs()[static_cast<std::size_t>(law.input.index)],
                                    "', which was never set (set_input)"));
  }
  if (const int body = nonfinite_body(model, d); body >= 0)
    return remember(d, make_error(ErrorCode::invalid_argument,
                                  "initial conditions: ", model.describe_body(body),
                                  " has a coordinate or velocity that is not finite"));
  const Scalar tol = d.settings.position_floor * Scalar(10);
  update_kinematics(model, d);
  update_markers(model, d);
  update_constraints(model, d);
  Scalar violation = max_abs(d.phi);
  // Damped Newton projection: (W + alpha B^T B) dx = -alpha B^T Phi, refactorized at every
  // iterate, with step halving when the violation grows. The rigid coordinates move first
  // (flexible bodies turned, not bent, to meet a joint or a driver's law); where they alone
  // stop halving the violation (a loop that only deformation closes), the modal coordinates
  // join, weighted by their stiffness (detail::ProjectionMetric).
  using detail::ProjectionMetric;
  const bool flexible = std::any_of(model.bodies().begin(), model.bodies().end(),
                                    [](const auto& b) { return b.nv > 6; });
  ProjectionMetric metric = flexible ? ProjectionMetric::rigid : ProjectionMetric::mass;
  for (int it = 0;; ++it) {
    if (violation <= tol) break;  // NaN falls through to the error
    if (it >= max_iterations || !std::isfinite(static_cast<double>(violation))) {
      int worst = 0;
      if (d.phi.size() > 0) d.phi.cwiseAbs().maxCoeff(&worst);
      const int joint = model.joint_of_row(worst);
      return remember(
          d, make_error(ErrorCode::not_converged,
                        "initial conditions: the joints cannot be "
                        "assembled at t = ",
                        static_cast<double>(d.t), " (largest violation ",
                        static_cast<double>(violation), " in ",
                        joint >= 0 ? model.describe_joint(joint) : std::string("no joint"), ")"));
    }
    detail::factorize_projection(model, d, metric);
    in.e = -in.penalty * d.phi;
    in.dx.setZero();
    add_jacobian_transpose_times(model, d, in.e, in.dx);
    if (metric == ProjectionMetric::rigid) detail::clear_modal(model, in.dx);
    in.cholesky.solve_in_place(in.dx);
    if (!in.dx.allFinite()) {
      violation = std::numeric_limits<Scalar>::quiet_NaN();
      continue;
    }
    copy_same_size(in.q_save, d.q);
    for (int halving = 0;; ++halving) {
      integrate_coordinates(model, d.q, in.dx);
      update_kinematics(model, d);
      update_markers(model, d);
      update_constraints(model, d);
      const Scalar trial = max_abs(d.phi);
      if (trial < violation || halving == 30) {
        if (metric == ProjectionMetric::rigid && !(trial < Scalar(0.5) * violation))
          metric = ProjectionMetric::elastic;
        violation = trial;
        break;
      }
      copy_same_size(d.q, in.q_save);
      in.dx *= Scalar(0.5);
    }
  }
  detail::factorize_projection(model, d);  // the metric at the assembled configuration
  detail::project_velocities(model, d, max_iterations);
  if (model.has_force_states()) {  // chamber pressures as set, at this position
    update_kinematics(model, d);
    update_markers(model, d);
    update_force_states(model, d, /*start=*/true);
  }
  d.lambda.setZero();
  detail::solve_accelerations(model, d, d.settings.penalty_factor, Scalar(0), Scalar(1),
                              max_iterations, tol);
  d.a = d.v_dot;
  // The scale of the Newton tolerance, fixed here: a violent phase later must not loosen it
  // (its energy error would grow with it).
  in.acceleration_scale =
      std::max(model.gravity().norm(), max_abs(d.v_dot.cwiseProduct(in.correction_scale)));
  in.lambda_last = d.lambda;
  in.has_previous = false;
  in.converged_multipliers = 1;
  in.penalty_boost = Scalar(1);
  in.boost_age = 0;
  in.reuse_backoff = 0;
  in.fresh_starts_left = 0;
  in.revision = d.revision;
  in.initialized = true;
  d.message.fill('\0');
  return Status::success();
}

namespace detail {

/// Back to the state the step started from (at t_n); the matrix is factorized anew, with the
/// penalty the step started from.
template <class Scalar>
void undo_step(Data<Scalar>& d, Scalar t_n) {
  auto& in = d.integrator;
  d.q = in.q_n;
  d.v = in.v_n;
  d.v_dot = in.vd_n;
  d.a = in.a_n;
  d.t = t_n;
  in.have_factorization = false;
  in.penalty_boost = in.penalty_boost_start;
  in.boost_age = in.boost_age_start;
}

/// One generalized-alpha step of size d.integrator.h (step() in model/step.hpp retries a
/// failed one in pieces; with control_error, a step whose local error estimate exceeds
/// local_error_tolerance fails too). On failure the state is left as it was before the step
/// (except for constraint_violation, which keeps the step).
template <class Scalar>
StepStatus step_whole(const Model<Scalar>& model, Data<Scalar>& d, bool control_error) {
  auto& in = d.integrator;
  auto& s = d.settings;
  // A runtime change (a joint switched): restart from the state as it is, as initialize()
  // does; the reason a restart failed stays in d.message.
  if (!in.initialized || d.revision != in.revision) {
    if (!initialize(model, d).ok()) return StepStatus::constraint_violation;
  }
  const Scalar h = in.h;
  // A penalty kept from earlier steps, within the largest the settings now allow.
  if (in.penalty_boost > Scalar(1))
    in.penalty_boost =
        std::max(Scalar(1), std::min(in.penalty_boost, s.max_penalty_factor / s.penalty_factor));
  in.penalty_boost_start = in.penalty_boost;
  in.boost_age_start = in.boost_age;
  copy_same_size(in.q_n, d.q);
  copy_same_size(in.v_n, d.v);
  copy_same_size(in.vd_n, d.v_dot);
  copy_same_size(in.a_n, d.a);
  const Scalar t_n = d.t;
  // The floor is the coordinates' round-off, which grows with their size (a chain 40 m long).
  in.tol_x = std::max(std::max(s.acceleration_tolerance,
                               s.relative_acceleration_tolerance * in.acceleration_scale) /
                          in.beta_prime,
                      s.position_floor * std::max(Scalar(1), max_abs(in.q_n)));
  // The joints are met to it always. A piece of a split step was taken because its step's
  // local error reached local_error_tolerance; its corrections may stop at a fraction of that
  // error instead (piece_newton_tolerance_fraction; off by default, step_settings.hpp says why).
  const Scalar tol_phi = in.tol_x;
  const bool piece = in.h != s.step;  // a piece of a split step (step())
  if (piece && s.local_error_tolerance > Scalar(0))
    in.tol_x = std::max(in.tol_x, s.piece_newton_tolerance_fraction * s.local_error_tolerance);
  copy_same_size(in.lambda_star, in.lambda_last);
  // Predictor: v_dot and lambda extrapolated linearly from the last two steps.
  if (in.has_previous && s.extrapolate_predictor && in.predict_linear)
    d.v_dot = Scalar(2) * in.vd_n - in.vd_prev;
  if (in.converged_multipliers >= 2 && s.extrapolate_multipliers)
    in.lambda_star = in.lambda_last + in.lambda_increment;
  in.a1 = ((Scalar(1) - in.alpha_f) * d.v_dot + in.alpha_f * in.vd_n - in.alpha_m * in.a_n) /
          (Scalar(1) - in.alpha_m);
  d.v = in.v_n + h * ((Scalar(1) - in.gamma) * in.a_n + in.gamma * in.a1);
  in.tmp = h * (in.v_n + h * ((Scalar(0.5) - in.beta) * in.a_n + in.beta * in.a1));
  integrate_coordinates(model, d.q, in.tmp);
  d.t = t_n + h;
  int it = 0;
  bool stale_for_next = false;
  const bool started_reused = in.have_factorization;
  bool converged = false, fresh = false, stale_step = false, restored = false, diverged = false;
  int growth = 0, slow = 0;
  bool raised = false, met_to_first_order = false, raised_in_step = false;
  bool stalled = false;  // the last correction, with a fresh matrix, shrank by less than half
  Scalar previous = std::numeric_limits<Scalar>::infinity();
  Scalar left = previous;  // the last correction, or the error it leaves when estimated below it
  Scalar residual_prev = std::numeric_limits<Scalar>::infinity();
  Scalar scaled_residual_prev = residual_prev;
  d.statistics.last_factorizations = 0;
  for (; it < s.max_iterations; ++it) {
    fresh = false;
    evaluate(model, d, /*rates=*/false);
    // The last correction was computed with this penalty; its multiplier update uses it too.
    const Scalar penalty = in.penalty;
    if (!in.have_factorization || !s.reuse_factorization || (piece && s.refactorize_pieces)) {
      detail::factorize_iteration(model, d);
      fresh = true;
    }
    if (it > 0 && !restored) in.lambda_star.noalias() += (raised ? penalty : in.penalty) * d.phi;
    raised = false;
    restored = false;
    // Residual M v_dot - Q + B^T (lambda* + alpha Phi).
    in.e = in.lambda_star + in.penalty * d.phi;
    in.r = -d.force;
    add_jacobian_transpose_times(model, d, in.e, in.r);
    add_mass_times(model, d, d.v_dot, in.r);
    // A reused matrix's correction is undone when the residual rose in two measures: as forces
    // (dominated by the constraint forces that the multiplier updates settle over the
    // iterations, alpha being 1e3 times the mass) and in the units of a correction (each entry
    // over the iteration matrix's diagonal, dominated by the free motion). Forces alone rose
    // after good corrections: a rigid pendulum's reused matrix was undone at every other step.
    const Scalar residual = in.r.norm();
    const Scalar scaled_residual = in.r.cwiseQuotient(in.iteration.diagonal()).norm();
    const bool residual_rose =
        stale_step && !(residual < residual_prev) && !(scaled_residual < scaled_residual_prev);
    if (residual_rose && previous <= Scalar(10) * in.tol_x) {
      detail::factorize_iteration(model, d);
      fresh = true;
      stale_step = false;
      stale_for_next = stale_for_next || s.refactor_after_stale_step;
    } else if (residual_rose) {
      stale_for_next = stale_for_next || s.refactor_after_stale_step;
      copy_same_size(d.q, in.q_save);
      copy_same_size(d.v, in.v_save);
      copy_same_size(d.v_dot, in.vd_save);
      copy_same_size(in.lambda_star, in.lambda_save);
      in.have_factorization = false;
      stale_step = false;
      restored = true;
      ++d.statistics.undone_corrections;
      continue;
    }
    in.dx = -in.r;
    detail::solve_turned(model, d, in.dx, fresh);
    Scalar size = detail::correction_size(d);
    if (!std::isfinite(size)) {
      diverged = true;
      break;
    }
    const bool stale = !fresh && it > 0 && size > s.refactor_rate * previous;
    if (stale && it == 1 && !s.accept_at_iteration_limit) {
      stale_for_next = true;
    } else if (stale) {
      // Stale within this step's motion: it will be stale again by the next step's predictor.
      stale_for_next = stale_for_next || s.refactor_after_stale_step;
      detail::factorize_iteration(model, d);
      fresh = true;
      in.dx = -in.r;
      detail::solve_turned(model, d, in.dx, fresh);
      size = detail::correction_size(d);
    }
    // One Uzawa pass on the linearized constraints (settings.linearized_multipliers), with a
    // matrix of this iterate only: with a stale one, whose alpha B^T B is another B's, the pass
    // can overshoot (it contracts only while alpha B S^-1 B^T < 2). The multipliers' update
    // e = alpha (Phi + B dx) is applied below, with the correction.
    const bool multiplier_pass =
        model.num_constraints() > 0 && fresh &&
        (s.linearized_multipliers == LinearizedMultipliers::always ||
         (s.linearized_multipliers == LinearizedMultipliers::pieces && piece));
    if (multiplier_pass) {
      jacobian_times(model, d, in.dx, in.lambda_pass);
      in.lambda_pass += d.phi;
      in.lambda_pass *= in.penalty;
      in.tmp.setZero();
      add_jacobian_transpose_times(model, d, in.lambda_pass, in.tmp);
      detail::solve_turned(model, d, in.tmp, fresh);
      in.dx -= in.tmp;
      size = detail::correction_size(d);
    }
    const Scalar last = previous;
    previous = size;
    stalled = fresh && it > 0 && previous > Scalar(0.5) * last;
    // Newton with a fresh matrix converges near the solution; corrections that grow twice in a
    // row with one, beyond the step's own motion, diverge: the step is too large for the
    // motion. Stop before the state does. (Near a singular configuration corrections may stall
    // or grow a little while far below the motion; the iteration limit handles those.)
    growth = fresh && it > 0 && previous > last ? growth + 1 : 0;
    // The augmented Lagrangian's multiplier updates contract by about
    // 1 / (1 + penalty sigma^2) per iteration in a direction where the constraint Jacobian's
    // singular value is sigma: near a singular configuration, or in a long chain, slowly even
    // with a fresh matrix. Two iterations in a row that shrink by less than a factor of four
    // (a fresh matrix's Newton contracts faster), on constraints already met, raise the penalty
    // tenfold (up to max_penalty_factor). (With constraints not met the slow contraction is the
    // step's nonlinearity, which a larger penalty, whose transient forces alpha Phi the matrix
    // leaves out, makes worse: the flexible slider crank at 1 ms.)
    slow = fresh && it > 0 && previous > in.tol_x && previous > Scalar(0.25) * last &&
                   max_abs(d.phi) <= tol_phi
               ? slow + 1
               : 0;
    if (slow >= 2 && s.penalty_factor > Scalar(0) &&
        in.penalty_boost * s.penalty_factor < s.max_penalty_factor) {
      in.penalty_boost =
          std::min(Scalar(10) * in.penalty_boost, s.max_penalty_factor / s.penalty_factor);
      in.have_factorization = false;
      raised = raised_in_step = true;
      slow = 0;
    }
    if (growth >= 2 &&
        previous > h * max_abs(in.v_n.cwiseProduct(in.correction_scale)) + Scalar(100) * in.tol_x) {
      diverged = true;
      break;
    }
    stale_step = !fresh;
    if (stale_step) {
      copy_same_size(in.q_save, d.q);
      copy_same_size(in.v_save, d.v);
      copy_same_size(in.vd_save, d.v_dot);
      copy_same_size(in.lambda_save, in.lambda_star);
    }
    residual_prev = residual;
    scaled_residual_prev = scaled_residual;
    if (multiplier_pass) in.lambda_star += in.lambda_pass;
    integrate_coordinates(model, d.q, in.dx);
    d.v_dot.noalias() += in.beta_prime * in.dx;
    d.v.noalias() += in.gamma_prime * in.dx;
    // Converged when this correction is within the tolerance, or (whole steps) when the error
    // it leaves is: theta / (1 - theta) |dx| with the contraction rate theta = |dx| / |dx_prev|
    // (Hairer & Wanner, Solving ODEs II, IV.8 (8.10)). The pieces of a split step, taken where
    // the motion outruns the matrix, trust that rate only where the multiplier pass makes the
    // contraction quadratic.
    left = previous;
    if (left > in.tol_x && it > 0 && (!piece || multiplier_pass) &&
        s.newton_error_estimate_fraction > Scalar(0) && previous < last && std::isfinite(last)) {
      const Scalar theta = previous / last, estimate = theta / (Scalar(1) - theta) * previous;
      if (estimate <= s.newton_error_estimate_fraction * in.tol_x) left = estimate;
    }
    // Phi was evaluated at the iterate this correction started from. When it is not within the
    // tolerance, the constraints count as met if Phi + B dx is: the violation at the new
    // iterate to first order (the rest, of order |dx|^2 over the mechanism's lengths, is far
    // below the tolerance once the correction or the error it leaves is within it).
    bool constraints_met = max_abs(d.phi) <= tol_phi;
    if (left <= in.tol_x && !constraints_met) {
      jacobian_times(model, d, in.dx, in.e);
      in.e += d.phi;
      constraints_met = max_abs(in.e) <= tol_phi;
      met_to_first_order = constraints_met;
    }
    if (left <= in.tol_x && constraints_met) {
      converged = true;
      ++it;
      break;
    }
  }
  if (restored) {
    // The loop ended on a correction undone (a budget reached right after it): the state is the
    // iterate before that correction, but Phi, B and dx are still the undone one's. The
    // multipliers, the joints' check and the drift test below read them: evaluate the kept
    // iterate, which takes no correction.
    evaluate(model, d, /*rates=*/false);
    in.dx.setZero();
  }
  d.statistics.last_iterations = it;
  d.statistics.last_correction = static_cast<double>(left / in.tol_x);
  d.statistics.iterations += it;
  // A sum is finite only if every term is (or it overflowed, itself a blow-up): a vectorized
  // test where allFinite() compares entry by entry.
  const bool finite = std::isfinite(d.v.sum() + d.v_dot.sum() + d.q.sum());
  bool kept_at_limit = false, kept_stalled = false;
  if (!converged && finite && it >= s.max_iterations) {
    // Stalled within the joints' tolerance: more iterations would not move the state by more
    // than a joint may be off (keep_stalled_steps). A budget too small for a step that still
    // converges is not that: its corrections shrink fast.
    kept_stalled = !s.accept_at_iteration_limit && s.keep_stalled_steps && stalled &&
                   previous <= s.violation_limit && max_abs(d.phi) <= s.violation_limit;
    if (s.accept_at_iteration_limit || kept_stalled) {
      converged = true;
      kept_at_limit = true;
      ++d.statistics.over_budget;
      if (kept_stalled) ++d.statistics.stalled_steps;
    }
  }
  if (!converged || !finite) {
    // A step from a finite state that diverges or turns non-finite was too large for the
    // motion, unless a law it follows is not finite there (invalid input, not to be split);
    // from a non-finite state it could not start. d.message says where.
    const bool start_finite = in.q_n.allFinite() && in.v_n.allFinite() && in.vd_n.allFinite();
    const int bad_law = start_finite ? detail::nonfinite_law(model, d, t_n + h) : -1;
    const StepStatus status = !start_finite         ? StepStatus::non_finite_state
                              : bad_law >= 0        ? StepStatus::invalid_input
                              : diverged || !finite ? StepStatus::step_too_large
                                                    : StepStatus::newton_not_converged;
    detail::undo_step(d, t_n);
    if (bad_law >= 0)
      detail::explain_nonfinite_law(model, d, bad_law, t_n, t_n + h);
    else
      detail::explain_step_failure(model, d, status, t_n, it, previous, in.tol_x);
    return status;
  }
  // Local error estimate of the converged step (Zienkiewicz & Xie, Earthquake Eng. Struct.
  // Dyn. 20 (1991), for Newmark's method): |beta - 1/6| h^2 |v_dot(n+1) - v_dot(n)|, a
  // displacement (m, rad; modal coordinates counted with their largest nodal translation).
  // Above local_error_tolerance, and when the caller can still split the step (step()), the
  // step is undone and reported as too large for the motion.
  {
    in.tmp = (d.v_dot - in.vd_n).cwiseProduct(in.correction_scale);
    Index worst = 0;
    const Scalar largest = in.tmp.size() > 0 ? in.tmp.cwiseAbs().maxCoeff(&worst) : Scalar(0);
    const Scalar estimate = std::abs(in.beta - Scalar(1) / Scalar(6)) * h * h * largest;
    in.last_error_estimate = estimate;
    if (control_error && s.local_error_tolerance > Scalar(0) &&
        estimate > s.local_error_tolerance) {
      detail::undo_step(d, t_n);
      detail::explain_local_error(model, d, t_n, estimate, worst);
      return StepStatus::step_too_large;
    }
    d.statistics.largest_error_estimate =
        std::max(d.statistics.largest_error_estimate, static_cast<double>(estimate));
    if (s.local_error_tolerance > Scalar(0) && estimate > s.local_error_tolerance)
      ++d.statistics.above_error_tolerance;
  }
  // Matrices that go stale in the first step that reuses them (the flexible four-bar, a
  // swinging pendulum) cost two extra corrections each time: after each such miss in a row,
  // twice as many steps refactorize at their start (up to refactor_backoff_limit).
  if (s.refactor_after_stale_step) {
    if (started_reused) {
      in.reuse_backoff = stale_for_next ? std::min(std::max(1, 2 * in.reuse_backoff),
                                                   std::max(1, s.refactor_backoff_limit))
                                        : 0;
      in.fresh_starts_left = in.reuse_backoff;
    } else if (in.fresh_starts_left > 0) {
      --in.fresh_starts_left;
    }
    stale_for_next = stale_for_next || in.fresh_starts_left > 0;
  }
  if (stale_for_next) in.have_factorization = false;
  // A raised penalty stays for penalty_hold_steps steps (a mechanism whose multipliers
  // converged slowly will again), then falls tenfold. The age saturates at the hold.
  in.boost_age = raised_in_step                        ? 0
                 : in.boost_age < s.penalty_hold_steps ? in.boost_age + 1
                                                       : s.penalty_hold_steps;
  if (in.penalty_boost > Scalar(1) && in.boost_age >= s.penalty_hold_steps) {
    in.penalty_boost = std::max(Scalar(1), in.penalty_boost / Scalar(10));
    in.have_factorization = false;
    in.boost_age = 0;
  }
  // The multipliers of the converged equations are lambda* + alpha Phi at the final positions,
  // Phi + B dx to first order in the last correction dx (the workspace holds Phi and B of the
  // last iterate). lambda* alone, where the next step starts from, would be off by alpha Phi:
  // with the penalty alpha ~ 1e9 m_ref, a reaction error of 0.1 % at a violation of 1e-12.
  jacobian_times(model, d, in.dx, in.e);
  in.e += d.phi;
  d.lambda = in.lambda_star + in.penalty * in.e;
  // The predictor's next increment: this step's change less a part of the increment it was
  // predicted with (multiplier_trend_memory; all of it is kept for 1, linear extrapolation).
  if (in.converged_multipliers >= 2 && s.extrapolate_multipliers)
    in.lambda_increment = (in.lambda_star - in.lambda_last) -
                          (Scalar(1) - s.multiplier_trend_memory) * in.lambda_increment;
  else
    in.lambda_increment = in.lambda_star - in.lambda_last;
  copy_same_size(in.lambda_last, in.lambda_star);
  // Under a Newton budget, a step whose constraints were met to first order only had too few
  // multiplier updates to show a trend: the next step starts from its multipliers without
  // extrapolating (as after a step kept at the budget; extrapolated, the crane under a budget
  // of two drifted off its joints within 1.4 s).
  const bool unsettled = kept_at_limit || (met_to_first_order && s.accept_at_iteration_limit);
  in.converged_multipliers = unsettled ? 0 : std::min(in.converged_multipliers + 1, 2);
  if (in.has_previous) {
    const Scalar linear_miss = (d.v_dot - Scalar(2) * in.vd_n + in.vd_prev)
                                   .cwiseProduct(in.correction_scale)
                                   .cwiseAbs()
                                   .maxCoeff();
    const Scalar constant_miss =
        (d.v_dot - in.vd_n).cwiseProduct(in.correction_scale).cwiseAbs().maxCoeff();
    in.predict_linear = linear_miss <= constant_miss;
  }
  copy_same_size(in.vd_prev, in.vd_n);
  in.has_previous = true;
  ++d.statistics.steps;
  // Drift: |B v + Phi_t| with B of the last iterate (velocity_drift_limit).
  bool project = s.project_velocities || kept_stalled, drifted = false;
  if (!project && s.velocity_drift_limit > Scalar(0) && model.num_constraints() > 0) {
    jacobian_times(model, d, d.v, in.e);
    in.e += d.phi_t;
    // Sound drift is O(h^2): the limit shrinks with h^2 below 1 ms, down to round-off's level.
    const Scalar h_ms = std::min(Scalar(1), s.step / Scalar(1e-3));
    const Scalar limit = std::max(s.velocity_drift_limit * h_ms * h_ms * (Scalar(1) + max_abs(d.v)),
                                  s.position_floor * std::max(Scalar(1), max_abs(d.q)) / s.step);
    drifted = project = max_abs(in.e) > limit;
    if (project) ++d.statistics.drift_projections;
  }
  if (s.refresh_workspace || project || model.has_force_states()) {
    update_kinematics(model, d);
    update_markers(model, d);
    update_constraints(model, d);
  }
  if (model.has_force_states()) update_force_states(model, d, /*start=*/false);
  if (project) {
    // Drifted velocities: in the mass metric, as S is no measure of kinetic energy (in S, 6
    // conservative random mechanisms gained over 1 % energy, in M none); its own factorization.
    if (drifted) {
      detail::factorize_projection(model, d);
      ++d.statistics.factorizations;
      ++d.statistics.last_factorizations;
    }
    // A singular configuration's lost directions contract slowly in the projection too.
    detail::project_velocities(model, d, (kept_stalled ? 10 : 1) * s.projection_iterations);
    if (s.project_accelerations) {
      update_kinematics(model, d);
      update_markers(model, d);
      update_constraints(model, d);
      detail::project_accelerations(model, d, s.projection_iterations);
    }
  }
  d.a = ((Scalar(1) - in.alpha_f) * d.v_dot + in.alpha_f * in.vd_n - in.alpha_m * in.a_n) /
        (Scalar(1) - in.alpha_m);
  if (max_abs(d.phi) > s.violation_limit) {
    detail::explain_violation(model, d, d.phi, "position", kept_at_limit);
    return StepStatus::constraint_violation;
  }
  if (project) {
    jacobian_times(model, d, d.v, in.e);
    in.e += d.phi_t;
    if (max_abs(in.e) > s.violation_limit * (Scalar(1) + max_abs(d.v))) {
      detail::explain_violation(model, d, in.e, "velocity", kept_at_limit);
      return StepStatus::constraint_violation;
    }
  }
  return kept_at_limit ? StepStatus::budget_reached : StepStatus::ok;
}

}  // namespace detail

}  // namespace flexstress
