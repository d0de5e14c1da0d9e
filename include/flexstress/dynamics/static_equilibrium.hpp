// Static equilibrium of a scene: the coordinates at which the applied forces (gravity, elastic
// forces, springs) balance the joint reactions, with all velocities zero, at the state's time
// (drivers at their prescribed positions). A run that starts here starts without a jolt.
//
// Solved by a pseudo-transient Newton iteration: S dx = -(B^T (lambda* + alpha Phi) - Q) with
// S = K + alpha B^T B + c M (modal stiffness, constraint penalty, and c M with c = (2 pi f)^2 a
// regularization that vanishes at convergence and keeps rigid directions that only gravity
// holds from taking unbounded steps), and lambda* += alpha Phi after each iteration. Needs a
// scene whose joints and drivers hold every rigid motion (a crane driven by its cylinder); a
// free mechanism has no static equilibrium to find.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "flexstress/core/status.hpp"
#include "flexstress/dynamics/scene.hpp"

namespace flexstress {

struct StaticEquilibriumOptions {
  int max_iterations = 200;
  /// On the correction (m, rad, modal units) and the constraint violation; 0: 1e-10, or 100
  /// epsilon if the scene's Scalar cannot resolve that (float: 1.2e-5).
  double tolerance = 0.0;
  double regularization_hz = 1.0;  ///< f in c = (2 pi f)^2
  /// alpha B^T B relative to the largest diagonal of K + c M. The multiplier update removes
  /// the penalty's bias, so a moderate factor converges in a few iterations; 1e6 made the
  /// matrix of a stiff flexible body singular to double precision (condition > 1e15).
  double penalty_factor = 1e3;
};

/// Moves s.q to static equilibrium (v, v_dot set to zero, multipliers in s.lambda). Fails,
/// naming the worst joint, if the iteration does not converge.
template <class SceneT>
Status solve_static_equilibrium(const SceneT& scene, typename SceneT::State& s,
                                const StaticEquilibriumOptions& opt = {}) {
  using Scalar = typename SceneT::scalar_type;
  if (Status data = scene.check_effect_data(); !data) return data;
  typename SceneT::Workspace w;
  typename SceneT::MatVV m;
  typename SceneT::VecV r, dx;
  typename SceneT::VecC lambda;
  m.setZero(SceneT::nv, SceneT::nv);
  r.setZero(SceneT::nv);
  dx.setZero(SceneT::nv);
  lambda = s.lambda;
  s.v.setZero();
  s.v_dot.setZero();
  s.a.setZero();
  const Scalar c =
      static_cast<Scalar>(std::pow(2.0 * 3.14159265358979323846 * opt.regularization_hz, 2));
  const Scalar tolerance = static_cast<Scalar>(
      opt.tolerance > 0.0
          ? opt.tolerance
          : std::max(1e-10, 100.0 * double(std::numeric_limits<Scalar>::epsilon())));
  Eigen::LLT<typename SceneT::MatVV> llt;
  Scalar alpha = Scalar(0), last = Scalar(0);
  for (int it = 0; it < opt.max_iterations; ++it) {
    scene.evaluate(s, w);
    if (it == 0 || it % 10 == 0) {
      m.setZero();
      scene.mass_blocks(w, m);
      m *= c;
      scene.add_modal_stiffness_damping(w, m, Scalar(1), Scalar(0));
      // alpha B^T B gets penalty_factor times the largest diagonal of K + c M: scaling by B's
      // own column norms matters for flexible bodies, whose joint rows carry node rotations
      // Phi_theta of order 100 per unit modal coordinate.
      const Scalar jtj = w.jac.colwise().squaredNorm().maxCoeff();
      alpha = static_cast<Scalar>(opt.penalty_factor) * max_abs(m.diagonal()) /
              (jtj > Scalar(0) ? jtj : Scalar(1));
      scene.add_constraint_gram(w, alpha, m);
      llt.compute(m);
      if (llt.info() != Eigen::Success)
        return make_error(ErrorCode::singular_matrix,
                          "static equilibrium: the iteration matrix is not positive definite");
    }
    if (it > 0) lambda.noalias() += alpha * w.phi;
    r.noalias() = w.jac.transpose() * (lambda + alpha * w.phi) - w.force;
    dx = -llt.solve(r);
    last = max_abs(dx);
    if (!std::isfinite(static_cast<double>(last))) break;  // never integrate NaN
    scene.integrate(s, dx);
    if (last <= tolerance && max_abs(w.phi) <= tolerance) {
      s.lambda = lambda;
      return Status::success();
    }
  }
  if (w.phi.size() == 0)
    return make_error(ErrorCode::not_converged, "static equilibrium did not converge in ",
                      opt.max_iterations, " iterations (last correction ",
                      static_cast<double>(last),
                      "); the scene has no joints, so nothing holds its rigid motions");
  int worst = 0;
  w.phi.cwiseAbs().maxCoeff(&worst);
  return make_error(ErrorCode::not_converged, "static equilibrium did not converge in ",
                    opt.max_iterations, " iterations (last correction ", static_cast<double>(last),
                    ", largest violation in joint ", SceneT::joint_of_row(worst), " (",
                    SceneT::joint_kind_name(SceneT::joint_of_row(worst)),
                    ")); is every rigid motion held by a joint or driver?");
}

}  // namespace flexstress
