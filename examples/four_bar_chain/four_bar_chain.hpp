// IFToMM benchmark A02, the N four-bar mechanism (Gonzalez, Dopico, Lugris, Cuadrado, "A
// benchmarking system for MBS simulation software", Multibody Syst. Dyn. 16 (2006) 179-190;
// the IFToMM library of computational benchmark problems): N + 1 cranks of 1 m pinned to the
// ground 1 m apart and N couplers of 1 m joining their tips; every link a 1 kg rod, g = 9.81,
// the tip B0 of the first crank starts at 1 m/s. Whenever the cranks lie horizontal, cranks and
// couplers are collinear and the mobility jumps from 1 to N + 1: a singular configuration,
// passed twice per revolution. Modelled in 3D with revolute joints, (3N + 1) x 5 constraint
// equations on (2N + 1) x 6 coordinates: heavily redundant, the plain KKT matrix is singular
// everywhere.
//
// The exact motion keeps every crank parallel to the first and every coupler horizontal (a
// chain of parallelograms); a solver that jumps branch at a singular configuration folds a
// parallelogram into an anti-parallelogram. Mechanical energy is conserved.
//
// The scene's type is composed from index sequences, so N = 40 (81 bodies, 121 joints) is as
// short to write as N = 1; above the fixed-storage limit the scene uses dynamic storage.
#pragma once

#include <algorithm>
#include <cmath>
#include <utility>

#include <flexstress/core/euler_parameters.hpp>
#include <flexstress/dynamics/implicit_integrator.hpp>

namespace four_bar_chain {

using namespace flexstress;

namespace detail {

template <std::size_t>
using Link = RigidBody;

template <class A, class B, class C>
struct concat_joints;
template <class... A, class... B, class... C>
struct concat_joints<Joints<A...>, Joints<B...>, Joints<C...>> {
  using type = Joints<A..., B..., C...>;
};

template <std::size_t... K>
Bodies<Link<K>...> links(std::index_sequence<K...>);
// Crank k (body k) on the ground at (k, 0); coupler k (body N + 1 + k) from the tip of crank k
// to the tip of crank k + 1.
template <std::size_t... K>
Joints<Revolute<ground, static_cast<int>(K)>...> ground_pins(std::index_sequence<K...>);
template <int Cranks, std::size_t... K>
Joints<Revolute<static_cast<int>(K), Cranks + static_cast<int>(K)>...> left_pins(
    std::index_sequence<K...>);
template <int Cranks, std::size_t... K>
Joints<Revolute<Cranks + static_cast<int>(K), static_cast<int>(K) + 1>...> right_pins(
    std::index_sequence<K...>);

}  // namespace detail

/// The chain of N parallelograms: its scene type and how to build it.
template <int N>
struct Chain {
  static constexpr int bars = N;
  static constexpr int cranks = N + 1;      // bodies 0 .. N
  static constexpr int bodies = 2 * N + 1;  // couplers N + 1 .. 2N
  using BodyList = decltype(detail::links(std::make_index_sequence<bodies>{}));
  using JointList = typename detail::concat_joints<
      decltype(detail::ground_pins(std::make_index_sequence<cranks>{})),
      decltype(detail::left_pins<cranks>(std::make_index_sequence<N>{})),
      decltype(detail::right_pins<cranks>(std::make_index_sequence<N>{}))>::type;
  using SceneT = Scene<double, BodyList, JointList, Effects<Gravity, QuadraticVelocity>>;
  using State = typename SceneT::State;
  static_assert(SceneT::nv == 6 * bodies && SceneT::nc == 5 * (cranks + 2 * N));

  /// A slender 1 kg, 1 m rod along its body x axis, frame at its centre (1 cm square section).
  static RigidBody rod() {
    const double a = 0.01, transverse = (1.0 + a * a) / 12, axial = a * a / 6;
    return RigidBody::rigid(1.0, Vector3d::Zero(),
                            Vector3d(axial, transverse, transverse).asDiagonal());
  }

