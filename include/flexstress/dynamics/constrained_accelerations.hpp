// Accelerations and multipliers of a constrained scene at a given state (index-1 form), by the
// augmented Lagrangian iteration of Bayo, Garcia de Jalon and Serna (Comput. Methods Appl. Mech.
// Eng. 71 (1988)):
//   (M + alpha B^T B) v_dot = Q - B^T lambda - alpha B^T c,   lambda += alpha (B v_dot + c),
// with c = conv + 2 zeta w_b (B v + Phi_t) + w_b^2 Phi (Baumgarte stabilization; w_b = 0 gives the
// pure acceleration constraint). Works with redundant constraints: M + alpha B^T B stays
// positive definite. Used by the explicit integrator and for consistent initial accelerations.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "flexstress/dynamics/scene.hpp"

namespace flexstress {

template <class SceneT>
class ConstrainedAccelerations {
 public:
  using Scalar = typename SceneT::scalar_type;
  using State = typename SceneT::State;
  using Workspace = typename SceneT::Workspace;
  using VecV = typename SceneT::VecV;
  using VecC = typename SceneT::VecC;
  using MatVV = typename SceneT::MatVV;

  struct Settings {
    Scalar penalty_factor = std::is_same_v<Scalar, float> ? Scalar(1e3) : Scalar(1e6);
    Scalar baumgarte_frequency = Scalar(0);  ///< w_b [rad/s]
    Scalar baumgarte_damping = Scalar(1);    ///< zeta
    int iterations = 20;
    Scalar tolerance = Scalar(100) * std::numeric_limits<Scalar>::epsilon();
  };

  ConstrainedAccelerations() {
    matrix_.setZero(SceneT::nv, SceneT::nv);
    // Sized (dynamic storage: the one allocation) and with a defined status before any copy.
    llt_.compute(MatVV::Identity(SceneT::nv, SceneT::nv));
    rhs_.setZero(SceneT::nv);
    c_.setZero(SceneT::nc);
    e_.setZero(SceneT::nc);
  }

  /// Evaluates the scene at s (into w) and solves for v_dot and lambda (in s). Returns the
  /// final acceleration-constraint residual (infinity norm).
  Scalar solve(const SceneT& scene, State& s, Workspace& w, const Settings& set) {
    scene.clear_inactive_multipliers(s.lambda);  // switched-off joints carry no reaction
    scene.evaluate(s, w);
    matrix_.setZero();
    scene.mass_blocks(w, matrix_);
    const Scalar alpha = set.penalty_factor * max_abs(matrix_.diagonal());
    scene.add_constraint_gram(w, alpha, matrix_);
    llt_.compute(matrix_);
    c_ = w.conv;
    if (set.baumgarte_frequency > Scalar(0)) {
      e_.noalias() = w.jac * s.v;  // product alone: no temporary
      e_ += w.phi_t;
      c_ += Scalar(2) * set.baumgarte_damping * set.baumgarte_frequency * e_ +
            set.baumgarte_frequency * set.baumgarte_frequency * w.phi;
    }
    Scalar residual = Scalar(0);
    for (int it = 0; it < set.iterations; ++it) {
      e_ = s.lambda + alpha * c_;
      rhs_ = w.force;
      rhs_.noalias() -= w.jac.transpose() * e_;
      s.v_dot = llt_.solve(rhs_);
      e_.noalias() = w.jac * s.v_dot;  // product alone: no temporary
      e_ += c_;
      s.lambda += alpha * e_;
      residual = max_abs(e_);
      if (residual <= set.tolerance * (Scalar(1) + max_abs(c_))) break;
    }
    return residual;
  }

 private:
  MatVV matrix_;
  Eigen::LLT<MatVV> llt_;
  VecV rhs_;
  VecC c_, e_;
};

}  // namespace flexstress
