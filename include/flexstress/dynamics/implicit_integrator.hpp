// Implicit integrator: Lie-group generalized-alpha with an index-3 augmented Lagrangian and
// velocity projection.
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
// Modified Newton: S is factorized once and reused across iterations and steps until the
// observed contraction rate says it is stale; it is factorized within its envelope in a body
// order that skips the zero blocks between bodies no joint joins (core/envelope_cholesky.hpp).
// A reused S is turned with the bodies (Settings::corotate_factorization): with global R_dot
// and body-frame w and p_dot, a body's own blocks of M and B^T B are T S_0 T^T with
// T = diag(A, 1, 1), so rotating the R_dot parts of the residual and correction by the rotation
// since the factorization makes them exact again for any rigid rotation.
// After convergence the velocities are projected onto B v + Phi_t = 0 with the same factorization,
// a projection orthogonal in the metric S (dominated by M b'), which removes velocity drift.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <utility>

#include <Eigen/Core>

#include "flexstress/core/envelope_cholesky.hpp"
#include "flexstress/core/scalar_traits.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/dynamics/scene.hpp"
#include "flexstress/dynamics/step_settings.hpp"

namespace flexstress {

/// Generalized-alpha parameters from the spectral radius at infinite frequency.
template <class Scalar>
struct GeneralizedAlpha {
  Scalar alpha_m, alpha_f, gamma, beta;
  static GeneralizedAlpha from_spectral_radius(Scalar rho) {
    GeneralizedAlpha p;
    p.alpha_m = (Scalar(2) * rho - Scalar(1)) / (rho + Scalar(1));
    p.alpha_f = rho / (rho + Scalar(1));
    p.gamma = Scalar(0.5) - p.alpha_m + p.alpha_f;
    p.beta = Scalar(0.25) * (p.gamma + Scalar(0.5)) * (p.gamma + Scalar(0.5));
    return p;
  }
};

template <class SceneT>
class ImplicitIntegrator {
 public:
  using Scalar = typename SceneT::scalar_type;
  using State = typename SceneT::State;
  using Workspace = typename SceneT::Workspace;
  using VecV = typename SceneT::VecV;
  using VecC = typename SceneT::VecC;
  using MatVV = typename SceneT::MatVV;
  static constexpr int nv = SceneT::nv, nc = SceneT::nc;

  using Settings = ImplicitSettings<Scalar>;
  using Statistics = StepStatistics;

  explicit ImplicitIntegrator(const SceneT& scene, const Settings& settings = Settings())
      : scene_(&scene), settings_(settings) {
    iteration_.setZero(nv, nv);
    // The factor's storage and the body order that keeps its fill small (setup; dynamic
    // storage: the one allocation). Entries outside the scene's pattern are zero by construction.
    chol_.analyze(SceneT::block_pattern());
    for (VecV* v : {&r_, &dx_, &v_n_, &vd_n_, &a_n_, &a1_, &tmp_, &vd_prev_, &v_save_, &vd_save_})
      v->setZero(nv);
    e_.setZero(nc);
    lambda_star_.setZero(nc);
    lambda_prev_.setZero(nc);
    lambda_save_.setZero(nc);
    for (Mat3<Scalar>& a : factorized_rotations_) a.setIdentity();
    correction_scale_.setOnes(nv);
    update_correction_scale();
    set_step(settings.step);
  }

  const Settings& settings() const { return settings_; }
  const Statistics& statistics() const { return stats_; }
  Workspace& workspace() { return ws_; }
  const Workspace& workspace() const { return ws_; }

  /// Changes the step size (the next step refactorizes).
  void set_step(Scalar h) {
    settings_.step = h;
    gen_ = GeneralizedAlpha<Scalar>::from_spectral_radius(settings_.spectral_radius);
    beta_prime_ = (Scalar(1) - gen_.alpha_m) / (h * h * gen_.beta * (Scalar(1) - gen_.alpha_f));
    gamma_prime_ = gen_.gamma / (h * gen_.beta);
    tol_x_ = std::max(settings_.acceleration_tolerance / beta_prime_, settings_.position_floor);
    have_factorization_ = false;
  }

