// Static equilibrium and linearization of a runtime model (setup-time algorithms: they may
// allocate).
//
// Static equilibrium: the coordinates at which the applied forces balance the joint reactions,
// with all velocities zero, at d.t (drivers at their prescribed positions): a run that starts
// there starts without a jolt. Solved by a pseudo-transient Newton iteration,
// S dx = -(B^T (lambda* + alpha Phi) - Q), S = K + alpha B^T B + c M (K the stiffness of the
// applied forces, -dQ/dx: elastic forces, gravity and force elements, so that a spring that
// holds a body counts; the constraint penalty; and c M with c = (2 pi f)^2 a regularization
// that vanishes at convergence and keeps rigid directions that only gravity holds from taking
// unbounded steps), and lambda* += alpha Phi after each iteration. Needs a model whose joints,
// drivers and springs hold every rigid motion (a crane driven by its cylinder, a platform on
// its suspension); a free mechanism has no static equilibrium.
//
// Linearization about an equilibrium (v = 0): M and K_eff = d/dx (B^T lambda - Q) (central
// differences, so the geometric stiffness of gravity and of the joint reactions is included),
// both projected on an orthonormal basis of the null space of B: the natural frequencies of
// small vibrations.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "flexstress/core/status.hpp"
#include "flexstress/dynamics/linearize.hpp"
#include "flexstress/model/data.hpp"
#include "flexstress/model/model.hpp"
#include "flexstress/model/pipeline.hpp"

