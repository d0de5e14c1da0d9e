// Static equilibrium and linearization of a runtime model (setup-time algorithms: they may
// allocate).
//
// Static equilibrium: the coordinates at which the applied forces balance the joint reactions,
// with all velocities zero, at d.t (drivers at their prescribed positions): a run that starts
// there starts without a jolt. Solved by a pseudo-transient Newton iteration,
// S dx = -(B^T (lambda* + alpha Phi) - Q), S = K + alpha B^T B + c M (modal stiffness,
// constraint penalty, and c M with c = (2 pi f)^2 a regularization that vanishes at convergence
// and keeps rigid directions that only gravity holds from taking unbounded steps), and
// lambda* += alpha Phi after each iteration. Needs a model whose joints and drivers hold every
// rigid motion (a crane driven by its cylinder); a free mechanism has no static equilibrium.
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

/// Moves d.q to static equilibrium at d.t (v, v_dot set to zero, multipliers in d.lambda).
/// Fails, naming the worst joint, if the iteration does not converge.
template <class Scalar>
Status solve_static_equilibrium(const Model<Scalar>& model, Data<Scalar>& d,
                                const StaticEquilibriumOptions& opt = {}) {
  auto& in = d.integrator;
  const int nv = model.num_velocities();
  d.v.setZero();
  d.v_dot.setZero();
  d.a.setZero();
  const Scalar c =
      static_cast<Scalar>(std::pow(2.0 * 3.14159265358979323846 * opt.regularization_hz, 2));
  const Scalar tolerance = static_cast<Scalar>(
      opt.tolerance > 0.0
          ? opt.tolerance
          : std::max(1e-10, 100.0 * double(std::numeric_limits<Scalar>::epsilon())));
  typename Data<Scalar>::VectorX lambda = d.lambda, r(nv), dx(nv);
  Scalar alpha = Scalar(0), last = Scalar(0);
  for (int it = 0; it < opt.max_iterations; ++it) {
    evaluate(model, d);
    if (it == 0 || it % 10 == 0) {
      in.iteration.setZero();
      set_mass_blocks(model, d, in.iteration);
      in.iteration *= c;
      add_modal_stiffness_damping(model, d, in.iteration, Scalar(1), Scalar(0));
      // alpha B^T B gets penalty_factor times the largest diagonal of K + c M over the largest
      // squared column norm of B (flexible joint rows carry node rotations of order 100 per
      // unit modal coordinate).
      const Eigen::MatrixXd b = dense_jacobian(model, d);
      const double jtj = b.size() ? b.colwise().squaredNorm().maxCoeff() : 0.0;
      alpha = static_cast<Scalar>(opt.penalty_factor * double(max_abs(in.iteration.diagonal())) /
                                  (jtj > 0 ? jtj : 1.0));
      add_constraint_gram(model, d, alpha, in.iteration);
      if (!in.cholesky.compute(in.iteration))
        return make_error(ErrorCode::singular_matrix,
                          "static equilibrium: the iteration matrix is not positive definite");
    }
    if (it > 0) lambda.noalias() += alpha * d.phi;
    r = -d.force;
    in.e = lambda + alpha * d.phi;
    add_jacobian_transpose_times(model, d, in.e, r);
    dx = -r;
    in.cholesky.solve_in_place(dx);
    last = max_abs(dx);
    if (!std::isfinite(static_cast<double>(last))) break;
    integrate_coordinates(model, d.q, dx);
    if (last <= tolerance && max_abs(d.phi) <= tolerance) {
      d.lambda = lambda;
      in.initialized = false;  // the next step starts from here
      in.have_factorization = false;
      return Status::success();
    }
  }
  if (d.phi.size() == 0)
    return make_error(ErrorCode::not_converged, "static equilibrium did not converge in ",
                      opt.max_iterations, " iterations (last correction ",
                      static_cast<double>(last),
                      "); the model has no joints, so nothing holds its rigid motions");
  int worst = 0;
  d.phi.cwiseAbs().maxCoeff(&worst);
  return make_error(ErrorCode::not_converged, "static equilibrium did not converge in ",
                    opt.max_iterations, " iterations (last correction ", static_cast<double>(last),
                    ", largest violation in ", model.describe_joint(model.joint_of_row(worst)),
                    "); is every rigid motion held by a joint or driver?");
}

/// Linearizes about the state of d (velocities treated as zero; d.lambda must hold the
/// equilibrium multipliers, e.g. from solve_static_equilibrium). d's workspace is overwritten.
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
    set_mass_blocks(model, d, ms);
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
  Eigen::MatrixXd k(nv, nv);
  for (int j = 0; j < nv; ++j) {
    Eigen::VectorXd e = Eigen::VectorXd::Zero(nv);
    e(j) = step;
    k.col(j) = (residual(e) - residual(-e)) / (2 * step);
  }
  d.q = q0;
  d.v = v0;
  evaluate(model, d);
  return linearization_on_null_space(m, k, b);
}

}  // namespace flexstress