  /// Consistent initial conditions at s.t: positions onto Phi = 0 (least mass-weighted change),
  /// velocities onto B v + Phi_t = 0, then accelerations and multipliers from the equations of
  /// motion (index-1 augmented Lagrangian iteration). Sets a = v_dot.
  Status initialize(State& s, int max_iterations = 100) {
    if (Status data = scene_->check_effect_data(); !data) return data;
    update_correction_scale();  // the bodies may have been replaced since construction
    if (const int body = scene_->nonfinite_body(s); body >= 0)
      return make_error(ErrorCode::invalid_argument, "initial conditions: body ", body,
                        " has a coordinate or velocity that is not finite");
    const Scalar tol = settings_.position_floor * Scalar(10);
    scene_->update_kinematics(s, ws_);
    scene_->update_constraints(s, ws_);
    Scalar violation = max_abs(ws_.phi);
    // Damped Newton projection: (M + alpha B^T B) dx = -alpha B^T Phi, refactorized at every
    // iterate (setup only), with step halving when the violation grows. Large initial modal
    // coordinates make the joints strongly nonlinear in p (node rotations I + skew(Phi_theta p)),
    // and a full step from a stale matrix can throw the iteration off.
    for (int it = 0;; ++it) {
      if (violation <= tol) break;  // NaN falls through to the error
      if (it >= max_iterations || !std::isfinite(static_cast<double>(violation)))
        return make_error(
            ErrorCode::not_converged,
            "initial conditions: the joints cannot be assembled at t = ", static_cast<double>(s.t),
            " (largest violation ", static_cast<double>(violation), " in joint ",
            SceneT::joint_of_row(worst_row(ws_.phi)), ")");
      factorize_projection(s);
      dx_.noalias() = -alpha_ * ws_.jac.transpose() * ws_.phi;
      chol_.solve_in_place(dx_);
      if (!dx_.allFinite()) {  // reported as not converged at the top of the loop
        violation = std::numeric_limits<Scalar>::quiet_NaN();
        continue;
      }
      q_save_ = s.q;
      for (int halving = 0;; ++halving) {
        scene_->integrate(s, dx_);
        scene_->update_kinematics(s, ws_);
        scene_->update_constraints(s, ws_);
        const Scalar trial = max_abs(ws_.phi);
        if (trial < violation || halving == 30) {
          violation = trial;
          break;
        }
        s.q = q_save_;
        dx_ *= Scalar(0.5);
      }
    }
    factorize_projection(s);  // the metric at the assembled configuration
    project_velocities(s, max_iterations);
    if constexpr (SceneT::has_force_states) {  // chamber pressures as set, at this position
      scene_->update_kinematics(s, ws_);
      scene_->start_force_states(s, ws_);
    }
    // Accelerations: (M + alpha B^T B) v_dot = Q - B^T lambda - alpha B^T conv, iterated.
    scene_->evaluate(s, ws_);
    iteration_.setZero();
    scene_->mass_blocks(ws_, iteration_);
    scene_->add_constraint_gram(ws_, alpha_, iteration_);
    chol_.compute(iteration_);
    record_rotations();
    have_factorization_ = false;
    s.lambda.setZero();
    for (int it = 0; it < max_iterations; ++it) {
      e_ = s.lambda + alpha_ * ws_.conv;
      r_ = ws_.force;
      r_.noalias() -= ws_.jac.transpose() * e_;  // no temporary: initialize() also runs mid-run
      s.v_dot = r_;
      chol_.solve_in_place(s.v_dot);
      e_.noalias() = ws_.jac * s.v_dot;  // product alone: no temporary
      e_ += ws_.conv;
      s.lambda += alpha_ * e_;
      if (max_abs(e_) <= tol * (Scalar(1) + max_abs(ws_.conv))) break;
    }
    s.a = s.v_dot;
    has_previous_ = false;
    converged_multipliers_ = 1;  // the multipliers just solved for
    revision_ = scene_->revision();
    return Status::success();
  }

