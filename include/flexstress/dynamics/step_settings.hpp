// Settings and statistics of the implicit integrator (Lie-group generalized-alpha with an
// index-3 augmented Lagrangian; model/implicit_step.hpp explains the method), shared by
// every model representation that steps with it.
#pragma once

#include <cmath>
#include <limits>
#include <type_traits>

#include "flexstress/core/status.hpp"

namespace flexstress {

/// Where each Newton correction also updates the multipliers on the linearized constraints
/// (ImplicitSettings::linearized_multipliers).
enum class LinearizedMultipliers {
  off,     ///< the multipliers move only between corrections (lambda* += alpha Phi)
  pieces,  ///< in the pieces of a split step
  always,  ///< in every step
};

template <class Scalar>
struct ImplicitSettings {
  Scalar step = Scalar(1e-3);
  /// Spectral radius at infinity: 1 conserves energy (no numerical damping), smaller values
  /// damp the highest frequencies. Scenes with joints need rho < 1: with rho = 1 (the
  /// trapezoidal rule) the multipliers of an index-3 system are only weakly stable
  /// (Cardona & Geradin, Comput. Struct. 33 (1989)), and the redundant Bricard loop still
  /// grows an oscillation at rho = 0.95 but is stable at 0.8 (measured: tests/dynamics).
  /// rho = 1 is for energy studies of unconstrained bodies.
  Scalar spectral_radius = Scalar(0.8);
  int max_iterations = 30;
  /// Newton stops when the largest correction, seen as a change of acceleration b' dx, is
  /// below the larger of acceleration_tolerance and relative_acceleration_tolerance times the
  /// model's acceleration scale (the larger of |gravity| and the largest acceleration at
  /// initialize()), and the largest constraint violation is below the same amount divided by
  /// b'. Units: m/s^2 for translations and for modal coordinates, whose corrections count with
  /// their mode's largest nodal translation (BodyModel::modal_displacement_scale; modal units
  /// would depend on how the modes are normalized), rad/s^2 for rotations. Scaling with b' ~
  /// 1/h^2 keeps the solver's error below the truncation error at every step size: a fixed
  /// position tolerance would let velocity errors g' dx ~ tol/h accumulate as an energy random
  /// walk at small h. The scale is fixed at initialize(): a violent phase later must not
  /// loosen the tolerance, nor a mechanism passing through rest tighten it.
  /// The absolute part (m/s^2): a floor for mechanisms that start at rest without gravity.
  Scalar acceleration_tolerance = std::is_same_v<Scalar, float> ? Scalar(1e-2) : Scalar(1e-5);
  /// The relative part: for a crank pin turning at 150 rad/s (3400 m/s^2) 3.4e-3 m/s^2, where
  /// further corrections only chase round-off; for the crane (gravity) below the floor.
  Scalar relative_acceleration_tolerance =
      std::is_same_v<Scalar, float> ? Scalar(1e-3) : Scalar(1e-6);
  /// Newton also stops when the error its last correction leaves is estimated within this
  /// fraction of the tolerance: theta / (1 - theta) |dx_k|, with the contraction rate theta =
  /// |dx_k| / |dx_k-1| (Hairer & Wanner, Solving ODEs II, IV.8). A correction that shrank a
  /// hundredfold needs no further correction to show it. Whole steps only: the pieces of a split
  /// step, where the motion outruns the matrix, do not trust the rate (applied to them too,
  /// 176 instead of 179 of the 200 random mechanisms ran). Measured: the crane 2.12 instead of
  /// 2.33 iterations per step, its figures unchanged; the flexible four-bar 3.08 instead of 3.49.
  /// 0: only a correction within the tolerance stops Newton.
  Scalar newton_error_estimate_fraction = Scalar(1);
  /// Floor of the position tolerances: the round-off of coordinates of order one, scaled by
  /// the largest coordinate when that is larger.
  Scalar position_floor = Scalar(100) * std::numeric_limits<Scalar>::epsilon();
  /// A converged step whose violation (position or velocity) still exceeds this reports
  /// constraint_violation.
  Scalar violation_limit = std::is_same_v<Scalar, float> ? Scalar(1e-3) : Scalar(1e-6);
  /// Penalty alpha relative to b' times the largest mass-matrix diagonal entry. Larger values
  /// converge the multipliers faster, but the iteration matrix omits the geometric stiffness
  /// of the transient penalty forces (alpha times the predictor's constraint violation), so
  /// the factor must stay well below L / |Phi_predicted| (about 1e6 at h = 1e-2, far more at
  /// h = 1e-3).
  Scalar penalty_factor = std::is_same_v<Scalar, float> ? Scalar(1e2) : Scalar(1e3);
  /// The largest penalty factor a step raises penalty_factor to where the multipliers converge
  /// slowly: tenfold after two corrections with a fresh matrix that each shrank by less than a
  /// factor of four on constraints already met (Newton with a fresh matrix contracts faster;
  /// the augmented Lagrangian's multiplier updates contract by 1 / (1 + alpha sigma^2) in a
  /// direction where the Jacobian's singular value is sigma, slowly in a long chain or near a
  /// singular configuration). penalty_factor or less: never raised. Above about 1e5 the
  /// round-off of alpha Phi on coordinates of tens of metres exceeds the correction tolerance.
  Scalar max_penalty_factor = std::is_same_v<Scalar, float> ? Scalar(1e4) : Scalar(1e5);
  /// Steps a raised penalty stays after the last step that raised it (each piece of a split
  /// step counts as one); then it falls tenfold, and again after as many steps, back to
  /// penalty_factor (0: it falls at the end of the step that raised it). A mechanism whose
  /// multipliers converge slowly (the 40-bar chain, away from its singular configurations too)
  /// keeps the larger penalty instead of raising it anew every other step; a raised penalty
  /// makes a reused matrix go stale sooner, which the mechanisms that never raise it do not
  /// pay.
  int penalty_hold_steps = 100;
  /// Keep a step that reaches max_iterations with Newton stalled short of its tolerance but
  /// within the joints': its last correction, made with a fresh matrix, shrank by less than
  /// half, and it and the constraint violation are within violation_limit. More iterations would
  /// not move such a state by more than a joint may be off: Newton is at the round-off of the
  /// equations, or at a singular configuration, where the Jacobian has lost rank and the constraint
  /// forces in the lost directions are not determined (no iteration settles them). The step returns
  /// budget_reached (counted in StepStatistics::over_budget and stalled_steps; last_correction says
  /// how far from the tolerance), its velocities projected onto the joints with ten times
  /// projection_iterations, and the next step does not extrapolate its multipliers. How the
  /// 40-bar chain passes its singular configurations on the defaults (docs/dynamics.md).
  bool keep_stalled_steps = true;
  bool reuse_factorization = true;
  /// Refactorize when a correction shrinks by less than this factor (stale matrix): at once
  /// from the third correction on; when it is the second, at the start of the next step,
  /// unless the step may end at its iteration limit (accept_at_iteration_limit), whose few
  /// iterations must contract fast.
  /// The second correction repairs the first, made with the stale matrix from the predictor,
  /// and a fresh matrix computes the same repair (measured on the crane: equal to 1 %), so
  /// refactorizing there would only pay off in later steps, which refactorizing at the next
  /// step's first iterate serves better (the crane: 0.37 instead of 0.44 factorizations and
  /// 2.61 instead of 2.73 iterations per step).
  Scalar refactor_rate = Scalar(0.25);
  /// Refactorize at the start of the next step when a matrix went stale within this one (a
  /// slow correction after the first, or one that increased the residual, made it refactorize
  /// mid-step): it would be stale again by the next predictor, and factorized there it saves
  /// the slow corrections. Measured: the stress suite's flexible pendulum 3.79 -> 3.48
  /// iterations and 0.39 -> 0.49 factorizations per step; the crane 2.32 -> 2.31 and 0.148
  /// -> 0.159 (its figures unchanged).
  bool refactor_after_stale_step = true;
  /// When the matrix goes stale in the first step that reuses it again and again, that step
  /// takes two corrections more than one that refactorizes at its start (the flexible four-bar:
  /// 4 instead of 2, alternating). After each such miss in a row twice as many steps
  /// refactorize at their start, up to this many; a reused matrix that serves its step through
  /// ends the run (1: only the next step, as refactor_after_stale_step alone). Measured: the
  /// flexible four-bar 3.03 -> 2.65 and the pendulum 3.02 -> 2.92 iterations per step, at about
  /// the same factorizations; the crane 2.12 -> 2.12 iterations, 0.148 -> 0.158 factorizations.
  int refactor_backoff_limit = 16;
  /// Reuse a factorization across rotations of the bodies. A body's own blocks of the
  /// iteration matrix (its mass matrix, M_Rw = -A skew(S) and M_Rp = A S_Phi, and the part of
  /// alpha B^T B its joints put on it) depend on its rotation A only through T S_0 T^T,
  /// T = diag(A, 1, 1) on [R_dot, w, p_dot]; the solve with a reused matrix rotates each body's
  /// R_dot components by A_now A_factorized^T (Q^T before, Q after), which is exact for those
  /// blocks and leaves the error of relative rotations in the blocks that couple two bodies.
  /// The penalty makes the rotation matter: alpha B^T B is about 1e3 times the mass matrix,
  /// and on the crane one step changed its entries coupling the boom's R_dot and a mode by
  /// 0.22 of M b'. Measured with this alone (docs/performance.md): the crane 0.37 -> 0.16
  /// factorizations and 2.61 -> 2.47 iterations per step; the flexible beam released
  /// horizontal 0.99 -> 0.39 and 4.88 -> 3.81; the rigid crane loop and the 40-bar chain
  /// unchanged. The motion is the same to the Newton
  /// tolerance: only the matrix of the modified Newton changes, not the residual.
  bool corotate_factorization = true;
  /// Project velocities onto B v + Phi_t = 0 after every step. Index-3 integration keeps the
  /// positions on the constraints, and usually the velocities within O(h^2) of them; each
  /// projection removes that component and with it an O(h^4) amount of kinetic energy per
  /// step, which costs long-run energy studies (see velocity_drift_limit for the default).
  bool project_velocities = false;
  /// Project only when the velocities have drifted: after a step whose |B v + Phi_t| exceeds
  /// this times (1 + the largest velocity) at steps of 1 ms or more, and times (h / 1 ms)^2
  /// below, since a sound run's drift is O(h^2) (the crane: 6.7e-7 over its cycle at 1 ms).
  /// The velocities of a redundant loop of 3D hinges can leave the joints and grow from
  /// round-off (the flexible slider crank: by a factor of about 2 per step, until Newton
  /// fails), and a drift well short of failing already slows Newton: that crank over 1 s at
  /// 0.1 ms takes 2.18 iterations per step with its limit at 1e-5, 4.68 at 1e-3. Drifted
  /// velocities are projected in the mass metric (a factorization of M + alpha B^T B). The
  /// limit never falls below position_floor times the largest coordinate over h, what
  /// round-off alone makes. 0 switches it off.
  Scalar velocity_drift_limit = std::is_same_v<Scalar, float> ? Scalar(1e-2) : Scalar(1e-3);
  /// Also project accelerations onto B v_dot + conv = 0 (needs project_velocities).
  bool project_accelerations = false;
  /// Evaluate the constraints once more at the accepted state, so that workspace() (Phi, B,
  /// Phi_t, conv) describes the state a step returns and its violation check reads the final
  /// positions. Off, the workspace keeps the last Newton iterate's evaluation (one correction
  /// earlier, without rates; the kept iterate's own when the step ended on an undone correction)
  /// and the check reads that iterate's Phi; the motion is the same
  /// to the bit and a step saves one constraint evaluation (8 % of the crane's step).
  /// Projections and stateful force elements need the evaluation and make it regardless.
  bool refresh_workspace = true;
  int projection_iterations = 3;
  /// Predict v_dot by linear extrapolation of the last two steps (else: constant), at each step
  /// whichever of the two would have missed the last step's v_dot less: where accelerations
  /// alternate from step to step (the constrained directions of a fast crank's rod), the linear
  /// one misses more, and its start was measured to drive the velocities off the joints.
  bool extrapolate_predictor = true;
  /// Predict the multipliers the same way (else: start from the last step's). Held constant,
  /// their change over the step is left to the penalty updates lambda* += alpha Phi, and the
  /// second Newton correction is mostly that change: on the crane it kept the contraction
  /// rate near refactor_rate, so that 0.75 steps in 1 refactorized (extrapolated: 0.44, and
  /// 2.73 iterations per step instead of 3.19; docs/performance.md).
  bool extrapolate_multipliers = true;
  /// The extrapolation's memory theta: the predicted change of lambda* is the last step's
  /// change less (1 - theta) times the change it was predicted with (1: linear extrapolation).
  /// The multipliers of redundant joints (a planar loop of 3D hinges) are not unique; linear
  /// extrapolation integrates their undetermined part twice, and it drifts until Newton stalls
  /// (the slider crank at 0.1 ms over 1 s: 41 iterations per step at 1, 5.4 at 0.9; the crane
  /// 2.32 and 2.33, 0.163 and 0.194 factorizations per step).
  Scalar multiplier_trend_memory = Scalar(0.9);
  /// Real-time budget: a step that reaches max_iterations with a finite state keeps its last
  /// iterate instead of being undone (counted in Statistics::over_budget), so each step costs
  /// at most max_iterations corrections. The accuracy this costs is measured in
  /// bench/accuracy_vs_time. It is also how a model passes singular configurations, where
  /// the multipliers are undefined and their update stalls (docs/dynamics.md, IFToMM A02).
  bool accept_at_iteration_limit = false;
  /// A step whose Newton iteration diverges or does not converge is retried in halves, and a
  /// failing half in halves again, down to step / 2^max_step_halvings; the step still ends at
  /// t + step, so a fixed-step caller keeps its clock. The next step starts with the pieces
  /// that passed, and larger ones follow when two in a row passed easily (step() in
  /// model/step.hpp), so a hard phase does not pay for a failed whole step at every step. Only
  /// hard steps pay (counted in StepStatistics::split_steps and substeps). 0: such a step fails
  /// at once. On the random
  /// mechanisms (tests/model/test_random_mechanisms.cpp) this turns most failed steps of
  /// fast, violent motions into converged ones.
  int max_step_halvings = 4;
  /// A converged step whose local error estimate, |beta - 1/6| h^2 |v_dot(n+1) - v_dot(n)|
  /// (Zienkiewicz & Xie 1991; m and rad, modal coordinates as their largest nodal translation),
  /// exceeds this is taken in pieces too (0: no error control). Measured largest estimates at
  /// 1 ms: the crane 1.5e-8, the stress suite's flexible cases up to 3.8e-6, Andrews'
  /// squeezer 0.17 (19 % off its reference at 1 ms).
  Scalar local_error_tolerance = std::is_same_v<Scalar, float> ? Scalar(1e-3) : Scalar(1e-4);
  /// Newton's corrections in the pieces of a split step stop at this fraction of
  /// local_error_tolerance (when that is above the acceleration tolerance; the joints are met to
  /// the acceleration tolerance all the same): a piece is taken because its step's local error
  /// reached the tolerance (Hairer & Wanner, Solving ODEs II, IV.8: Newton to kappa Tol, kappa
  /// 0.01 to 0.1). Measured with the pieces' Newton as whole steps' (linearized_multipliers off,
  /// refactorize_pieces false) at 1e-2: Andrews' squeezer 2.78 instead of 5.08 iterations per
  /// piece, but the violent random mechanisms' energy drifted more (the conservative ones'
  /// largest growth 77 % instead of 15 % of their kinetic energy), so it is off by default; the
  /// defaults' multiplier pass brings the squeezer to 2.33 per piece on its own.
  /// 0: pieces converge as whole steps.
  Scalar piece_newton_tolerance_fraction = Scalar(0);
  /// Each Newton correction dx also takes one Uzawa pass on the linearized constraints: the
  /// multipliers move by e = alpha (Phi + B dx) and the correction by -S^-1 B^T e (one more
  /// solve with the same factorization, two products with B). Between corrections the augmented
  /// Lagrangian moves them by alpha Phi only after the state has answered the old ones, so an
  /// error of the multipliers' predictor dl first moves the state by about dl / (M b') and is
  /// then undone, a Newton correction that contracts linearly; with the pass, it contracts
  /// quadratically, and Newton's error estimate (newton_error_estimate_fraction) is trusted
  /// in the pieces of a split step too. Where: see LinearizedMultipliers.
  LinearizedMultipliers linearized_multipliers = LinearizedMultipliers::pieces;
  /// The pieces of a split step factorize the iteration matrix at every correction (Newton
  /// instead of modified Newton; each piece starts with a fresh one either way): pieces are
  /// taken where the motion outruns a matrix. Whole steps keep reuse_factorization.
  bool refactorize_pieces = true;
};

/// Success, or an error naming the first setting out of its range.
template <class Scalar>
Status check_settings(const ImplicitSettings<Scalar>& s) {
  const auto bad = [](const char* what) {
    return make_error(ErrorCode::invalid_argument, "settings: ", what);
  };
  const auto non_negative = [](Scalar x) { return std::isfinite(x) && x >= Scalar(0); };
  if (!(s.step > Scalar(0)) || !std::isfinite(s.step))
    return bad("the step must be positive and finite");
  if (!(s.spectral_radius >= Scalar(0)) || !(s.spectral_radius <= Scalar(1)))
    return bad("the spectral radius must be in [0, 1]");
  if (s.max_iterations < 1) return bad("max_iterations must be at least 1");
  if (!non_negative(s.acceleration_tolerance) || !non_negative(s.relative_acceleration_tolerance))
    return bad(
        "acceleration_tolerance and relative_acceleration_tolerance must be finite and "
        "not negative");
  if (!(s.newton_error_estimate_fraction >= Scalar(0)) ||
      !(s.newton_error_estimate_fraction <= Scalar(1)))
    return bad("newton_error_estimate_fraction must be in [0, 1] (0: off)");
  if (!non_negative(s.local_error_tolerance))
    return bad("local_error_tolerance must be finite and not negative (0: no control)");
  if (s.linearized_multipliers != LinearizedMultipliers::off &&
      s.linearized_multipliers != LinearizedMultipliers::pieces &&
      s.linearized_multipliers != LinearizedMultipliers::always)
    return bad("linearized_multipliers must be off, pieces or always");
  if (!(s.piece_newton_tolerance_fraction >= Scalar(0)) ||
      !(s.piece_newton_tolerance_fraction <= Scalar(1)))
    return bad("piece_newton_tolerance_fraction must be in [0, 1] (0: pieces as whole steps)");
  if (!non_negative(s.velocity_drift_limit))
    return bad("velocity_drift_limit must be finite and not negative (0: never)");
  if (!(s.multiplier_trend_memory >= Scalar(0)) || !(s.multiplier_trend_memory <= Scalar(1)))
    return bad("multiplier_trend_memory must be in [0, 1]");
  if (!non_negative(s.max_penalty_factor))
    return bad("max_penalty_factor must be finite and not negative (0: never raised)");
  if (s.penalty_hold_steps < 0) return bad("penalty_hold_steps must not be negative");
  if (s.refactor_backoff_limit < 1)
    return bad("refactor_backoff_limit must be at least 1 (1: only the next step)");
  if (s.max_step_halvings < 0 || s.max_step_halvings > 20)
    return bad("max_step_halvings must be in [0, 20]");
  return Status::success();
}

struct StepStatistics {
  long steps = 0;
  long iterations = 0;
  long factorizations = 0;
  int last_iterations = 0;
  int last_factorizations = 0;
  long over_budget = 0;        ///< steps kept at the iteration limit (accept_at_iteration_limit)
  long stalled_steps = 0;      ///< of those, kept with Newton stalled (keep_stalled_steps)
  long drift_projections = 0;  ///< projections made because the velocities drifted
  /// Corrections of a reused matrix undone because the residual rose (the matrix had gone stale)
  long undone_corrections = 0;
  long split_steps = 0;               ///< steps retried in pieces (max_step_halvings)
  long substeps = 0;                  ///< the pieces those steps took
  double largest_error_estimate = 0;  ///< the largest local error estimate of a step (m, rad)
  /// Pieces kept although their estimate exceeded local_error_tolerance: the smallest ones
  /// (step / 2^max_step_halvings), which are not split further.
  long above_error_tolerance = 0;
  /// The last step's final Newton correction over its tolerance (or the error it leaves, when
  /// Newton stopped on that estimate: newton_error_estimate_fraction): at most 1 when it
  /// converged, how far from converged a step kept at the budget is.
  double last_correction = 0;
};

}  // namespace flexstress