namespace flexstress {

struct StaticEquilibriumOptions {
  int max_iterations = 200;
  /// On the correction (m, rad, modal units) and the constraint violation; 0: 1e-10, or 100
  /// epsilon if the model's Scalar cannot resolve that (float: 1.2e-5).
  double tolerance = 0.0;
  double regularization_hz = 1.0;  ///< f in c = (2 pi f)^2
  /// alpha B^T B relative to the largest diagonal of K + c M. The multiplier update removes
  /// the penalty's bias, so a moderate factor converges in a few iterations; 1e6 made the
  /// matrix of a stiff flexible body singular to double precision (condition > 1e15).
  double penalty_factor = 1e3;
};

/// B as a dense nc x nv matrix (setup: allocates).
template <class Scalar>
Eigen::MatrixXd dense_jacobian(const Model<Scalar>& model, const Data<Scalar>& d) {
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(model.num_constraints(), model.num_velocities());
  for (const auto& j : model.joints())
    for (int side = 0; side < 2; ++side) {
      const int body = side == 0 ? j.body_i : j.body_j;
      if (body < 0) continue;
      const auto& bb = model.bodies()[static_cast<std::size_t>(body)];
      b.block(j.row, bb.v_offset, j.equations, bb.nv) +=
          detail::ConstRowBlock<Scalar>(d.jacobian.data() + (side == 0 ? j.jac_i : j.jac_j),
                                        j.equations, bb.nv)
              .template cast<double>();
    }
  return b;
}

/// The stiffness of the applied forces at d's coordinates, -dQ/dx (nv x nv, central
/// differences of step `step` in m, rad and modal units; velocities as in d). Leaves d
/// evaluated at its coordinates.
template <class Scalar>
Eigen::MatrixXd applied_stiffness(const Model<Scalar>& model, Data<Scalar>& d, double step = 1e-7) {
  const int nv = model.num_velocities();
  const auto q0 = d.q;
  typename Data<Scalar>::VectorX dx = Data<Scalar>::VectorX::Zero(nv);
  Eigen::MatrixXd k(nv, nv);
  Eigen::VectorXd plus(nv);
  for (int j = 0; j < nv; ++j) {
    for (const double sign : {1.0, -1.0}) {
      d.q = q0;
      dx(j) = static_cast<Scalar>(sign * step);
      integrate_coordinates(model, d.q, dx);
      evaluate(model, d);
      if (sign > 0)
        plus = d.force.template cast<double>();
      else
        k.col(j) = -(plus - d.force.template cast<double>()) / (2 * step);
    }
    dx(j) = Scalar(0);
  }
  d.q = q0;
  evaluate(model, d);
  return k;
}

namespace detail {

/// The equilibrium iteration from d's state (solve_static_equilibrium). With `applied`, the
/// matrix has the stiffness of every applied force (applied_stiffness, symmetrized; the modal
/// stiffness alone where that is not positive definite with c M) and is factorized densely;
/// without, the modal stiffness K, in the step's envelope factorization, refactorized every
/// `refresh` iterations. Returns whether it converged; `last` is the last correction.
template <class Scalar>
bool equilibrium_iterations(const Model<Scalar>& model, Data<Scalar>& d,
                            const StaticEquilibriumOptions& opt, bool applied, int refresh,
                            Scalar& last) {
  auto& in = d.integrator;
  const int nv = model.num_velocities();
  const Scalar c =
      static_cast<Scalar>(std::pow(2.0 * 3.14159265358979323846 * opt.regularization_hz, 2));
  const Scalar tolerance = static_cast<Scalar>(
      opt.tolerance > 0.0
          ? opt.tolerance
          : std::max(1e-10, 100.0 * double(std::numeric_limits<Scalar>::epsilon())));
  typename Data<Scalar>::VectorX lambda = d.lambda, r(nv), dx(nv);
  Scalar alpha = Scalar(0);
  Eigen::LLT<Eigen::MatrixXd> llt;
  last = Scalar(0);
  for (int it = 0; it < opt.max_iterations; ++it) {
    if (applied && (it == 0 || it % 10 == 0)) {
      const Eigen::MatrixXd k_applied = applied_stiffness(model, d);
      typename Data<Scalar>::MatrixX block = Data<Scalar>::MatrixX::Zero(nv, nv);
      start_iteration_matrix(model, d, block);
      const Eigen::MatrixXd mass = block.template cast<double>();
      block.setZero();
      add_modal_stiffness_damping(model, d, block, Scalar(1), Scalar(0));
      const Eigen::MatrixXd modal = block.template cast<double>();
      const Eigen::MatrixXd b = dense_jacobian(model, d);
      const double jtj = b.size() ? b.colwise().squaredNorm().maxCoeff() : 0.0;
      bool factorized = false;
      for (int attempt = 0; attempt < 2 && !factorized; ++attempt) {
        Eigen::MatrixXd s =
            (attempt == 0 ? Eigen::MatrixXd(0.5 * (k_applied + k_applied.transpose())) : modal) +
            double(c) * mass;
        const double a =
            opt.penalty_factor * s.diagonal().cwiseAbs().maxCoeff() / (jtj > 0 ? jtj : 1.0);
        s.noalias() += a * b.transpose() * b;
        llt.compute(s);
        factorized = llt.info() == Eigen::Success;
        alpha = static_cast<Scalar>(a);
      }
      if (!factorized) return false;
    }
    evaluate(model, d);
    if (!applied && it % refresh == 0) {
      start_iteration_matrix(model, d, in.iteration);
      scale_body_blocks(model, in.iteration, c);
      add_modal_stiffness_damping(model, d, in.iteration, Scalar(1), Scalar(0));
      // alpha B^T B gets penalty_factor times the largest diagonal of K + c M over the largest
      // squared column norm of B (flexible joint rows carry node rotations of order 100 per
      // unit modal coordinate).
      const Eigen::MatrixXd b = dense_jacobian(model, d);
      const double jtj = b.size() ? b.colwise().squaredNorm().maxCoeff() : 0.0;
      alpha = static_cast<Scalar>(opt.penalty_factor * double(max_abs(in.iteration.diagonal())) /
                                  (jtj > 0 ? jtj : 1.0));
      add_constraint_gram(model, d, alpha, in.iteration);
      if (!in.cholesky.compute(in.iteration)) return false;
    }
    if (it > 0) lambda.noalias() += alpha * d.phi;
    r = -d.force;
    in.e = lambda + alpha * d.phi;
    add_jacobian_transpose_times(model, d, in.e, r);
    if (applied) {
      dx = (-llt.solve(r.template cast<double>())).template cast<Scalar>();
    } else {
      dx = -r;
      in.cholesky.solve_in_place(dx);
    }
    last = max_abs(dx);
    if (!std::isfinite(static_cast<double>(last))) return false;
    integrate_coordinates(model, d.q, dx);
    if (last <= tolerance && max_abs(d.phi) <= tolerance) {
      d.lambda = lambda;
      return true;
    }
  }
  return false;
}

}  // namespace detail

/// Moves d.q to static equilibrium at d.t (v, v_dot set to zero, multipliers in d.lambda).
/// Fails, naming the worst joint, if the iteration does not converge; d.q is then left as it
/// was. The iteration's matrix first has the modal stiffness alone, which is enough where
/// joints and drivers hold the bodies; where that does not converge (a body that a spring
/// holds: the spring's stiffness, missing from the matrix, overshoots by about k / (c m) per
/// iteration), it starts again with a matrix refactorized at every iteration (a kept matrix
/// holds the stiff alpha B^T B of the joint directions it was made at, and diverged on a
/// pendulum on a spherical joint started 0.2 rad off the vertical, its corrections growing a
/// thousandfold per iteration; with a fresh one each it converged in 72), then with the
/// stiffness of every applied force.
template <class Scalar>
Status solve_static_equilibrium(const Model<Scalar>& model, Data<Scalar>& d,
                                const StaticEquilibriumOptions& opt = {}) {
  const auto q_start = d.q;
  const auto lambda_start = d.lambda;
  d.v.setZero();
  d.v_dot.setZero();
  d.a.setZero();
  Scalar last = Scalar(0);
  for (const int pass : {0, 1, 2}) {
    const bool applied = pass == 2;
    d.q = q_start;
    d.lambda = lambda_start;
    if (detail::equilibrium_iterations(model, d, opt, applied, pass == 0 ? 10 : 1, last)) {
      d.integrator.initialized = false;  // the next step starts from here
      d.integrator.have_factorization = false;
      return Status::success();
    }
    int worst = 0;
    if (applied && d.phi.size() > 0) d.phi.cwiseAbs().maxCoeff(&worst);
    if (applied) {
      // Not converged: back to where it started (a diverged iterate may not even be finite),
      // with the violation reported at the last iterate. The iteration matrix was overwritten
      // and the velocities zeroed: the next step starts afresh.
      d.q = q_start;
      d.lambda = lambda_start;
      d.integrator.initialized = false;
      d.integrator.have_factorization = false;
      evaluate(model, d);
      if (d.phi.size() == 0)
        return make_error(ErrorCode::not_converged, "static equilibrium did not converge in ",
                          opt.max_iterations, " iterations (last correction ",
                          static_cast<double>(last),
                          "); the model has no joints: is every rigid motion held by a spring?");
      return make_error(ErrorCode::not_converged, "static equilibrium did not converge in ",
                        opt.max_iterations, " iterations (last correction ",
                        static_cast<double>(last), ", largest violation in ",
                        model.describe_joint(model.joint_of_row(worst)),
                        "); is every rigid motion held by a joint, driver or spring?");
    }
  }
  return Status::success();  // not reached
}

/// Linearizes about the state of d (velocities treated as zero; d.lambda must hold the
/// equilibrium multipliers, e.g. from solve_static_equilibrium; Linearization::static_residual
/// says how far the state is from that). d's workspace is overwritten.
template <class Scalar>
Result<Linearization> linearize(const Model<Scalar>& model, Data<Scalar>& d, double step = 1e-7) {
  const int nv = model.num_velocities();
  const auto q0 = d.q, v0 = d.v;
  const auto lambda = d.lambda;
  d.v.setZero();
  evaluate(model, d);
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(nv, nv);
  {
    typename Data<Scalar>::MatrixX ms = Data<Scalar>::MatrixX::Zero(nv, nv);
    start_iteration_matrix(model, d, ms);
    m = ms.template cast<double>();
  }
  const Eigen::MatrixXd b = dense_jacobian(model, d);
  typename Data<Scalar>::VectorX res(nv), dx(nv);
  const auto residual = [&](const Eigen::VectorXd& e) {
    d.q = q0;
    dx = e.cast<Scalar>();
    integrate_coordinates(model, d.q, dx);
    evaluate(model, d);
    res = -d.force;
    add_jacobian_transpose_times(model, d, lambda, res);
    return Eigen::VectorXd(res.template cast<double>());
  };
  const double static_residual =
      nv > 0 ? residual(Eigen::VectorXd::Zero(nv)).cwiseAbs().maxCoeff() : 0.0;
  Eigen::MatrixXd k(nv, nv);
  for (int j = 0; j < nv; ++j) {
    Eigen::VectorXd e = Eigen::VectorXd::Zero(nv);
    e(j) = step;
    k.col(j) = (residual(e) - residual(-e)) / (2 * step);
  }
  d.q = q0;
  d.v = v0;
  evaluate(model, d);
  auto lin = linearization_on_null_space(m, k, b);
  if (lin) lin->static_residual = static_residual;
  return lin;
}

}  // namespace flexstress
