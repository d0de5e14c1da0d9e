// The implicit step's building blocks over (model, data): its parameters, the iteration matrix
// S = M b' + D g' + K + alpha B^T B (D and K of the bodies and the spring-dampers; factorized
// in its envelope, reused and turned with the bodies), the solves and projections on it, and
// the index-1 acceleration solve that consistent initial conditions and the explicit
// integrator share. model/implicit_step.hpp explains the method; these are its pieces.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <Eigen/Core>

#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/model/data.hpp"
#include "flexstress/model/model.hpp"
#include "flexstress/model/pipeline.hpp"

namespace flexstress {

namespace detail {

/// The integrator's constants for steps (or pieces of a step) of size h.
template <class Scalar>
void set_step_parameters(Data<Scalar>& d, Scalar h) {
  auto& in = d.integrator;
  const Scalar rho = d.settings.spectral_radius;
  in.h = h;
  in.alpha_m = (Scalar(2) * rho - Scalar(1)) / (rho + Scalar(1));
  in.alpha_f = rho / (rho + Scalar(1));
  in.gamma = Scalar(0.5) - in.alpha_m + in.alpha_f;
  in.beta = Scalar(0.25) * (in.gamma + Scalar(0.5)) * (in.gamma + Scalar(0.5));
  in.beta_prime = (Scalar(1) - in.alpha_m) / (h * h * in.beta * (Scalar(1) - in.alpha_f));
  in.gamma_prime = in.gamma / (h * in.beta);
  in.tol_x = std::max(d.settings.acceleration_tolerance / in.beta_prime, d.settings.position_floor);
  in.have_factorization = false;
}

template <class Scalar>
void record_rotations(const Model<Scalar>& model, Data<Scalar>& d) {
  for (std::size_t b = 0; b < model.bodies().size(); ++b)
    d.integrator.factorized_rotations[b] = d.rotation[b];
}

/// S = M b' + D g' + K + alpha B^T B at the current evaluation.
template <class Scalar>
void factorize_iteration(const Model<Scalar>& model, Data<Scalar>& d) {
  auto& in = d.integrator;
  start_iteration_matrix(model, d, in.iteration);
  const Scalar m_ref = max_abs(in.iteration.diagonal());
  scale_body_blocks(model, in.iteration, in.beta_prime);
  add_modal_stiffness_damping(model, d, in.iteration, Scalar(1), in.gamma_prime);
  add_force_element_tangent(model, d, in.iteration, Scalar(1), in.gamma_prime);
  in.penalty = d.settings.penalty_factor * in.penalty_boost * in.beta_prime * m_ref;
  add_constraint_gram(model, d, in.penalty, in.iteration);
  in.cholesky.compute(in.iteration);
  record_rotations(model, d);
  in.have_factorization = true;
  ++d.statistics.factorizations;
  ++d.statistics.last_factorizations;
}

/// What a projection outside a step may change, and at what cost.
enum class ProjectionMetric {
  mass,     ///< W = M: least kinetic energy change (velocities, as an impulse would)
  rigid,    ///< the rigid coordinates only, W = M on them (modal coordinates kept)
  elastic,  ///< W = M + K / omega_0^2, omega_0 = 2 pi x 1 Hz: a mode of frequency f costs
            ///< (f / 1 Hz)^2 times a rigid motion of the same modal mass
};

/// The metric of projections outside a step: W + alpha B^T B (evaluates at the state). With
/// ProjectionMetric::rigid the modal rows and columns are identity rows and columns, so a
/// solve leaves the modal entries of its right-hand side as they are (clear_modal them).
template <class Scalar>
void factorize_projection(const Model<Scalar>& model, Data<Scalar>& d,
                          ProjectionMetric metric = ProjectionMetric::mass) {
  auto& in = d.integrator;
  evaluate(model, d);
  start_iteration_matrix(model, d, in.iteration);
  if (metric == ProjectionMetric::elastic) {
    const Scalar omega_0 = Scalar(2 * 3.14159265358979323846);
    add_modal_stiffness_damping(model, d, in.iteration, Scalar(1) / (omega_0 * omega_0), Scalar(0));
  }
  const Scalar m_ref = max_abs(in.iteration.diagonal());
  in.penalty = d.settings.penalty_factor * m_ref;
  add_constraint_gram(model, d, in.penalty, in.iteration);
  if (metric == ProjectionMetric::rigid)
    for (const auto& b : model.bodies())
      for (int k = b.v_offset + 6; k < b.v_offset + b.nv; ++k) {
        in.iteration.row(k).setZero();
        in.iteration.col(k).setZero();
        in.iteration(k, k) = Scalar(1);
      }
  in.cholesky.compute(in.iteration);
  record_rotations(model, d);
  in.have_factorization = false;  // the step needs its own matrix
}

/// Zeroes the modal coordinates' entries of a velocity-space vector.
template <class Scalar, class V>
void clear_modal(const Model<Scalar>& model, V& x) {
  for (const auto& b : model.bodies())
    if (b.nv > 6) x.segment(b.v_offset + 6, b.nv - 6).setZero();
}

/// x <- S^-1 x, turned with the bodies unless S was factorized at this iterate (`fresh`):
/// x <- Q S^-1 Q^T x, Q rotating each body's R_dot part by A_now A_factorized^T.
template <class Scalar, class V>
void solve_turned(const Model<Scalar>& model, Data<Scalar>& d, V& x, bool fresh) {
  auto& in = d.integrator;
  const bool turn = d.settings.corotate_factorization && !fresh;
  const auto& bodies = model.bodies();
  if (turn)
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      auto t = x.template segment<3>(bodies[b].v_offset);
      const Vec3<Scalar> local =
          in.factorized_rotations[b] * (d.rotation[b].transpose() * Vec3<Scalar>(t));
      t = local;
    }
  in.cholesky.solve_in_place(x);
  if (turn)
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      auto t = x.template segment<3>(bodies[b].v_offset);
      const Vec3<Scalar> global =
          d.rotation[b] * (in.factorized_rotations[b].transpose() * Vec3<Scalar>(t));
      t = global;
    }
}