  /// The scene and its initial state: cranks vertical, couplers horizontal at y = 1, the crank
  /// tips moving at +1 m/s (the benchmark's start). Every joint axis (marker z) is global z.
  static SceneT make(State& s) {
    SceneT scene;
    // A crank's body x points along global y (up); body z = global z.
    const Matrix3d crank_axes = (Matrix3d() << 0, -1, 0, 1, 0, 0, 0, 0, 1).finished();
    flexstress::detail::for_each_index(
        [&](auto k) {
          constexpr int K = static_cast<int>(decltype(k)::value);
          scene.template body<K>() = rod();
          if constexpr (K < cranks) {
            s.template coordinates<K>().position = Vector3d(K, 0.5, 0);
            s.template coordinates<K>().theta = from_rotation_matrix<double>(crank_axes);
            s.template velocity<K>() << 0.5, 0, 0, 0, 0, -1;  // w = -1 rad/s: tip at +1 m/s
          } else {
            s.template coordinates<K>().position = Vector3d(K - cranks + 0.5, 1.0, 0);
            s.template velocity<K>() << 1, 0, 0, 0, 0, 0;
          }
        },
        std::make_index_sequence<bodies>{});
    flexstress::detail::for_each_index(
        [&](auto k) {
          constexpr int K = static_cast<int>(decltype(k)::value);
          auto& j = scene.template joint<K>();
          if constexpr (K < cranks) {  // ground pin of crank K
            j.marker_i = fixed_marker<double>(Vector3d(K, 0, 0));
            j.marker_j = make_marker(scene.template body<K>(), -1, Vector3d(-0.5, 0, 0));
          } else if constexpr (K < cranks + N) {  // tip of crank c, left end of coupler c
            constexpr int c = K - cranks;
            j.marker_i = make_marker(scene.template body<c>(), -1, Vector3d(0.5, 0, 0));
            j.marker_j = make_marker(scene.template body<cranks + c>(), -1, Vector3d(-0.5, 0, 0));
          } else {  // right end of coupler c, tip of crank c + 1
            constexpr int c = K - cranks - N;
            j.marker_i = make_marker(scene.template body<cranks + c>(), -1, Vector3d(0.5, 0, 0));
            j.marker_j = make_marker(scene.template body<c + 1>(), -1, Vector3d(0.5, 0, 0));
          }
        },
        std::make_index_sequence<SceneT::num_joints>{});
    return scene;
  }

  /// Integrator settings for the chain. Where the cranks pass the horizontal, the constraint
  /// Jacobian loses rank: in a direction where its singular value is sigma, the augmented
  /// Lagrangian's multiplier update contracts by about 1 / (1 + penalty_factor sigma^2) per
  /// iteration. A penalty factor of 1e5 (default 1e3) keeps that below 1/2 except within about
  /// 3 mrad of the singular configuration; the few steps closer than that are kept at the
  /// iteration budget (their multipliers are ill-defined there; their positions are not), and
  /// velocity projection removes what they leave in the velocities.
  static typename ImplicitIntegrator<SceneT>::Settings settings(double h) {
    typename ImplicitIntegrator<SceneT>::Settings set;
    set.step = h;
    set.penalty_factor = 1e5;
    set.accept_at_iteration_limit = true;
    set.project_velocities = true;
    return set;
  }
};

/// Planar angle of a body's x axis.
inline double heading(const EulerParameters<double>& theta) {
  const Matrix3d a = rotation_matrix(theta);
  return std::atan2(a(1, 0), a(0, 0));
}

/// What the benchmark asks of a run, measured step by step against the exact motion (every
/// crank parallel to the first, every coupler horizontal, energy constant).
struct Monitor {
  double crank_spread = 0;  ///< largest angle between a crank and the first crank (rad)
  double coupler_tilt = 0;  ///< largest angle of a coupler from the horizontal (rad)
  double energy_error = 0;  ///< largest |E - E0| (J)
  int singular_passes = 0;  ///< sign changes of the first crank's tip height
  double budget_angle = 0;  ///< largest crank angle from the horizontal at a budget-kept step
  double first_crank = 0;   ///< current angle of the first crank (rad)

  template <class ChainT>
  void record(const typename ChainT::State& s, double energy, double e0, bool kept_at_budget) {
    using flexstress::detail::for_each_index;
    constexpr double two_pi = 6.283185307179586;
    const double a0 = heading(s.template coordinates<0>().theta);
    for_each_index(
        [&](auto k) {
          constexpr int K = static_cast<int>(decltype(k)::value);
          const double a = heading(s.template coordinates<K>().theta);
          if constexpr (K < ChainT::cranks)
            crank_spread = std::max(crank_spread, std::abs(std::remainder(a - a0, two_pi)));
          else
            coupler_tilt = std::max(coupler_tilt, std::abs(std::remainder(a, two_pi)));
        },
        std::make_index_sequence<ChainT::bodies>{});
    energy_error = std::max(energy_error, std::abs(energy - e0));
    if (started_ && (std::sin(a0) > 0) != (std::sin(first_crank) > 0)) ++singular_passes;
    started_ = true;
    first_crank = a0;
    if (kept_at_budget)  // angle from the horizontal, folded into [0, pi/2]
      budget_angle = std::max(budget_angle, std::abs(std::asin(std::sin(a0))));
  }

 private:
  bool started_ = false;
};

}  // namespace four_bar_chain