  /// One step of size h. Never allocates or throws. On failure the state is left as it was
  /// before the step (except for constraint_violation, which keeps the step).
  StepStatus step(State& s) {
    // The model changed at runtime (a joint switched or anchored): restart from the state as
    // it is, as initialize() does. The accelerations jump with the forces at this instant, and a
    // step started from the old ones would smear the jump over the step (generalized-alpha
    // evaluates at t + (1 - af) h), an O(h) error in velocity; a joint switched on is assembled
    // and the velocities projected (a plastic capture).
    if (scene_->revision() != revision_ && !initialize(s).ok())
      return StepStatus::constraint_violation;
    const Scalar h = settings_.step;
    const auto q_n = s.q;
    v_n_ = s.v;
    vd_n_ = s.v_dot;
    a_n_ = s.a;
    const Scalar t_n = s.t;
    lambda_star_ = s.lambda;
    // Predictor: v_dot_{n+1} and lambda_{n+1} extrapolated linearly from the last two steps
    // (constant on the first). A better predictor means a smaller constraint violation Phi_pred
    // to correct, hence smaller transient penalty forces and fewer iterations with a reused
    // matrix.
    if (has_previous_ && settings_.extrapolate_predictor) s.v_dot = Scalar(2) * vd_n_ - vd_prev_;
    if (converged_multipliers_ >= 2 && settings_.extrapolate_multipliers)
      lambda_star_ = Scalar(2) * s.lambda - lambda_prev_;
    a1_ = ((Scalar(1) - gen_.alpha_f) * s.v_dot + gen_.alpha_f * vd_n_ - gen_.alpha_m * a_n_) /
          (Scalar(1) - gen_.alpha_m);
    s.v = v_n_ + h * ((Scalar(1) - gen_.gamma) * a_n_ + gen_.gamma * a1_);
    tmp_ = h * (v_n_ + h * ((Scalar(0.5) - gen_.beta) * a_n_ + gen_.beta * a1_));
    scene_->integrate(s, tmp_);
    s.t = t_n + h;
    int it = 0;
    bool stale_for_next = false;  // refactorize at the next step (Settings::refactor_rate)
    bool converged = false, fresh = false, stale_step = false, restored = false;
    Scalar previous = std::numeric_limits<Scalar>::infinity();
    Scalar residual_prev = std::numeric_limits<Scalar>::infinity();
    stats_.last_factorizations = 0;
    for (; it < settings_.max_iterations; ++it) {
      // "fresh": the matrix was factorized at this iterate. An older one (from an earlier
      // iteration of this step too) lacks the derivatives of the mass matrix, the quadratic
      // velocity terms and the penalty forces at the current iterate; with kHz modes excited
      // those are large, and an unchecked stale matrix diverges within a few iterations.
      fresh = false;
      scene_->evaluate(s, ws_, /*rates=*/false);  // the residual needs Phi and B only
      if (!have_factorization_ || !settings_.reuse_factorization) {
        factorize(s);
        fresh = true;
      }
      if (it > 0 && !restored) lambda_star_.noalias() += alpha_ * ws_.phi;
      restored = false;
      // Residual M v_dot - Q + B^T (lambda* + alpha Phi).
      e_ = lambda_star_ + alpha_ * ws_.phi;
      r_.noalias() = -ws_.force;
      // Coefficient-based for fixed-size scenes, where calling the general matrix-vector
      // kernel costs more than the product; the kernel for large dynamic ones (the 40-bar
      // chain: 12 % slower steps without it).
      if constexpr (SceneT::fixed_storage)
        r_.noalias() += ws_.jac.transpose().lazyProduct(e_);
      else
        r_.noalias() += ws_.jac.transpose() * e_;
      scene_->add_mass_times(ws_, s.v_dot, r_);
      const Scalar residual = r_.norm();
      // A correction made with a reused matrix that increased the residual is undone and
      // redone with a fresh matrix: a stale constraint Jacobian leaks the (large, transient)
      // penalty forces into the free directions of the mechanism. A correction within ten
      // tolerances is kept (the fresh matrix is built at its iterate instead): it cannot be the
      // start of a divergence, and so close to convergence the residual's norm moves with
      // round-off and the multiplier update (the crane at 1e-3: the redone correction came out
      // the same as the undone one in all 511 such steps).
      if (stale_step && !(residual < residual_prev) && previous <= Scalar(10) * tol_x_) {
        factorize(s);
        fresh = true;
        stale_step = false;
      } else if (stale_step && !(residual < residual_prev)) {
        s.q = q_save_;
        s.v = v_save_;
        s.v_dot = vd_save_;
        lambda_star_ = lambda_save_;
        have_factorization_ = false;
        stale_step = false;
        restored = true;
        continue;
      }
      dx_ = -r_;
      solve_turned(dx_, fresh);
      const Scalar size = correction_size();
      if (!std::isfinite(size)) break;
      // A stale matrix that contracts too slowly: refactorize and redo this iteration, or,
      // at the second correction, refactorize at the next step (Settings::refactor_rate).
      const bool stale = !fresh && it > 0 && size > settings_.refactor_rate * previous;
      if (stale && it == 1 && !settings_.accept_at_iteration_limit) {
        stale_for_next = true;
      } else if (stale) {
        factorize(s);
        fresh = true;
        dx_ = -r_;
        solve_turned(dx_, fresh);
      }
      previous = correction_size();
      stale_step = !fresh;
      if (stale_step) {
        q_save_ = s.q;
        v_save_ = s.v;
        vd_save_ = s.v_dot;
        lambda_save_ = lambda_star_;
      }
      residual_prev = residual;
      scene_->integrate(s, dx_);
      s.v_dot.noalias() += beta_prime_ * dx_;
      s.v.noalias() += gamma_prime_ * dx_;
      if (previous <= tol_x_ && max_abs(ws_.phi) <= tol_x_) {
        converged = true;
        ++it;
        break;
      }
    }
    stats_.last_iterations = it;
    stats_.iterations += it;
    const bool finite = s.v.allFinite() && s.v_dot.allFinite() && scene_->coordinates_finite(s);
    bool kept_at_limit = false;
    if (!converged && finite && settings_.accept_at_iteration_limit &&
        it >= settings_.max_iterations) {
      converged = true;
      kept_at_limit = true;
      ++stats_.over_budget;
    }
    if (!converged || !finite) {
      s.q = q_n;
      s.v = v_n_;
      s.v_dot = vd_n_;
      s.a = a_n_;
      s.t = t_n;
      have_factorization_ = false;
      return finite ? StepStatus::newton_not_converged : StepStatus::non_finite_state;
    }
    if (stale_for_next) have_factorization_ = false;
    lambda_prev_ = s.lambda;
    s.lambda = lambda_star_;
    // Multipliers kept at the iteration limit are not converged, and a line through them
    // extrapolates their error too: the next two steps hold them (the pendulum of
    // tests/dynamics/test_pendulum.cpp under a budget of 3 iterations, measured with the
    // factorization not turned: 281 instead of 295 of 1000 steps at the limit).
    converged_multipliers_ = kept_at_limit ? 0 : std::min(converged_multipliers_ + 1, 2);
    vd_prev_ = vd_n_;
    has_previous_ = true;
    ++stats_.steps;
    // Drift control: project velocities onto B v + Phi_t = 0 and accelerations onto
    // B v_dot + conv = 0 (ALI3-P). Without the acceleration projection the trapezoidal rule
    // (rho = 1) leaves the accelerations of an index-3 system weakly unstable: they oscillate
    // from step to step without damping.
    if (settings_.refresh_workspace || settings_.project_velocities || SceneT::has_force_states) {
      scene_->update_kinematics(s, ws_);
      scene_->update_constraints(s, ws_);
    }
    if constexpr (SceneT::has_force_states) scene_->commit_force_states(s, ws_);
    if (settings_.project_velocities) {
      project_velocities(s, settings_.projection_iterations);
      if (settings_.project_accelerations) {
        scene_->update_kinematics(s, ws_);
        scene_->update_constraints(s, ws_);
        project_accelerations(s, settings_.projection_iterations);
      }
    }
    s.a = ((Scalar(1) - gen_.alpha_f) * s.v_dot + gen_.alpha_f * vd_n_ - gen_.alpha_m * a_n_) /
          (Scalar(1) - gen_.alpha_m);
    if (max_abs(ws_.phi) > settings_.violation_limit) return StepStatus::constraint_violation;
    if (settings_.project_velocities) {
      e_.noalias() = ws_.jac * s.v;  // product alone: no temporary
      e_ += ws_.phi_t;
      if (max_abs(e_) > settings_.violation_limit * (Scalar(1) + max_abs(s.v)))
        return StepStatus::constraint_violation;
    }
    return StepStatus::ok;
  }