/// v <- v - S^-1 alpha B^T (B v + Phi_t), repeated (the workspace holds B and Phi_t at d).
template <class Scalar>
void project_velocities(const Model<Scalar>& model, Data<Scalar>& d, int iterations) {
  auto& in = d.integrator;
  for (int k = 0; k < iterations; ++k) {
    jacobian_times(model, d, d.v, in.e);
    in.e += d.phi_t;
    if (max_abs(in.e) <= d.settings.position_floor * (Scalar(1) + max_abs(d.v))) break;
    in.e *= in.penalty;
    in.tmp.setZero();
    add_jacobian_transpose_times(model, d, in.e, in.tmp);
    solve_turned(model, d, in.tmp, false);
    d.v -= in.tmp;
  }
}

/// v_dot <- v_dot - S^-1 alpha B^T (B v_dot + conv), repeated.
template <class Scalar>
void project_accelerations(const Model<Scalar>& model, Data<Scalar>& d, int iterations) {
  auto& in = d.integrator;
  for (int k = 0; k < iterations; ++k) {
    jacobian_times(model, d, d.v_dot, in.e);
    in.e += d.conv;
    if (max_abs(in.e) <= d.settings.position_floor * (Scalar(1) + max_abs(d.v_dot))) break;
    in.e *= in.penalty;
    in.tmp.setZero();
    add_jacobian_transpose_times(model, d, in.e, in.tmp);
    solve_turned(model, d, in.tmp, false);
    d.v_dot -= in.tmp;
  }
}

/// Accelerations and multipliers at d's state (index-1 form) by the augmented Lagrangian
/// iteration of Bayo, Garcia de Jalon and Serna (Comput. Methods Appl. Mech. Eng. 71 (1988)):
///   (M + alpha B^T B) v_dot = Q - B^T lambda - alpha B^T c,   lambda += alpha (B v_dot + c),
/// with c = conv + 2 zeta w_b (B v + Phi_t) + w_b^2 Phi (Baumgarte stabilization; w_b = 0 gives
/// the acceleration constraint itself), from d.lambda as the first guess. Works with redundant
/// constraints: M + alpha B^T B stays positive definite. Returns the final residual of the
/// acceleration constraint (infinity norm). Consistent initial accelerations and the explicit
/// integrator both use it.
template <class Scalar>
Scalar solve_accelerations(const Model<Scalar>& model, Data<Scalar>& d, Scalar penalty_factor,
                           Scalar baumgarte_frequency, Scalar baumgarte_damping, int iterations,
                           Scalar tolerance) {
  auto& in = d.integrator;
  for (std::size_t k = 0; k < model.joints().size(); ++k)  // switched-off joints: no reaction
    if (!d.joint_active[k])
      d.lambda.segment(model.joints()[k].row, model.joints()[k].equations).setZero();
  evaluate(model, d);
  start_iteration_matrix(model, d, in.iteration);
  in.penalty = penalty_factor * max_abs(in.iteration.diagonal());
  add_constraint_gram(model, d, in.penalty, in.iteration);
  in.cholesky.compute(in.iteration);
  record_rotations(model, d);
  in.have_factorization = false;  // the step needs its own matrix
  auto& c = in.lambda_save;       // scratch: the stabilized right-hand side
  c = d.conv;
  if (baumgarte_frequency > Scalar(0)) {
    jacobian_times(model, d, d.v, in.e);
    in.e += d.phi_t;
    c += Scalar(2) * baumgarte_damping * baumgarte_frequency * in.e +
         baumgarte_frequency * baumgarte_frequency * d.phi;
  }
  Scalar residual = Scalar(0);
  for (int it = 0; it < iterations; ++it) {
    in.e = -(d.lambda + in.penalty * c);
    in.r = d.force;
    add_jacobian_transpose_times(model, d, in.e, in.r);
    d.v_dot = in.r;
    in.cholesky.solve_in_place(d.v_dot);
    jacobian_times(model, d, d.v_dot, in.e);
    in.e += c;
    d.lambda += in.penalty * in.e;
    residual = max_abs(in.e);
    if (residual <= tolerance * (Scalar(1) + max_abs(c))) break;
  }
  return residual;
}

template <class Scalar>
Scalar correction_size(const Data<Scalar>& d) {
  return max_abs(d.integrator.dx.cwiseProduct(d.integrator.correction_scale));
}

template <class Scalar>
Status remember(Data<Scalar>& d, Status s) {
  if (!s.ok()) std::snprintf(d.message.data(), d.message.size(), "%s", s.error().what().c_str());
  return s;
}

}  // namespace detail

}  // namespace flexstress
