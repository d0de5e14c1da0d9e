// A scene: bodies, joints, force elements and effects fixed at compile time, so every size (the
// velocity count nv, the constraint count nc) is a compile-time constant and the step works on
// fixed-size storage. Scenes above a size bound (a 40-bar chain) switch to dynamic storage,
// allocated once when a Workspace is built.
//
// Model / Data split (as in Pinocchio): the Scene object is the model (bodies, markers, joint
// parameters, gravity), set up once and then only read; a State holds coordinates, velocities
// and multipliers; a Workspace holds everything an evaluation writes. Evaluations are const
// member functions and never allocate.
//
// Global velocity vector: v = [v_0; v_1; ...], v_b = [R_dot (global); w (body); p_dot].
// Constraints: Phi(q, t) = 0 with Jacobian B (nc x nv): Phi_dot = B v + Phi_t, and the
// acceleration constraint B v_dot = -conv.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <type_traits>
#include <utility>

#include <Eigen/Core>

#include "flexstress/core/envelope_cholesky.hpp"
#include "flexstress/core/euler_parameters.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/dynamics/body_model.hpp"
#include "flexstress/dynamics/effects.hpp"
#include "flexstress/dynamics/force_elements.hpp"
#include "flexstress/dynamics/ground_motion.hpp"
#include "flexstress/dynamics/joints.hpp"
#include "flexstress/dynamics/marker.hpp"