  /// Penalty alpha in use (after the first factorization).
  Scalar penalty() const { return alpha_; }

  /// What the next step depends on besides the State: the previous v_dot and lambda (the
  /// predictor) and the factorized iteration matrix with its penalty (the modified Newton
  /// reuses it across steps). Saved and restored by checkpoints (dynamics/checkpoint.hpp), so a
  /// restored run continues bit-identically.
  struct History {
    VecV vd_prev;
    VecC lambda_prev;
    int converged_multipliers = 0;  ///< trailing steps with converged multipliers (0 to 2)
    bool has_previous = false;
    bool have_factorization = false;
    Scalar alpha = Scalar(0);
    MatVV iteration;  ///< the matrix last factorized (meaningful with have_factorization)
    /// The bodies' rotations when it was factorized (Settings::corotate_factorization).
    std::array<Mat3<Scalar>, SceneT::num_bodies> rotations;
    Statistics statistics;
  };
  void save_history(History& h) const {
    h.vd_prev = vd_prev_;
    h.lambda_prev = lambda_prev_;
    h.converged_multipliers = converged_multipliers_;
    h.has_previous = has_previous_;
    h.have_factorization = have_factorization_;
    h.alpha = alpha_;
    if (have_factorization_) {
      h.iteration = iteration_;
      h.rotations = factorized_rotations_;
    }
    h.statistics = stats_;
  }
  /// Restores a saved history (setup: refactorizes the saved matrix, which gives the same
  /// factor bit for bit). The sizes must be the scene's (checkpoint.hpp checks them).
  void restore_history(const History& h) {
    vd_prev_ = h.vd_prev;
    lambda_prev_ = h.lambda_prev;
    converged_multipliers_ = h.converged_multipliers;
    has_previous_ = h.has_previous;
    alpha_ = h.alpha;
    stats_ = h.statistics;
    revision_ = scene_->revision();  // the history belongs to the scene as it is now
    have_factorization_ = h.have_factorization;
    if (have_factorization_) {
      iteration_ = h.iteration;
      chol_.compute(iteration_);
      factorized_rotations_ = h.rotations;
    }
  }

