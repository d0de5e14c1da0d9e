// Explicit integrator for cheap, non-stiff scenes: classical fourth-order Runge-Kutta on
// (R, theta, p, v) with the quaternion rate theta_dot = 1/2 G_bar^T w, accelerations from the
// index-1 augmented Lagrangian (constrained_accelerations.hpp, Baumgarte-stabilized), and a
// projection of positions and velocities back onto the constraints after every step.
//
// RK4 is stable for h w <= 2.78 (its stability interval on the imaginary axis, 2 sqrt 2); a
// step whose h times the highest modal frequency exceeds that is refused with
// StepStatus::step_above_stability_limit instead of blowing up silently.
#pragma once

#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "flexstress/core/euler_parameters.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/dynamics/constrained_accelerations.hpp"
#include "flexstress/dynamics/scene.hpp"

namespace flexstress {

template <class SceneT>
class ExplicitIntegrator {
 public:
  using Scalar = typename SceneT::scalar_type;
  using State = typename SceneT::State;
  using Workspace = typename SceneT::Workspace;
  using VecV = typename SceneT::VecV;
  using MatVV = typename SceneT::MatVV;
  static constexpr int nv = SceneT::nv;
  static_assert(!SceneT::has_force_states,
                "force elements with internal states (HydraulicDrive) are solved inside the "
                "implicit step: use ImplicitIntegrator");

  struct Settings {
    Scalar step = Scalar(1e-3);
    typename ConstrainedAccelerations<SceneT>::Settings accelerations{};
    /// Projection of positions and velocities onto the constraints after each step.
    bool project = true;
    int projection_iterations = 3;
    Scalar penalty_factor = std::is_same_v<Scalar, float> ? Scalar(1e3) : Scalar(1e6);
    /// RK4's stability bound on h times the highest frequency.
    Scalar stability_limit = Scalar(2.78);
  };

  explicit ExplicitIntegrator(const SceneT& scene, const Settings& settings = Settings())
      : scene_(&scene), settings_(settings), model_status_(scene.check_effect_data()) {
    if (settings_.accelerations.baumgarte_frequency == Scalar(0))
      settings_.accelerations.baumgarte_frequency = Scalar(0.1) / settings_.step;
    for (VecV* v : {&k1_, &k2_, &k3_, &k4_, &v0_, &v1_, &v2_, &v3_, &v4_, &dx_, &tmp_})
      v->setZero(nv);
    matrix_.setZero(nv, nv);
    // Sized (dynamic storage: the one allocation) and with a defined status before any copy.
    llt_.compute(MatVV::Identity(nv, nv));
    e_.setZero(SceneT::nc);
  }

  const Settings& settings() const { return settings_; }
  Workspace& workspace() { return ws_; }
  /// Whether the scene has the data its effects need; if not, step() returns invalid_input
  /// and this says what is missing.
  const Status& model_status() const { return model_status_; }

  /// Largest h * omega over the scene's modes for the current step size.
  Scalar stability_number() const { return settings_.step * scene_->max_modal_frequency(); }

  StepStatus step(State& s) {
    if (!model_status_.ok()) return StepStatus::invalid_input;
    if (stability_number() > settings_.stability_limit)
      return StepStatus::step_above_stability_limit;
    const Scalar h = settings_.step;
    const auto q0 = s.q;
    v0_ = s.v;
    const Scalar t0 = s.t;
    // Stage 1.
    accel_.solve(*scene_, s, ws_, settings_.accelerations);
    k1_ = s.v_dot;
    v1_ = v0_;
    // Stage 2: move to t + h/2 along v1.
    advance(s, q0, v1_, h / 2);
    s.v = v0_ + h / 2 * k1_;
    s.t = t0 + h / 2;
    accel_.solve(*scene_, s, ws_, settings_.accelerations);
    k2_ = s.v_dot;
    v2_ = s.v;
    // Stage 3.
    advance(s, q0, v2_, h / 2);
    s.v = v0_ + h / 2 * k2_;
    accel_.solve(*scene_, s, ws_, settings_.accelerations);
    k3_ = s.v_dot;
    v3_ = s.v;
    // Stage 4.
    advance(s, q0, v3_, h);
    s.v = v0_ + h * k3_;
    s.t = t0 + h;
    accel_.solve(*scene_, s, ws_, settings_.accelerations);
    k4_ = s.v_dot;
    v4_ = s.v;
    // Combination: positions with the RK4 weights of the stage velocities, through the
    // quaternion rate (fourth order in theta), then velocities.
    combine(s, q0, h);
    s.v = v0_ + (h / 6) * (k1_ + 2 * k2_ + 2 * k3_ + k4_);
    s.t = t0 + h;
    if (settings_.project) project(s);
    if (!s.v.allFinite() || !scene_->coordinates_finite(s)) {
      s.q = q0;
      s.v = v0_;
      s.t = t0;
      return StepStatus::non_finite_state;
    }
    accel_.solve(*scene_, s, ws_, settings_.accelerations);
    s.a = s.v_dot;
    return StepStatus::ok;
  }