namespace flexstress {

template <class... B>
struct Bodies {};
template <class... J>
struct Joints {};
template <class... F>
struct ForceElements {};

/// Coordinates of one body: R, theta, p.
template <class Scalar, int NModes>
struct BodyCoordinates {
  Vec3<Scalar> position = Vec3<Scalar>::Zero();
  EulerParameters<Scalar> theta = identity_euler_parameters<Scalar>();
  Vec<Scalar, NModes> p = Vec<Scalar, NModes>::Zero();
};

namespace detail {

template <std::size_t N>
constexpr std::array<int, N + 1> prefix_sums(const std::array<int, N>& a) {
  std::array<int, N + 1> s{};
  for (std::size_t i = 0; i < N; ++i) s[i + 1] = s[i] + a[i];
  return s;
}

template <int K, class Tuple, bool Ground = (K < 0)>
struct modes_of {
  static constexpr int value = std::tuple_element_t<static_cast<std::size_t>(K), Tuple>::num_modes;
};
template <int K, class Tuple>
struct modes_of<K, Tuple, true> {
  static constexpr int value = 0;
};

/// The marker parts a joint kind reads (MarkerParts): its parts_i and parts_j, or all of both
/// for a kind that does not declare them.
template <class Kind, class = void>
struct joint_parts {
  static constexpr unsigned i = MarkerParts::all, j = MarkerParts::all;
};
template <class Kind>
struct joint_parts<Kind, std::void_t<decltype(Kind::parts_i), decltype(Kind::parts_j)>> {
  static constexpr unsigned i = Kind::parts_i, j = Kind::parts_j;
};

template <class F, std::size_t... I>
constexpr void for_each_index(F&& f, std::index_sequence<I...>) {
  (f(std::integral_constant<std::size_t, I>{}), ...);
}

}  // namespace detail

#ifndef FLEXSTRESS_FIXED_STORAGE_LIMIT
#define FLEXSTRESS_FIXED_STORAGE_LIMIT 64
#endif
/// Largest velocity / constraint count a scene keeps in fixed-size storage by default. Fixed
/// storage saves little time per step (3 % on the crane, nv = 28; docs/performance.md) but
/// costs compile time (every size instantiates its own Eigen kernels), so a program may lower
/// it by defining FLEXSTRESS_FIXED_STORAGE_LIMIT, or choose per scene (StorageLimit below).
/// The limit is part of the scene's type, so translation units that differ in it still agree
/// on every type they share.
inline constexpr int fixed_storage_limit = FLEXSTRESS_FIXED_STORAGE_LIMIT;

template <class Scalar, class BodyList, class JointList, class EffectList = Effects<>,
          class ForceList = ForceElements<>, class Ground = FixedGround<Scalar>,
          int StorageLimit = fixed_storage_limit>
class Scene;

template <class Scalar, class... B, class... J, class... E, class... F, class Ground,
          int StorageLimit>
class Scene<Scalar, Bodies<B...>, Joints<J...>, Effects<E...>, ForceElements<F...>, Ground,
            StorageLimit> {
 public:
  using scalar_type = Scalar;
  using Effects_ = Effects<E...>;
  using BodyTuple = std::tuple<B...>;
  using ForceKinds = std::tuple<F...>;
  static constexpr int num_bodies = sizeof...(B);
  static constexpr int num_joints = sizeof...(J);
  static constexpr int num_forces = sizeof...(F);
  static constexpr std::array<int, num_bodies> body_nv{B::nv...};
  static constexpr std::array<int, num_bodies + 1> body_offset = detail::prefix_sums(body_nv);
  static constexpr int nv = body_offset[num_bodies];
  static constexpr std::array<int, num_joints> joint_nc{J::equations...};
  static constexpr std::array<int, num_joints + 1> joint_offset = detail::prefix_sums(joint_nc);
  static constexpr int nc = joint_offset[num_joints];
  static constexpr bool fixed_storage = nv <= StorageLimit && nc <= StorageLimit;
  static constexpr int NV = fixed_storage ? nv : Eigen::Dynamic;
  static constexpr int NC = fixed_storage ? nc : Eigen::Dynamic;

  static_assert(num_bodies > 0, "a scene needs at least one body");
  static_assert(((J::body_i < num_bodies && J::body_j < num_bodies && J::body_i >= ground &&
                  J::body_j >= ground && J::body_i != J::body_j) &&
                 ...),
                "a joint refers to a body index outside the scene (or joins a body to itself)");
  static_assert(
      ((std::is_same_v<typename B::Kinematics, BodyKinematics<Scalar, B::num_modes>>)&&...),
      "all bodies of a scene must use the scene's Scalar type");

  /// The same scene with another storage limit (0: dynamic storage, allocated once per
  /// State, Workspace and integrator).
  template <int Limit>
  using with_storage_limit =
      Scene<Scalar, Bodies<B...>, Joints<J...>, Effects<E...>, ForceElements<F...>, Ground, Limit>;

  template <int K>
  using BodyType = std::tuple_element_t<static_cast<std::size_t>(K), BodyTuple>;
  /// Number of equations of joint K.
  template <int K>
  static constexpr int joint_equations = joint_nc[static_cast<std::size_t>(K)];
  template <int K>
  static constexpr int modes_of = detail::modes_of<K, BodyTuple>::value;
  template <int K>
  static constexpr bool has_modes = detail::modes_of<K, BodyTuple>::value > 0;

  using VecV = Eigen::Matrix<Scalar, NV, 1>;
  using VecC = Eigen::Matrix<Scalar, NC, 1>;
  using MatVV = Eigen::Matrix<Scalar, NV, NV>;
  using MatCV = Eigen::Matrix<Scalar, NC, NV>;

  /// A joint of kind Kind with its two markers and parameters.
  template <class Kind>
  struct JointInstance {
    Marker<Scalar, modes_of<Kind::body_i>> marker_i;
    Marker<Scalar, modes_of<Kind::body_j>> marker_j;
    typename Kind::template Params<Scalar> params{};
  };
  template <class Kind>
  struct ForceInstance {
    Marker<Scalar, modes_of<Kind::body_i>> marker_i;
    Marker<Scalar, modes_of<Kind::body_j>> marker_j;
    typename Kind::template Params<Scalar> params{};
  };

  // ---- model ------------------------------------------------------------------------------
  BodyTuple bodies;
  std::tuple<JointInstance<J>...> joints;
  std::tuple<ForceInstance<F>...> forces;
  Vec3<Scalar> gravity = Vec3<Scalar>(Scalar(0), Scalar(-9.81), Scalar(0));
  Ground ground_motion{};

  template <int K>
  BodyType<K>& body() {
    return std::get<static_cast<std::size_t>(K)>(bodies);
  }
  template <int K>
  const BodyType<K>& body() const {
    return std::get<static_cast<std::size_t>(K)>(bodies);
  }
  template <int K>
  auto& joint() {
    return std::get<static_cast<std::size_t>(K)>(joints);
  }
  template <int K>
  const auto& joint() const {
    return std::get<static_cast<std::size_t>(K)>(joints);
  }
  template <int K>
  auto& force() {
    return std::get<static_cast<std::size_t>(K)>(forces);
  }

  // ---- state ------------------------------------------------------------------------------
  struct State {
    Scalar t = Scalar(0);
    std::tuple<BodyCoordinates<Scalar, B::num_modes>...> q;
    VecV v, v_dot, a;  ///< velocities, accelerations, algorithmic accelerations (gen-alpha)
    VecC lambda;       ///< constraint multipliers
    /// Internal states of the force elements (the last accepted step's), in their order.
    std::tuple<typename detail::force_state<F, Scalar>::type...> force_states;
    State() {
      v.setZero(nv);
      v_dot.setZero(nv);
      a.setZero(nv);
      lambda.setZero(nc);
    }
    template <int K>
    auto& coordinates() {
      return std::get<static_cast<std::size_t>(K)>(q);
    }
    template <int K>
    const auto& coordinates() const {
      return std::get<static_cast<std::size_t>(K)>(q);
    }
    /// Velocity block of body K.
    template <int K>
    auto velocity() {
      return v.template segment<body_nv[K]>(body_offset[K]);
    }
    template <int K>
    auto velocity() const {
      return v.template segment<body_nv[K]>(body_offset[K]);
    }
  };

  // ---- workspace --------------------------------------------------------------------------
  struct Workspace {
    std::tuple<BodyKinematics<Scalar, B::num_modes>...> kin;
    std::tuple<typename B::Terms...> terms;
    std::tuple<typename B::MatV...> mass;
    std::tuple<typename B::MatN...> geometric;  ///< K_G (GeometricStiffening)
    VecV force;  ///< generalized applied force: Q_e - Q_v - K p - D p_dot
    MatCV jac;   ///< B
    VecC phi, phi_t, conv;
    GroundState<Scalar> ground;
    Workspace() {
      force.setZero(nv);
      jac.setZero(nc, nv);
      phi.setZero(nc);
      phi_t.setZero(nc);
      conv.setZero(nc);
    }
  };

  // ---- external forces (part of the model) ------------------------------------------------
  /// External forces (Effects<ExternalForces>): called once per force evaluation, after the
  /// built-in effects, with the time and the workspace's kinematics; adds to w.force (for
  /// example with add_point_force). It runs inside step(), so it must not allocate or throw.
  /// A plain function pointer and a user pointer: no type erasure that could allocate.
  using ExternalForceFunction = void (*)(const Scene& scene, Scalar t, Workspace& w, void* user);
  ExternalForceFunction external_forces = nullptr;
  void* external_forces_user = nullptr;

  // ---- runtime changes (no reallocation) --------------------------------------------------
  /// Switches joint K on or off while the scene runs (a payload hooked or released, a brake
  /// locked or freed). An inactive joint's equations read 0 = 0: zero rows of B, Phi, Phi_t and
  /// conv, which both integrators' augmented Lagrangian tolerates like any redundant constraint
  /// (M + alpha B^T B stays positive definite), so every size stays fixed and nothing is
  /// allocated. Each switch counts in revision(); the implicit integrator's next step sees it
  /// and restarts from the state as initialize() does: accelerations consistent with the new
  /// forces, and for a joint switched on, positions assembled and velocities projected in the
  /// mass metric (a perfectly plastic capture: momentum kept, the relative motion's energy
  /// lost). anchor_joint_at() first makes the joint hold the bodies where they are.
  template <int K>
  void set_joint_active(bool active) {
    static_assert(K >= 0 && K < num_joints, "no such joint");
    joint_active_[static_cast<std::size_t>(K)] = active;
    ++revision_;
  }
  template <int K>
  bool joint_active() const {
    return joint_active_[static_cast<std::size_t>(K)];
  }
  bool joint_active(int k) const { return joint_active_[static_cast<std::size_t>(k)]; }

  /// Moves marker j of joint K on its body so that it coincides with marker i at state s: the
  /// joint then holds the two bodies as they are (origin and axes), so switching it on is a
  /// capture without a jump in positions. Exact on a rigid body j; on a flexible body j the
  /// moved point keeps its node's mode shapes (the offset's small-rotation lever arm is not
  /// updated). Holds for joints whose equations are met by coincident frames (spherical,
  /// revolute, universal, cylindrical, prismatic, fixed).
  template <int K>
  void anchor_joint_at(const State& s, Workspace& w) {
    using Kind = std::tuple_element_t<static_cast<std::size_t>(K), std::tuple<J...>>;
    constexpr int bi = Kind::body_i, bj = Kind::body_j;
    static_assert(bj >= 0, "anchor_joint_at moves marker j, which must not be on the ground");
    update_kinematics(s, w);
    auto& inst = std::get<static_cast<std::size_t>(K)>(joints);
    MarkerEval<Scalar, modes_of<bi>> mi;
    mi.evaluate(inst.marker_i, kinematics<bi>(w));
    const auto& kj = kinematics<bj>(w);
    const auto rebase = [&](auto& vector, const Vec3<Scalar>& global) {
      Vec3<Scalar> local =
          kj.rotation.transpose() * (vector.is_point ? Vec3<Scalar>(global - kj.position) : global);
      if constexpr (modes_of < bj >> 0) local -= vector.psi * kj.p;
      vector.c = local;
    };
    rebase(inst.marker_j.origin, mi.origin.value);
    rebase(inst.marker_j.x, mi.x.value);
    rebase(inst.marker_j.y, mi.y.value);
    rebase(inst.marker_j.z, mi.z.value);
    ++revision_;
  }

  /// Counts the runtime changes made to the model (joints switched, markers anchored): an
  /// integrator that sees it change drops its factorized Newton matrix.
  std::uint64_t revision() const { return revision_; }
  /// Zeroes the multipliers of inactive joints (their reactions are zero, not the last ones).
  template <class V>
  void clear_inactive_multipliers(V& lambda) const {
    for (int k = 0; k < num_joints; ++k)
      if (!joint_active_[static_cast<std::size_t>(k)])
        lambda
            .segment(joint_offset[static_cast<std::size_t>(k)],
                     joint_nc[static_cast<std::size_t>(k)])
            .setZero();
  }

  // ---- evaluation -------------------------------------------------------------------------
  /// Body kinematics (A, p, velocities) from the state, and the ground at time t.
  void update_kinematics(const State& s, Workspace& w) const {
    detail::for_each_index(
        [&](auto k) {
          constexpr int K = static_cast<int>(decltype(k)::value);
          auto& kin = std::get<K>(w.kin);
          const auto& q = std::get<K>(s.q);
          kin.position = q.position;
          kin.rotation = rotation_matrix(q.theta);
          const auto v = s.v.template segment<body_nv[K]>(body_offset[K]);
          kin.velocity = v.template head<3>();
          kin.omega = v.template segment<3>(3);
          if constexpr (has_modes<K>) {
            kin.p = q.p;
            kin.p_dot = v.template tail<modes_of<K>>();
          }
        },
        std::make_index_sequence<num_bodies>{});
    ground_motion.evaluate(s.t, w.ground);
  }

  /// Constraint values, Jacobian, explicit time derivative and convective terms at s.t (call
  /// update_kinematics first). With rates == false, phi_t and conv are left incomplete (the
  /// marker velocities are taken as zero): for Newton iterations, which need only Phi and B.
  void update_constraints(const State& s, Workspace& w, bool rates = true) const {
    detail::for_each_index(
        [&](auto k) { evaluate_joint<static_cast<int>(decltype(k)::value)>(s.t, w, rates); },
        std::make_index_sequence<num_joints>{});
  }

  /// Mass matrix blocks and the applied generalized force (effects and force elements).
  void update_dynamics(const State& s, Workspace& w) const {
    detail::for_each_index(
        [&](auto k) {
          constexpr int K = static_cast<int>(decltype(k)::value);
          const auto& body = std::get<K>(bodies);
          const auto& kin = std::get<K>(w.kin);
          auto& terms = std::get<K>(w.terms);
          auto& m = std::get<K>(w.mass);
          body.compute_terms(kin, terms);
          body.mass_matrix(kin, terms, m);
          auto f = w.force.template segment<body_nv[K]>(body_offset[K]);
          typename BodyType<K>::VecV fb = BodyType<K>::VecV::Zero();
          if constexpr (Effects_::template has<Gravity>)
            body.gravity_force(kin, terms, gravity, fb);
          if constexpr (Effects_::template has<QuadraticVelocity>) {
            typename BodyType<K>::VecV qv;
            body.quadratic_velocity(kin, terms, qv);
            fb -= qv;
          }
          if constexpr (has_modes<K>) {
            auto fp = fb.template tail<modes_of<K>>();
            // Coefficient-based products here and in add_mass_times: fixed and small, where
            // the general matrix-vector kernel's call costs more than the product.
            fp.noalias() -= body.modal_stiffness().lazyProduct(kin.p);
            if constexpr (Effects_::template has<ModalDamping>)
              fp.noalias() -= body.modal_damping().lazyProduct(kin.p_dot);
            if constexpr (Effects_::template has<GeometricStiffening>) {
              // The load factors of the current iterate: its accelerations (the integrators
              // keep s.v_dot at the iterate) and angular velocity.
              auto& kg = std::get<K>(w.geometric);
              const auto vd = s.v_dot.template segment<body_nv[K]>(body_offset[K]);
              Vec3<Scalar> a_g = kin.rotation.transpose() * vd.template head<3>();
              if constexpr (Effects_::template has<Gravity>)
                a_g.noalias() -= kin.rotation.transpose() * gravity;
              body.geometric_stiffness(a_g, vd.template segment<3>(3), kin.omega, kg);
              fp.noalias() -= kg.lazyProduct(kin.p);
            }
          }
          f = fb;
        },
        std::make_index_sequence<num_bodies>{});
    detail::for_each_index(
        [&](auto k) { apply_force_element<static_cast<int>(decltype(k)::value)>(s, w); },
        std::make_index_sequence<num_forces>{});
    if constexpr (Effects_::template has<ExternalForces>) {
      if (external_forces != nullptr) external_forces(*this, s.t, w, external_forces_user);
    }
    (void)s;
  }

  /// Adds the generalized force of a force f (global components) acting at the origin of
  /// marker m on body K: Q += J_m^T f (for use in an external force callback).
  template <int K>
  void add_point_force(Workspace& w, const Marker<Scalar, modes_of<K>>& m,
                       const Vec3<Scalar>& f) const {
    static_assert(K >= 0 && K < num_bodies, "add_point_force: body index outside the scene");
    w.force.template segment<body_nv[K]>(body_offset[K]) +=
        m.origin.row(std::get<static_cast<std::size_t>(K)>(w.kin), f).transpose();
  }

  /// Whether any active force element has internal states (integrators then call the two
  /// functions below).
  static constexpr bool has_force_states =
      ((detail::force_state<F, Scalar>::stateful && Effects_::template has<typename F::effect>) ||
       ... || false);
  /// Starts the force elements' internal states at s (their user-set values, e.g. chamber
  /// pressures, at s's configuration and time). Call update_kinematics(s, w) first.
  void start_force_states(State& s, const Workspace& w) const { update_force_states<true>(s, w); }
  /// Stores the force elements' internal states at s after an accepted step (call
  /// update_kinematics(s, w) first).
  void commit_force_states(State& s, const Workspace& w) const { update_force_states<false>(s, w); }

  /// All of the above at the state's time (rates: as in update_constraints).
  void evaluate(const State& s, Workspace& w, bool rates = true) const {
    update_kinematics(s, w);
    update_constraints(s, w, rates);
    update_dynamics(s, w);
  }

  /// y += M x with the block-diagonal mass matrix of the last update_dynamics.
  template <class X, class Y>
  void add_mass_times(const Workspace& w, const X& x, Y& y) const {
    detail::for_each_index(
        [&](auto k) {
          constexpr int K = static_cast<int>(decltype(k)::value);
          y.template segment<body_nv[K]>(body_offset[K]).noalias() +=
              std::get<K>(w.mass).lazyProduct(x.template segment<body_nv[K]>(body_offset[K]));
        },
        std::make_index_sequence<num_bodies>{});
  }

  /// Writes the block-diagonal mass matrix into m (nv x nv); other entries are left alone.
  template <class M>
  void mass_blocks(const Workspace& w, M& m) const {
    detail::for_each_index(
        [&](auto k) {
          constexpr int K = static_cast<int>(decltype(k)::value);
          m.template block<body_nv[K], body_nv[K]>(body_offset[K], body_offset[K]) =
              std::get<K>(w.mass);
        },
        std::make_index_sequence<num_bodies>{});
  }

  /// m += alpha B^T B, assembled joint by joint: the rows of a joint touch only the columns of
  /// its two bodies, so B^T B is a sum of body-pair blocks (O(nc nv_body^2) instead of the
  /// dense O(nc nv^2), which matters for long chains: 605 x 486 for the 40-bar linkage).
  template <class M>
  void add_constraint_gram(const Workspace& w, Scalar alpha, M& m) const {
    detail::for_each_index(
        [&](auto k) {
          constexpr int K = static_cast<int>(decltype(k)::value);
          using Kind = std::tuple_element_t<static_cast<std::size_t>(K), std::tuple<J...>>;
          constexpr int bi = Kind::body_i, bj = Kind::body_j, n = joint_nc[K], r = joint_offset[K];
          if (!joint_active_[static_cast<std::size_t>(K)]) return;  // zero rows
          if constexpr (n > 0) {
            const auto rows = w.jac.template middleRows<n>(r);
            if constexpr (bi >= 0) {
              const auto scaled_i = scaled_transpose<bi>(rows, alpha);
              add_gram_block<bi, bi>(scaled_i, rows, m);
              if constexpr (bj >= 0) add_gram_block<bi, bj>(scaled_i, rows, m);
            }
            if constexpr (bj >= 0) {
              const auto scaled_j = scaled_transpose<bj>(rows, alpha);
              add_gram_block<bj, bj>(scaled_j, rows, m);
              if constexpr (bi >= 0) add_gram_block<bj, bi>(scaled_j, rows, m);
            }
          }
        },
        std::make_index_sequence<num_joints>{});
  }

  /// Where the iteration matrix M b' + ... + alpha B^T B can be nonzero: one dense block per
  /// body, coupled where a joint joins two bodies (setup: allocates).
  static BlockPattern block_pattern() {
    BlockPattern pattern;
    pattern.block_sizes.assign(body_nv.begin(), body_nv.end());
    const auto couple = [&](int i, int j) {
      if (i >= 0 && j >= 0) pattern.couplings.emplace_back(i, j);  // ground joints: diagonal
    };
    (couple(J::body_i, J::body_j), ...);
    return pattern;
  }

  /// Adds the modal stiffness and damping (the derivatives of the elastic forces) to the
  /// modal blocks of an iteration matrix: m += k_factor (K + K_G) + c_factor D, with the
  /// geometric stiffness K_G of the last update_dynamics (GeometricStiffening).
  template <class M>
  void add_modal_stiffness_damping(const Workspace& w, M& m, Scalar k_factor,
                                   Scalar c_factor) const {
    detail::for_each_index(
        [&](auto k) {
          constexpr int K = static_cast<int>(decltype(k)::value);
          if constexpr (has_modes<K>) {
            const auto& body = std::get<K>(bodies);
            constexpr int o = body_offset[K] + 6;
            auto block = m.template block<modes_of<K>, modes_of<K>>(o, o);
            block += k_factor * body.modal_stiffness();
            if constexpr (Effects_::template has<ModalDamping>)
              block += c_factor * body.modal_damping();
            if constexpr (Effects_::template has<GeometricStiffening>)
              block += k_factor * std::get<K>(w.geometric);
          }
        },
        std::make_index_sequence<num_bodies>{});
    (void)w;
  }

  /// Checks that every flexible body has the data the scene's effects need (the geometric
  /// stiffness of GeometricStiffening) and that the active force elements' parameters are in
  /// their domains (naming the element and the parameter); the integrators' initialize() calls
  /// it.
  Status check_effect_data() const {
    Status status = Status::success();
    detail::for_each_index(
        [&](auto k) {
          constexpr int K = static_cast<int>(decltype(k)::value);
          if constexpr (has_modes<K> && Effects_::template has<GeometricStiffening>)
            if (status.ok() && !std::get<K>(bodies).has_geometric_stiffness())
              status = make_error(ErrorCode::invalid_argument, "body ", K,
                                  ": the scene has GeometricStiffening but the body has no "
                                  "geometric stiffness (BodyModel::set_geometric_stiffness)");
        },
        std::make_index_sequence<num_bodies>{});
    detail::for_each_index(
        [&](auto k) {
          constexpr std::size_t K = decltype(k)::value;
          using Kind = std::tuple_element_t<K, std::tuple<F...>>;
          if constexpr (Effects_::template has<typename Kind::effect>)
            if (status.ok())
              if (const char* bad = Kind::check(std::get<K>(forces).params))
                status = make_error(ErrorCode::invalid_argument, "force element ", K, ": ", bad);
        },
        std::make_index_sequence<num_forces>{});
    return status;
  }

  /// Moves the coordinates along a velocity-space increment dx (Lie-group update):
  /// R += dx_R, theta = theta (x) exp(dx_w), p += dx_p; theta is renormalized.
  template <class X>
  void integrate(State& s, const X& dx) const {
    detail::for_each_index(
        [&](auto k) {
          constexpr int K = static_cast<int>(decltype(k)::value);
          auto& q = std::get<K>(s.q);
          const auto d = dx.template segment<body_nv[K]>(body_offset[K]);
          q.position += d.template head<3>();
          q.theta = normalized<Scalar>(compose<Scalar>(
              q.theta, exp_rotation<Scalar>(Vec3<Scalar>(d.template segment<3>(3)))));
          if constexpr (has_modes<K>) q.p += d.template tail<modes_of<K>>();
        },
        std::make_index_sequence<num_bodies>{});
  }

  /// True if every coordinate of s is finite (the integrators' check before keeping a step).
  bool coordinates_finite(const State& s) const {
    bool finite = true;
    detail::for_each_index(
        [&](auto k) {
          const auto& q = std::get<static_cast<int>(decltype(k)::value)>(s.q);
          finite = finite && q.position.allFinite() && q.theta.allFinite();
          if constexpr (has_modes<static_cast<int>(decltype(k)::value)>)
            finite = finite && q.p.allFinite();
        },
        std::make_index_sequence<num_bodies>{});
    return finite;
  }

  /// The first body whose coordinates or velocities are not finite, or -1.
  int nonfinite_body(const State& s) const {
    int found = -1;
    detail::for_each_index(
        [&](auto k) {
          constexpr int K = static_cast<int>(decltype(k)::value);
          const auto& q = std::get<static_cast<std::size_t>(K)>(s.q);
          bool finite =
              q.position.allFinite() && q.theta.allFinite() && s.template velocity<K>().allFinite();
          if constexpr (has_modes<K>) finite = finite && q.p.allFinite();
          if (!finite && found < 0) found = K;
        },
        std::make_index_sequence<num_bodies>{});
    return found;
  }

  /// Largest modal angular frequency of the scene's flexible bodies.
  Scalar max_modal_frequency() const {
    Scalar m = Scalar(0);
    detail::for_each_index(
        [&](auto k) { m = std::max(m, std::get<decltype(k)::value>(bodies).max_frequency()); },
        std::make_index_sequence<num_bodies>{});
    return m;
  }

  // ---- energies (for tests and monitors) ---------------------------------------------------
  struct Energy {
    Scalar kinetic = Scalar(0), gravity = Scalar(0), elastic = Scalar(0), springs = Scalar(0);
    Scalar total() const { return kinetic + gravity + elastic + springs; }
  };
  /// Energies at the state (call update_kinematics first).
  Energy energy(const Workspace& w) const {
    Energy e;
    detail::for_each_index(
        [&](auto k) {
          constexpr std::size_t K = decltype(k)::value;
          const auto& body = std::get<K>(bodies);
          const auto& kin = std::get<K>(w.kin);
          e.kinetic += body.kinetic_energy(kin);
          e.elastic += body.elastic_energy(kin);
          if constexpr (Effects_::template has<Gravity>)
            e.gravity += body.gravity_potential(kin, gravity);
        },
        std::make_index_sequence<num_bodies>{});
    detail::for_each_index(
        [&](auto k) {
          constexpr int K = static_cast<int>(decltype(k)::value);
          using Kind = std::tuple_element_t<static_cast<std::size_t>(K), std::tuple<F...>>;
          if constexpr (std::is_same_v<typename Kind::effect, SpringDampers> &&
                        Effects_::template has<SpringDampers>) {
            const auto m = force_markers<K>(w);
            e.springs += Kind::energy(std::get<K>(forces).params, m.i, m.j);
          }
        },
        std::make_index_sequence<num_forces>{});
    return e;
  }

  /// The two markers of force element K, evaluated at the workspace's kinematics.
  template <int K>
  struct ForceMarkers {
    using Kind = std::tuple_element_t<static_cast<std::size_t>(K), std::tuple<F...>>;
    MarkerEval<Scalar, modes_of<Kind::body_i>> i;
    MarkerEval<Scalar, modes_of<Kind::body_j>> j;
  };
  template <int K>
  ForceMarkers<K> force_markers(const Workspace& w) const {
    using Kind = typename ForceMarkers<K>::Kind;
    const auto& inst = std::get<static_cast<std::size_t>(K)>(forces);
    ForceMarkers<K> m;
    m.i.evaluate(inst.marker_i, kinematics<Kind::body_i>(w));
    m.j.evaluate(inst.marker_j, kinematics<Kind::body_j>(w));
    return m;
  }

  /// Kinematics of body K (the ground for K = -1) in the workspace.
  template <int K>
  const BodyKinematics<Scalar, modes_of<K>>& kinematics(const Workspace& w) const {
    if constexpr (K < 0) {
      return w.ground.kinematics;
    } else {
      return std::get<static_cast<std::size_t>(K)>(w.kin);
    }
  }

  /// Name of joint k, for messages ("joint 3 (prismatic)").
  static const char* joint_kind_name(int k) {
    static constexpr const char* names[] = {J::name..., ""};
    return names[k];
  }
  /// Which joint owns constraint row r.
  static int joint_of_row(int r) {
    for (int k = 0; k < num_joints; ++k)
      if (r < joint_offset[static_cast<std::size_t>(k) + 1]) return k;
    return -1;
  }

 private:
  template <int K>
  void evaluate_joint(Scalar t, Workspace& w, bool rates) const {
    using Kind = std::tuple_element_t<static_cast<std::size_t>(K), std::tuple<J...>>;
    constexpr int bi = Kind::body_i, bj = Kind::body_j;
    constexpr int row0 = joint_offset[K];
    if (!joint_active_[static_cast<std::size_t>(K)]) {  // 0 = 0 (set_joint_active)
      constexpr int n = joint_equations<K>;
      w.jac.template middleRows<n>(row0).setZero();
      w.phi.template segment<n>(row0).setZero();
      w.phi_t.template segment<n>(row0).setZero();
      w.conv.template segment<n>(row0).setZero();
      return;
    }
    const auto& inst = std::get<static_cast<std::size_t>(K)>(joints);
    MarkerEval<Scalar, modes_of<bi>> mi;
    MarkerEval<Scalar, modes_of<bj>> mj;
    mi.evaluate(inst.marker_i, kinematics<bi>(w), rates, detail::joint_parts<Kind>::i);
    mj.evaluate(inst.marker_j, kinematics<bj>(w), rates, detail::joint_parts<Kind>::j);
    Kind::evaluate(inst.params, mi, mj, t, [&](int r, const auto& row) {
      const int i = row0 + r;
      w.phi(i) = row.phi;
      Scalar phi_t = row.phi_t, conv = row.conv;
      if constexpr (bi >= 0) {
        w.jac.template block<1, body_nv[bi]>(i, body_offset[bi]) = row.bi;
      } else if constexpr (Ground::moving) {
        phi_t += row.bi.dot(ground_velocity(w));
        conv += row.bi.dot(w.ground.acceleration);
      }
      if constexpr (bj >= 0) {
        w.jac.template block<1, body_nv[bj]>(i, body_offset[bj]) = row.bj;
      } else if constexpr (Ground::moving) {
        phi_t += row.bj.dot(ground_velocity(w));
        conv += row.bj.dot(w.ground.acceleration);
      }
      w.phi_t(i) = phi_t;
      w.conv(i) = conv;
    });
  }

  static constexpr std::array<bool, num_joints> all_joints_active() {
    std::array<bool, num_joints> a{};
    for (auto& x : a) x = true;
    return a;
  }
  std::array<bool, num_joints> joint_active_ = all_joints_active();
  std::uint64_t revision_ = 0;

  /// alpha times the transpose of a joint's rows restricted to body K's columns, copied so
  /// that the gram products below read it by contiguous columns (and vectorize).
  template <int K, class Rows>
  static Mat<Scalar, body_nv[K], Rows::RowsAtCompileTime> scaled_transpose(const Rows& rows,
                                                                           Scalar alpha) {
    return alpha * rows.template middleCols<body_nv[K]>(body_offset[K]).transpose();
  }

  /// Block (BI, BJ) += alpha B_I^T B_J, with scaled_i = alpha B_I^T. Coefficient-based product:
  /// these blocks are small and fixed-size, and the general matrix-matrix kernel spends longer
  /// packing them than multiplying.
  template <int BI, int BJ, class Scaled, class Rows, class M>
  static void add_gram_block(const Scaled& scaled_i, const Rows& rows, M& m) {
    m.template block<body_nv[BI], body_nv[BJ]>(body_offset[BI], body_offset[BJ]).noalias() +=
        scaled_i.lazyProduct(rows.template middleCols<body_nv[BJ]>(body_offset[BJ]));
  }

  static Vec6<Scalar> ground_velocity(const Workspace& w) {
    Vec6<Scalar> v;
    v << w.ground.kinematics.velocity, w.ground.kinematics.omega;
    return v;
  }

  template <int K>
  void apply_force_element(const State& s, Workspace& w) const {
    using Kind = std::tuple_element_t<static_cast<std::size_t>(K), std::tuple<F...>>;
    if constexpr (Effects_::template has<typename Kind::effect>) {
      constexpr int bi = Kind::body_i, bj = Kind::body_j;
      const auto& params = std::get<static_cast<std::size_t>(K)>(forces).params;
      const auto m = force_markers<K>(w);
      Vec3<Scalar> f;
      if constexpr (detail::force_state<Kind, Scalar>::stateful)
        f = Kind::force(params, std::get<static_cast<std::size_t>(K)>(s.force_states), s.t, m.i,
                        m.j);
      else
        f = Kind::force(params, m.i, m.j);
      if constexpr (bj >= 0)
        w.force.template segment<body_nv[bj]>(body_offset[bj]) += m.j.row_origin(f).transpose();
      if constexpr (bi >= 0)
        w.force.template segment<body_nv[bi]>(body_offset[bi]) -= m.i.row_origin(f).transpose();
    }
    (void)s;
    (void)w;
  }

  // Calls Kind::Op (commit or start) on each active stateful force element.
  template <bool Start>
  void update_force_states(State& s, const Workspace& w) const {
    detail::for_each_index(
        [&](auto k) {
          constexpr std::size_t K = decltype(k)::value;
          using Kind = std::tuple_element_t<K, std::tuple<F...>>;
          if constexpr (detail::force_state<Kind, Scalar>::stateful &&
                        Effects_::template has<typename Kind::effect>) {
            const auto& params = std::get<K>(forces).params;
            const auto m = force_markers<static_cast<int>(K)>(w);
            if constexpr (Start)
              Kind::start(params, std::get<K>(s.force_states), s.t, m.i, m.j);
            else
              Kind::commit(params, std::get<K>(s.force_states), s.t, m.i, m.j);
          }
        },
        std::make_index_sequence<num_forces>{});
    (void)s;
    (void)w;
  }
};

}  // namespace flexstress
