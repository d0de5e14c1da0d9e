// Explicit integration for cheap, non-stiff models: classical fourth-order Runge-Kutta on
// (R, theta, p, v) with the quaternion rate theta_dot = 1/2 G_bar^T w, accelerations from the
// index-1 augmented Lagrangian with Baumgarte stabilization (detail::solve_accelerations, the
// one the implicit integrator's initialization uses), and a mass-weighted projection of
// positions and velocities back onto the constraints after every step.
//
// RK4 is stable for h w <= 2.78 (its stability interval on the imaginary axis, 2 sqrt 2); a
// step whose h times the highest modal frequency exceeds that is refused with
// StepStatus::step_above_stability_limit instead of blowing up silently. Force elements with
// internal states (hydraulic cylinders) are solved inside the implicit step only.
#pragma once

#include <cmath>
#include <type_traits>

#include <Eigen/Core>

#include "flexstress/core/euler_parameters.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/model/data.hpp"
#include "flexstress/model/implicit_step.hpp"
#include "flexstress/model/model.hpp"
#include "flexstress/model/pipeline.hpp"

namespace flexstress {

template <class Scalar>
struct ExplicitSettings {
  Scalar step = Scalar(1e-3);
  /// Baumgarte stabilization of the acceleration constraint: w_b (rad/s; 0: 0.1 / h) and zeta.
  Scalar baumgarte_frequency = Scalar(0);
  Scalar baumgarte_damping = Scalar(1);
  Scalar penalty_factor = std::is_same_v<Scalar, float> ? Scalar(1e3) : Scalar(1e6);
  int acceleration_iterations = 20;
  Scalar acceleration_tolerance = Scalar(100) * std::numeric_limits<Scalar>::epsilon();
  /// Projection of positions and velocities onto the constraints after each step.
  bool project = true;
  int projection_iterations = 3;
  /// RK4's stability bound on h times the highest frequency.
  Scalar stability_limit = Scalar(2.78);
};

/// Largest h * omega over the model's modes for step h.
template <class Scalar>
Scalar stability_number(const Model<Scalar>& model, Scalar h) {
  Scalar w = Scalar(0);
  for (const auto& b : model.bodies()) w = std::max(w, b.max_frequency);
  return h * w;
}

namespace detail {

template <class Scalar>
void explicit_accelerations(const Model<Scalar>& model, Data<Scalar>& d,
                            const ExplicitSettings<Scalar>& s) {
  const Scalar wb =
      s.baumgarte_frequency > Scalar(0) ? s.baumgarte_frequency : Scalar(0.1) / s.step;
  solve_accelerations(model, d, s.penalty_factor, wb, s.baumgarte_damping,
                      s.acceleration_iterations, s.acceleration_tolerance);
}

/// Mass-weighted projection of positions onto Phi = 0 and of velocities onto B v + Phi_t = 0,
/// with one factorization of M + alpha B^T B at the step's end.
template <class Scalar>
void project_explicit(const Model<Scalar>& model, Data<Scalar>& d,
                      const ExplicitSettings<Scalar>& s) {
  auto& in = d.integrator;
  evaluate(model, d);
  start_iteration_matrix(model, d, in.iteration);
  in.penalty = s.penalty_factor * max_abs(in.iteration.diagonal());
  add_constraint_gram(model, d, in.penalty, in.iteration);
  in.cholesky.compute(in.iteration);
  record_rotations(model, d);
  in.have_factorization = false;
  for (int k = 0; k < s.projection_iterations; ++k) {
    in.e = -in.penalty * d.phi;
    in.dx.setZero();
    add_jacobian_transpose_times(model, d, in.e, in.dx);
    in.cholesky.solve_in_place(in.dx);
    integrate_coordinates(model, d.q, in.dx);
    update_kinematics(model, d);
    update_markers(model, d);
    update_constraints(model, d);
  }
  for (int k = 0; k < s.projection_iterations; ++k) {
    jacobian_times(model, d, d.v, in.e);
    in.e += d.phi_t;
    in.e *= in.penalty;
    in.tmp.setZero();
    add_jacobian_transpose_times(model, d, in.e, in.tmp);
    in.cholesky.solve_in_place(in.tmp);
    d.v -= in.tmp;
  }
}

/// RK4 combination in coordinates: R and p with the weighted stage velocities; theta with the
/// weighted quaternion rates of the four stages at the stage orientations (fourth order).
template <class Scalar>
void combine_stages(const Model<Scalar>& model, Data<Scalar>& d, Scalar h) {
  auto& rk = d.rk4;
  d.integrator.dx = (rk.v[0] + Scalar(2) * rk.v[1] + Scalar(2) * rk.v[2] + rk.v[3]) * (h / 6);
  d.q = d.integrator.q_n;
  for (const auto& b : model.bodies()) {
    const int o = b.v_offset;
    const EulerParameters<Scalar> theta0(d.integrator.q_n.template segment<4>(b.q_offset + 3));
    const auto stage_theta = [&](int k, Scalar dt) {
      return compose<Scalar>(
          theta0, exp_rotation<Scalar>(Vec3<Scalar>(dt * rk.v[k].template segment<3>(o + 3))));
    };
    const auto rate = [&](const EulerParameters<Scalar>& t, int k) {
      return euler_parameter_rates<Scalar>(t, Vec3<Scalar>(rk.v[k].template segment<3>(o + 3)));
    };
    const EulerParameters<Scalar> t2 = stage_theta(0, h / 2), t3 = stage_theta(1, h / 2),
                                  t4 = stage_theta(2, h);
    const EulerParameters<Scalar> dtheta =
        h / 6 * (rate(theta0, 0) + 2 * rate(t2, 1) + 2 * rate(t3, 2) + rate(t4, 3));
    d.q.template segment<4>(b.q_offset + 3) =
        normalized<Scalar>(EulerParameters<Scalar>(theta0 + dtheta));
    d.q.template segment<3>(b.q_offset) += d.integrator.dx.template segment<3>(o);
    if (b.modes > 0)
      d.q.segment(b.q_offset + 7, b.modes) += d.integrator.dx.segment(o + 6, b.modes);
  }
}

}  // namespace detail

/// One RK4 step of size s.step from d's state (t, q, v; d.lambda is the multipliers' first
/// guess). Never allocates or throws; on failure d's state is left as it was.
template <class Scalar>
StepStatus explicit_step(const Model<Scalar>& model, Data<Scalar>& d,
                         const ExplicitSettings<Scalar>& s = ExplicitSettings<Scalar>()) {
  if (model.has_force_states()) return StepStatus::invalid_input;  // see the file comment
  if (stability_number(model, s.step) > s.stability_limit)
    return StepStatus::step_above_stability_limit;
  auto& in = d.integrator;
  auto& rk = d.rk4;
  in.initialized = false;  // an implicit step after this one starts afresh from the state
  const Scalar h = s.step, t0 = d.t;
  begin_input_span(d, h);
  in.q_n = d.q;
  in.v_n = d.v;
  in.lambda_save = d.lambda;
  // Stage k starts from q0 moved along the previous stage's velocity (exact on the group).
  const Scalar offsets[4] = {Scalar(0), h / 2, h / 2, h};
  for (int k = 0; k < 4; ++k) {
    if (k > 0) {
      d.q = in.q_n;
      in.tmp = offsets[k] * rk.v[k - 1];
      integrate_coordinates(model, d.q, in.tmp);
      d.v = in.v_n + offsets[k] * rk.k[k - 1];
      d.t = t0 + offsets[k];
    }
    rk.v[k] = d.v;
    detail::explicit_accelerations(model, d, s);
    rk.k[k] = d.v_dot;
  }
  detail::combine_stages(model, d, h);
  d.v = in.v_n + (h / 6) * (rk.k[0] + Scalar(2) * rk.k[1] + Scalar(2) * rk.k[2] + rk.k[3]);
  d.t = t0 + h;
  if (s.project) detail::project_explicit(model, d, s);
  if (!d.v.allFinite() || !d.q.allFinite()) {
    d.q = in.q_n;
    d.v = in.v_n;
    d.t = t0;
    d.lambda = in.lambda_save;
    return StepStatus::non_finite_state;
  }
  detail::explicit_accelerations(model, d, s);
  d.a = d.v_dot;
  ++d.statistics.steps;
  end_input_span(d);
  return StepStatus::ok;
}

}  // namespace flexstress
