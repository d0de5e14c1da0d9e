// Effects are compile-time tags: a scene lists the effects it wants in Effects<...>, and the
// code for an effect the scene does not name is never generated (`if constexpr`).
#pragma once

#include <type_traits>

namespace flexstress {

/// Uniform gravity (the scene model's `gravity` vector, global frame).
struct Gravity {};
/// Quadratic velocity vector of the FFRF equations: centrifugal, Coriolis and gyroscopic
/// coupling of rigid motion and deformation (Shabana; the FFRF reference sheet).
struct QuadraticVelocity {};
/// Modal damping D p_dot, D = diag(2 zeta omega), of flexible bodies.
struct ModalDamping {};
/// Spring-dampers between markers (the scene's force elements).
struct SpringDampers {};
/// A user callback that adds external forces (Scene::external_forces).
struct ExternalForces {};
/// Geometric stiffness of flexible bodies under their own inertial and gravity loads
/// (centrifugal stiffening of rotating beams): K_G(state) p with K_G a combination of
/// precomputed modal matrices (reduction/modal_geometric_stiffness.hpp), which each flexible
/// body must be given (BodyModel::set_geometric_stiffness).
struct GeometricStiffening {};
/// Valve-controlled hydraulic cylinders among the scene's force elements
/// (dynamics/hydraulic_cylinder.hpp): chamber pressures solved inside the implicit step.
struct HydraulicDrive {};

/// The list of effects a scene simulates.
template <class... E>
struct Effects {
  template <class Effect>
  static constexpr bool has = (std::is_same_v<Effect, E> || ...);
};

/// All built-in effects (a convenience for full-fidelity scenes).
using AllEffects = Effects<Gravity, QuadraticVelocity, ModalDamping, SpringDampers>;

}  // namespace flexstress
