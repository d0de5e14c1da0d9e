// Sub-model inertia (optional): the stress the detail's own mass adds when the host frame
// accelerates, rotates or carries it against gravity. The paper's sub-model is quasi-static and
// driven by the host's elastic deformation alone; its own inertia then acts only through the
// host beam (whose mass includes the segment). Locally, between the attachments, the detail
// also carries its own weight and inertia forces; this adds them, quasi-statically, with the
// boundary held (superposition with the boundary-driven solution).
//
// The body force of a rigid host-frame motion, -rho (a_O + alpha x x + omega x (omega x x)),
// with gravity as a_O -= g (all in the host frame), is linear in 12 inertia coordinates
// g = [a_O - g (3); alpha (3); wx^2, wy^2, wz^2, wx wy, wy wz, wz wx], so the outputs get
// y += G g with G = R_inertia U_inertia precomputed once (12 solves with the factorization the
// sub-model already has). Neglected: the detail's elastic accelerations (its local modes are far
// above the host's) and Coriolis forces on its elastic velocities, both second order here.
// A model that does not want this simply does not build it.
#pragma once

#include <Eigen/Core>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/stress/stress_outputs.hpp"
#include "flexstress/stress/sub_model.hpp"

namespace flexstress::stress {

/// The 12 inertia coordinates from the host frame's motion: frame-origin acceleration and
/// gravity (host frame), angular velocity and angular acceleration (host frame).
template <class Scalar>
Eigen::Matrix<Scalar, 12, 1> inertia_coordinates(const Vec3<Scalar>& acceleration,
                                                 const Vec3<Scalar>& gravity,
                                                 const Vec3<Scalar>& omega,
                                                 const Vec3<Scalar>& omega_dot) {
  Eigen::Matrix<Scalar, 12, 1> g;
  g << acceleration - gravity, omega_dot, omega.x() * omega.x(), omega.y() * omega.y(),
      omega.z() * omega.z(), omega.x() * omega.y(), omega.y() * omega.z(), omega.z() * omega.x();
  return g;
}

template <class Scalar = double>
class SubModelInertia {
 public:
  using Rows = Eigen::Matrix<Scalar, Eigen::Dynamic, 12>;
  using Coordinates = Eigen::Matrix<Scalar, 12, 1>;

  /// G for the outputs (same rows, same order as outputs.rows(sub)).
  FLEXSTRESS_PRECOMPUTE
  static Result<SubModelInertia> build(const SubModel& sub, const StressOutputs& outputs);

  Index num_outputs() const { return rows_.rows(); }
  const Rows& rows() const { return rows_; }
  /// y += G g (never allocates).
  template <class Out>
  void add_to(const Coordinates& g, Out&& y) const {
    y.noalias() += rows_ * g;
  }

 private:
  Rows rows_;
};

template <class Scalar>
template <class>
Result<SubModelInertia<Scalar>> SubModelInertia<Scalar>::build(const SubModel& sub,
                                                               const StressOutputs& outputs) {
  auto rows = outputs.rows(sub, sub.inertia_fields());
  if (!rows) return rows.error();
  SubModelInertia m;
  m.rows_ = rows->template cast<Scalar>();
  return m;
}

}  // namespace flexstress::stress

// This header's precompute entry points (core/precompute.hpp).
#define FLEXSTRESS_PRECOMPUTE_STRESS_SUB_MODEL_INERTIA(X)                                \
  X(10, Result<stress::SubModelInertia<double>>, stress::SubModelInertia<double>::build, \
    (const stress::SubModel&, const stress::StressOutputs&))
namespace flexstress {
FLEXSTRESS_PRECOMPUTE_EXTERN(FLEXSTRESS_PRECOMPUTE_STRESS_SUB_MODEL_INERTIA)
}  // namespace flexstress