 private:
  /// S = M b' + D g' + K + alpha B^T B at the current evaluation (ws_ is up to date).
  void factorize(const State&) {
    iteration_.setZero();
    scene_->mass_blocks(ws_, iteration_);
    const Scalar m_ref = max_abs(iteration_.diagonal());
    iteration_ *= beta_prime_;
    scene_->add_modal_stiffness_damping(ws_, iteration_, Scalar(1), gamma_prime_);
    alpha_ = settings_.penalty_factor * beta_prime_ * m_ref;
    scene_->add_constraint_gram(ws_, alpha_, iteration_);
    chol_.compute(iteration_);
    record_rotations();
    have_factorization_ = true;
    ++stats_.factorizations;
    ++stats_.last_factorizations;
  }

  /// Each coordinate's scale in the convergence test: 1 for R and w, the mode's largest nodal
  /// translation for a modal coordinate (Settings::acceleration_tolerance).
  void update_correction_scale() {
    detail::for_each_index(
        [&](auto k) {
          constexpr int K = static_cast<int>(decltype(k)::value);
          constexpr int modes = SceneT::body_nv[K] - 6;
          if constexpr (modes > 0)
            correction_scale_.template segment<modes>(SceneT::body_offset[K] + 6) =
                scene_->template body<K>().modal_displacement_scale();
        },
        std::make_index_sequence<SceneT::num_bodies>{});
  }

  /// The largest scaled component of the correction dx_.
  Scalar correction_size() const {
    return max_abs(dx_.cwiseProduct(correction_scale_));  // NaN stays NaN
  }

  /// x <- S^-1 x with the factorized S, turned with the bodies (Settings::corotate_factorization)
  /// unless S was factorized at the current kinematics (`fresh`): x <- Q S^-1 Q^T x, where Q
  /// rotates each body's R_dot components by A_now A_factorized^T.
  template <class V>
  void solve_turned(V& x, bool fresh) {
    const bool turn = settings_.corotate_factorization && !fresh;
    std::array<Mat3<Scalar>, SceneT::num_bodies> turned;
    if (turn)
      detail::for_each_index(
          [&](auto k) {
            constexpr int K = static_cast<int>(decltype(k)::value);
            turned[K].noalias() =
                std::get<K>(ws_.kin).rotation * factorized_rotations_[K].transpose();
            auto translation = x.template segment<3>(SceneT::body_offset[K]);
            const Vec3<Scalar> local = turned[K].transpose() * translation;
            translation = local;
          },
          std::make_index_sequence<SceneT::num_bodies>{});
    chol_.solve_in_place(x);
    if (turn)
      detail::for_each_index(
          [&](auto k) {
            constexpr int K = static_cast<int>(decltype(k)::value);
            auto translation = x.template segment<3>(SceneT::body_offset[K]);
            const Vec3<Scalar> global = turned[K] * translation;
            translation = global;
          },
          std::make_index_sequence<SceneT::num_bodies>{});
  }

