// Motion of the ground frame: fixed (the default, costs nothing) or prescribed, for a crane on a
// vehicle or a ship. Joints to the ground then become rheonomic (time-dependent).
#pragma once

#include <Eigen/Core>

#include "flexstress/core/euler_parameters.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/dynamics/body_vector.hpp"

namespace flexstress {

/// Ground kinematics at time t: the BodyKinematics of a zero-mode body, and its prescribed
/// accelerations [R_ddot (global); alpha (body frame)].
template <class Scalar>
struct GroundState {
  BodyKinematics<Scalar, 0> kinematics;
  Vec6<Scalar> acceleration = Vec6<Scalar>::Zero();
};

/// The ground does not move.
template <class Scalar>
struct FixedGround {
  static constexpr bool moving = false;
  void evaluate(Scalar, GroundState<Scalar>& g) const { g = GroundState<Scalar>(); }
};

/// A ground that translates along a prescribed path R(t) and rotates about a fixed global axis
/// by a prescribed angle phi(t) (e.g. a ship's roll, a truck's travel). Path and angle are motion
/// laws (value, rate, acceleration).
template <class Scalar, template <class> class PathLaw, template <class> class AngleLaw>
struct PrescribedGround {
  static constexpr bool moving = true;
  PathLaw<Scalar> x{}, y{}, z{};
  AngleLaw<Scalar> angle{};
  Vec3<Scalar> axis = Vec3<Scalar>::UnitZ();

  void evaluate(Scalar t, GroundState<Scalar>& g) const {
    const auto px = x(t), py = y(t), pz = z(t);
    const auto a = angle(t);
    g.kinematics.position = Vec3<Scalar>(px.value, py.value, pz.value);
    g.kinematics.velocity = Vec3<Scalar>(px.rate, py.rate, pz.rate);
    g.kinematics.rotation = rotation_matrix<Scalar>(from_axis_angle<Scalar>(axis, a.value));
    // Rotation about a fixed axis: the axis is the same in the body frame.
    g.kinematics.omega = axis.normalized() * a.rate;
    g.acceleration.template head<3>() =
        Vec3<Scalar>(px.acceleration, py.acceleration, pz.acceleration);
    g.acceleration.template tail<3>() = axis.normalized() * a.acceleration;
  }
};

}  // namespace flexstress