 private:
  /// q = q0 moved for time dt at constant body velocity v (exact on the group).
  void advance(State& s, const decltype(State::q)& q0, const VecV& v, Scalar dt) {
    s.q = q0;
    tmp_ = dt * v;
    scene_->integrate(s, tmp_);
  }

  /// RK4 combination in coordinates: R and p with the weighted velocities; theta with the
  /// weighted quaternion rates of the four stages, evaluated at the stage orientations.
  void combine(State& s, const decltype(State::q)& q0, Scalar h) {
    const VecV &v1 = v1_, &v2 = v2_, &v3 = v3_, &v4 = v4_;
    dx_ = (v1 + 2 * v2 + 2 * v3 + v4) * (h / 6);
    s.q = q0;
    detail::for_each_index(
        [&](auto k) {
          constexpr int K = static_cast<int>(decltype(k)::value);
          constexpr int o = SceneT::body_offset[K];
          auto& q = std::get<K>(s.q);
          const auto& qi = std::get<K>(q0);
          auto stage_theta = [&](const VecV& v, Scalar dt) {
            return compose<Scalar>(
                qi.theta, exp_rotation<Scalar>(Vec3<Scalar>(dt * v.template segment<3>(o + 3))));
          };
          const EulerParameters<Scalar> t1 = qi.theta, t2 = stage_theta(v1, h / 2),
                                        t3 = stage_theta(v2, h / 2), t4 = stage_theta(v3, h);
          auto rate = [&](const EulerParameters<Scalar>& t, const VecV& v) {
            return euler_parameter_rates<Scalar>(t, Vec3<Scalar>(v.template segment<3>(o + 3)));
          };
          const EulerParameters<Scalar> d =
              h / 6 * (rate(t1, v1) + 2 * rate(t2, v2) + 2 * rate(t3, v3) + rate(t4, v4));
          q.theta = normalized<Scalar>(EulerParameters<Scalar>(qi.theta + d));
          q.position = qi.position + dx_.template segment<3>(o);
          if constexpr (SceneT::template has_modes<K>)
            q.p = qi.p + dx_.template segment<SceneT::template modes_of<K>>(o + 6);
        },
        std::make_index_sequence<SceneT::num_bodies>{});
  }

  /// Mass-weighted projection of positions onto Phi = 0 and velocities onto B v + Phi_t = 0.
  void project(State& s) {
    scene_->evaluate(s, ws_);
    matrix_.setZero();
    scene_->mass_blocks(ws_, matrix_);
    const Scalar alpha = settings_.penalty_factor * max_abs(matrix_.diagonal());
    scene_->add_constraint_gram(ws_, alpha, matrix_);
    llt_.compute(matrix_);
    for (int k = 0; k < settings_.projection_iterations; ++k) {
      dx_.noalias() = -alpha * ws_.jac.transpose() * ws_.phi;
      llt_.solveInPlace(dx_);
      scene_->integrate(s, dx_);
      scene_->update_kinematics(s, ws_);
      scene_->update_constraints(s, ws_);
    }
    for (int k = 0; k < settings_.projection_iterations; ++k) {
      e_.noalias() = ws_.jac * s.v;  // product alone: no temporary
      e_ += ws_.phi_t;
      tmp_.noalias() = alpha * ws_.jac.transpose() * e_;
      llt_.solveInPlace(tmp_);
      s.v -= tmp_;
    }
  }

  const SceneT* scene_;
  Settings settings_;
  Status model_status_;
  Workspace ws_;
  ConstrainedAccelerations<SceneT> accel_;
  VecV k1_, k2_, k3_, k4_, v0_, v1_, v2_, v3_, v4_, dx_, tmp_;
  typename SceneT::VecC e_;
  MatVV matrix_;
  Eigen::LLT<MatVV> llt_;
};

}  // namespace flexstress
