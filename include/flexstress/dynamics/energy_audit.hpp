// Energy audit of a running scene: the mechanical energy E (kinetic, gravity, elastic, springs;
// Scene::energy) against the work of the prescribed motions and the energy the modal damping
// took out, so that the balance
//
//   r(t) = E(t) - E(0) - W(t) + D(t)
//
// is zero for the exact motion (W also counts the work of force elements with internal states:
// a hydraulic cylinder's oil force on the mechanism) (the work-energy theorem of a system with
// ideal joints; Shabana, Dynamics of Multibody Systems, sec. 3.8). The equations of motion M v_dot
// = Q - B^T lambda with B v + Phi_t = 0 give dE/dt = -lambda^T B v - p_dot^T D p_dot = lambda^T
// Phi_t - p_dot^T D p_dot: scleronomic joints do no work, drivers and a moving ground do W' =
// lambda^T Phi_t, and modal damping dissipates D' = p_dot^T D p_dot. W and D are integrated by the
// trapezoidal rule over each recorded step, so r measures the integrator's energy error (its
// numerical dissipation, the Newton tolerance, constraint drift) plus the O(h^2) error of that
// quadrature; both shrink as h is refined. The quadratic velocity terms must be in the scene
// (without them the scene's own equations do not conserve energy, and the audit says so by a
// growing r).
//
// Not counted: the work of ExternalForces callbacks, the dissipation of spring-dampers' dampers,
// and the geometric stiffening forces (a linearized, non-conservative load-dependent stiffness).
// A scene with those effects gets an audit of the rest.
//
// Allocation-free after construction: record() may run inside a real-time loop.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <tuple>
#include <utility>

#include "flexstress/dynamics/effects.hpp"
#include "flexstress/dynamics/scene.hpp"

namespace flexstress {

template <class SceneT>
class EnergyAudit {
 public:
  using Scalar = typename SceneT::scalar_type;
  using State = typename SceneT::State;

  explicit EnergyAudit(const SceneT& scene) : scene_(&scene) {}

  /// Starts the audit at s (a consistent state: s.lambda and s.v as the integrator left them).
  void start(const State& s) {
    powers(s, driver_power_, damping_power_);
    energy0_ = energy_ = scene_->energy(w_).total();
    work_ = dissipated_ = Scalar(0);
    max_residual_ = max_change_ = Scalar(0);
    t_ = s.t;
  }

  /// Adds the step from the last recorded state to s.
  void record(const State& s) {
    Scalar driver = Scalar(0), damping = Scalar(0);
    powers(s, driver, damping);
    const Scalar half_h = Scalar(0.5) * (s.t - t_);
    work_ += half_h * (driver_power_ + driver);
    dissipated_ += half_h * (damping_power_ + damping);
    driver_power_ = driver;
    damping_power_ = damping;
    t_ = s.t;
    energy_ = scene_->energy(w_).total();
    max_residual_ = std::max(max_residual_, std::abs(residual()));
    max_change_ = std::max(max_change_, std::abs(energy_ - energy0_));
  }

  Scalar energy() const { return energy_; }           ///< E at the last recorded state
  Scalar initial_energy() const { return energy0_; }  ///< E(0)
  Scalar driver_work() const { return work_; }        ///< W: work of drivers and moving ground
  Scalar dissipated() const { return dissipated_; }   ///< D: taken out by modal damping
  Scalar residual() const { return energy_ - energy0_ - work_ + dissipated_; }  ///< r
  Scalar max_abs_residual() const { return max_residual_; }                     ///< max |r| so far
  /// max |E - E(0)| so far: the energy the motion moved, a datum-free scale for r.
  Scalar max_energy_change() const { return max_change_; }

 private:
  // Evaluates the workspace at s (kinematics, constraints) and the two powers.
  void powers(const State& s, Scalar& driver, Scalar& damping) {
    scene_->update_kinematics(s, w_);
    scene_->update_constraints(s, w_);
    driver = s.lambda.dot(w_.phi_t);
    if constexpr (SceneT::has_force_states) driver += force_element_power(s);
    damping = Scalar(0);
    if constexpr (SceneT::Effects_::template has<ModalDamping>) {
      detail::for_each_index(
          [&](auto k) {
            constexpr int K = static_cast<int>(decltype(k)::value);
            if constexpr (SceneT::template has_modes<K>) {
              const auto& kin = scene_->template kinematics<K>(w_);
              damping += kin.p_dot.dot(scene_->template body<K>().modal_damping() * kin.p_dot);
            }
          },
          std::make_index_sequence<SceneT::num_bodies>{});
    }
  }

  // Power f . (v_j - v_i) of the stateful force elements at their committed state (at s after
  // an accepted step: no further flow or compression since, so this is the force at s).
  Scalar force_element_power(const State& s) const {
    Scalar power = Scalar(0);
    const auto& forces = scene_->forces;
    detail::for_each_index(
        [&](auto k) {
          constexpr std::size_t K = decltype(k)::value;
          using Kind = std::tuple_element_t<K, typename SceneT::ForceKinds>;
          if constexpr (detail::force_state<Kind, Scalar>::stateful &&
                        SceneT::Effects_::template has<typename Kind::effect>) {
            const auto m = scene_->template force_markers<static_cast<int>(K)>(w_);
            const Vec3<Scalar> f =
                Kind::force(std::get<K>(forces).params, std::get<K>(s.force_states), s.t, m.i, m.j);
            power += f.dot(Vec3<Scalar>(m.j.origin.velocity - m.i.origin.velocity));
          }
        },
        std::make_index_sequence<SceneT::num_forces>{});
    return power;
  }

  const SceneT* scene_;
  typename SceneT::Workspace w_;
  Scalar t_ = Scalar(0), energy0_ = Scalar(0), energy_ = Scalar(0);
  Scalar work_ = Scalar(0), dissipated_ = Scalar(0);
  Scalar driver_power_ = Scalar(0), damping_power_ = Scalar(0);
  Scalar max_residual_ = Scalar(0), max_change_ = Scalar(0);
};

}  // namespace flexstress
