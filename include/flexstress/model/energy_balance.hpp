// Energy balance of a running model: the mechanical energy E (kinetic, gravity, elastic,
// springs) against the work W of the prescribed motions, of force elements with internal states
// (a hydraulic cylinder's oil force) and of point loads, and the energy D that modal damping and
// the spring-dampers' dampers took out,
//   r(t) = E(t) - E(0) - W(t) + D(t),
// zero for the exact motion (the work-energy theorem with ideal joints; Shabana, Dynamics of
// Multibody Systems, sec. 3.8). With M v_dot = Q - B^T lambda and B v + Phi_t = 0, drivers do
// W' = lambda^T Phi_t, modal damping dissipates D' = p_dot^T D p_dot and a damper c L_dot^2;
// all are integrated by the trapezoidal rule over each recorded step, so r measures the
// integrator's energy error plus that quadrature's O(h^2). Allocation-free after start.
#pragma once

#include <algorithm>
#include <cmath>

#include "flexstress/model/data.hpp"
#include "flexstress/model/model.hpp"
#include "flexstress/model/pipeline.hpp"
#include "flexstress/model/readouts.hpp"

namespace flexstress {

template <class Scalar>
class EnergyBalance {
 public:
  /// Starts at d's state (consistent: d.lambda and d.v as initialize() or a step left them).
  void start(const Model<Scalar>& model, Data<Scalar>& d) {
    powers(model, d, driver_power_, damping_power_);
    energy0_ = energy_ = energy(model, d).total();
    work_ = dissipated_ = max_residual_ = max_change_ = Scalar(0);
    t_ = d.t;
  }
  /// Adds the step from the last recorded state to d's.
  void record(const Model<Scalar>& model, Data<Scalar>& d) {
    Scalar driver = Scalar(0), damping = Scalar(0);
    powers(model, d, driver, damping);
    const Scalar half_h = Scalar(0.5) * (d.t - t_);
    work_ += half_h * (driver_power_ + driver);
    dissipated_ += half_h * (damping_power_ + damping);
    driver_power_ = driver;
    damping_power_ = damping;
    t_ = d.t;
    energy_ = energy(model, d).total();
    max_residual_ = std::max(max_residual_, std::abs(residual()));
    max_change_ = std::max(max_change_, std::abs(energy_ - energy0_));
  }
  Scalar energy_now() const { return energy_; }       ///< E at the last recorded state
  Scalar initial_energy() const { return energy0_; }  ///< E(0)
  Scalar driver_work() const { return work_; }        ///< W
  Scalar dissipated() const { return dissipated_; }   ///< D
  Scalar residual() const { return energy_ - energy0_ - work_ + dissipated_; }  ///< r
  Scalar max_abs_residual() const { return max_residual_; }
  /// max |E - E(0)| so far: the energy the motion moved, a datum-free scale for r.
  Scalar max_energy_change() const { return max_change_; }

 private:
  void powers(const Model<Scalar>& model, Data<Scalar>& d, Scalar& driver, Scalar& damping) {
    update_kinematics(model, d);
    update_markers(model, d);
    update_constraints(model, d);
    driver = d.lambda.dot(d.phi_t);
    Scalar spring_damping = Scalar(0);
    // Force elements with internal states, at their committed state: f . (v_j - v_i); point
    // loads: f . r' + 1/2 sum_k (m x e_k) . e_k' (their generalized force times v).
    for (std::size_t k = 0; k < model.forces().size(); ++k) {
      const int id = static_cast<int>(k);
      if (model.forces()[k].kind == ForceKind::point_load) {
        Vec3<Scalar> f, m;
        point_load(model, d, id, f, m);
        const auto& state = force_marker(model, d, id, false);
        driver += f.dot(state.origin.velocity);
        for (int a = 0; a < 3; ++a)
          driver += Scalar(0.5) * m.cross(state.axis(a).value).dot(state.axis(a).velocity);
        continue;
      }
      if (model.forces()[k].kind == ForceKind::spring_damper) {
        const auto& mi = force_marker(model, d, id, false);
        const auto& mj = force_marker(model, d, id, true);
        const Vec3<Scalar> dist = mj.origin.value - mi.origin.value;
        const Scalar length = dist.norm();
        if (length > Scalar(0)) {
          const Scalar rate =
              dist.dot(Vec3<Scalar>(mj.origin.velocity - mi.origin.velocity)) / length;
          spring_damping += model.forces()[k].params.damping * rate * rate;
        }
        continue;
      }
      const Vec3<Scalar> f = force_element_force(model, d, id);
      driver += f.dot(Vec3<Scalar>(force_marker(model, d, id, true).origin.velocity -
                                   force_marker(model, d, id, false).origin.velocity));
    }
    damping = spring_damping;
    const auto& bodies = model.bodies();
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      if (!bodies[b].effects.modal_damping) continue;
      Scalar kinetic, elastic, potential, power;
      bodies[b].kernels->energies(bodies[b].holder.get(), d.q.data() + bodies[b].q_offset,
                                  d.v.data() + bodies[b].v_offset, d.rotation[b], model.gravity(),
                                  &kinetic, &elastic, &potential, &power);
      damping += power;
    }
  }

  Scalar t_ = Scalar(0), energy0_ = Scalar(0), energy_ = Scalar(0);
  Scalar work_ = Scalar(0), dissipated_ = Scalar(0);
  Scalar driver_power_ = Scalar(0), damping_power_ = Scalar(0);
  Scalar max_residual_ = Scalar(0), max_change_ = Scalar(0);
};

}  // namespace flexstress
