// Force elements between markers: a linear spring-damper along the line between two marker
// origins (translational spring-damper-actuator, TSDA). Active with the SpringDampers effect.
// A force element kind names the effect that activates it (`effect`); one with internal
// states (hydraulic_cylinder.hpp) also has a State type and a commit() the scene calls after
// each accepted step.
#pragma once

#include <cmath>
#include <type_traits>

#include "flexstress/core/types.hpp"
#include "flexstress/dynamics/effects.hpp"
#include "flexstress/dynamics/marker.hpp"

namespace flexstress {

namespace detail {

/// Internal state of a force element kind: its State<Scalar> if it has one (a hydraulic
/// cylinder's chamber pressures), else nothing.
struct NoForceState {};
template <class Kind, class Scalar, class = void>
struct force_state {
  using type = NoForceState;
  static constexpr bool stateful = false;
};
template <class Kind, class Scalar>
struct force_state<Kind, Scalar, std::void_t<typename Kind::template State<Scalar>>> {
  using type = typename Kind::template State<Scalar>;
  static constexpr bool stateful = true;
};

}  // namespace detail

/// Spring-damper between the origins of marker i (body I) and marker j (body J):
/// tension f = k (L - L0) + c L_dot (+ preload), acting along the line.
template <int I, int J>
struct SpringDamper {
  static constexpr int body_i = I, body_j = J;
  using effect = SpringDampers;  ///< active in scenes that name this effect
  template <class Scalar>
  struct Params {
    Scalar stiffness = Scalar(0);
    Scalar damping = Scalar(0);
    Scalar rest_length = Scalar(0);
    Scalar preload = Scalar(0);
  };
  /// The name of the first parameter out of its domain, or nullptr.
  template <class Scalar>
  static const char* check(const Params<Scalar>& p) {
    if (!std::isfinite(double(p.stiffness)) || !std::isfinite(double(p.damping)) ||
        !std::isfinite(double(p.rest_length)) || !std::isfinite(double(p.preload)))
      return "stiffness, damping, rest_length and preload must be finite";
    return nullptr;
  }
  /// Force on marker j's origin (global); marker i gets the opposite.
  template <class Scalar, int NI, int NJ>
  static Vec3<Scalar> force(const Params<Scalar>& p, const MarkerEval<Scalar, NI>& i,
                            const MarkerEval<Scalar, NJ>& j) {
    const Vec3<Scalar> d = j.origin.value - i.origin.value;
    const Scalar length = d.norm();
    if (!(length > Scalar(0))) return Vec3<Scalar>::Zero();
    const Vec3<Scalar> n = d / length;
    const Scalar rate = n.dot(Vec3<Scalar>(j.origin.velocity - i.origin.velocity));
    const Scalar tension = p.stiffness * (length - p.rest_length) + p.damping * rate + p.preload;
    return -tension * n;
  }
  /// Stored energy 1/2 k (L - L0)^2 + preload L.
  template <class Scalar, int NI, int NJ>
  static Scalar energy(const Params<Scalar>& p, const MarkerEval<Scalar, NI>& i,
                       const MarkerEval<Scalar, NJ>& j) {
    const Scalar l = (j.origin.value - i.origin.value).norm();
    return Scalar(0.5) * p.stiffness * (l - p.rest_length) * (l - p.rest_length) + p.preload * l;
  }
};

}  // namespace flexstress