  /// Records each body's rotation with a new factorization (ws_ holds its kinematics).
  void record_rotations() {
    detail::for_each_index(
        [&](auto k) {
          constexpr int K = static_cast<int>(decltype(k)::value);
          factorized_rotations_[K] = std::get<K>(ws_.kin).rotation;
        },
        std::make_index_sequence<SceneT::num_bodies>{});
  }

  /// Metric for position/velocity projections outside a step: M + alpha B^T B.
  void factorize_projection(const State& s) {
    scene_->evaluate(s, ws_);
    iteration_.setZero();
    scene_->mass_blocks(ws_, iteration_);
    const Scalar m_ref = max_abs(iteration_.diagonal());
    alpha_ = settings_.penalty_factor * m_ref;
    scene_->add_constraint_gram(ws_, alpha_, iteration_);
    chol_.compute(iteration_);
    record_rotations();
    have_factorization_ = false;  // the step needs its own matrix
  }

  /// v <- v - S^-1 alpha B^T (B v + Phi_t), repeated (ws_ holds B and Phi_t at s).
  void project_velocities(State& s, int iterations) {
    for (int k = 0; k < iterations; ++k) {
      e_.noalias() = ws_.jac * s.v;  // product alone: no temporary
      e_ += ws_.phi_t;
      if (max_abs(e_) <= settings_.position_floor * (Scalar(1) + max_abs(s.v))) break;
      tmp_.noalias() = alpha_ * ws_.jac.transpose() * e_;
      solve_turned(tmp_, false);
      s.v -= tmp_;
    }
  }

  /// v_dot <- v_dot - S^-1 alpha B^T (B v_dot + conv), repeated (ws_ up to date at s).
  void project_accelerations(State& s, int iterations) {
    for (int k = 0; k < iterations; ++k) {
      e_.noalias() = ws_.jac * s.v_dot;  // product alone: no temporary
      e_ += ws_.conv;
      if (max_abs(e_) <= settings_.position_floor * (Scalar(1) + max_abs(s.v_dot))) break;
      tmp_.noalias() = alpha_ * ws_.jac.transpose() * e_;
      solve_turned(tmp_, false);
      s.v_dot -= tmp_;
    }
  }

  template <class V>
  static int worst_row(const V& phi) {
    int r = 0;
    if (phi.size() > 0) phi.cwiseAbs().maxCoeff(&r);
    return r;
  }

  const SceneT* scene_;
  Settings settings_;
  Statistics stats_;
  GeneralizedAlpha<Scalar> gen_{};
  Scalar beta_prime_ = Scalar(0), gamma_prime_ = Scalar(0), alpha_ = Scalar(0), tol_x_ = Scalar(0);
  bool have_factorization_ = false;
  Workspace ws_;
  MatVV iteration_;
  EnvelopeCholesky<Scalar, SceneT::NV> chol_;  ///< of iteration_
  /// Each body's rotation A at the iterate iteration_ was built from.
  std::array<Mat3<Scalar>, SceneT::num_bodies> factorized_rotations_;
  VecV correction_scale_;  ///< per coordinate (update_correction_scale)
  VecV r_, dx_, v_n_, vd_n_, a_n_, a1_, tmp_, vd_prev_, v_save_, vd_save_;
  VecC lambda_save_;
  decltype(State::q) q_save_;
  bool has_previous_ = false;
  int converged_multipliers_ = 0;  ///< trailing steps whose multipliers converged (0 to 2)
  std::uint64_t revision_ = 0;     ///< the scene's revision() the history was built for
  VecC e_, lambda_star_, lambda_prev_;
};

}  // namespace flexstress
