// Per-body kernels of a runtime model, compiled for the body's mode count.
//
// A model's structure (which bodies, joints and forces) is data, but the work per body stays
// fixed-size: a body with N modes is a BodyModel<Scalar, N> with its markers, and a table of
// function pointers (BodyKernels) instantiated for N does everything that depends on N:
// markers, mass matrix and forces, Jacobian columns, iteration-matrix blocks. Which counts get
// their own instantiation is a build choice (FLEXSTRESS_MODE_COUNTS); any other count up to
// max_runtime_modes runs the same code with N = Eigen::Dynamic in bounded storage.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "flexstress/core/euler_parameters.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/dynamics/body_model.hpp"
#include "flexstress/dynamics/marker.hpp"
#include "flexstress/model/joint_rows.hpp"

namespace flexstress {

/// A marker-slot flag beside the MarkerParts bits: evaluate its rates even in a Newton
/// iterate (force elements with damping read velocities).
inline constexpr unsigned marker_needs_rates = 16u;

/// What a body's dynamics stage includes (Model::effects, decided at finalize).
struct BodyEffects {
  bool gravity = false;
  bool quadratic_velocity = true;
  bool modal_damping = false;
};

/// A body with its markers, for a compile-time (or bounded runtime) mode count.
template <class Scalar, int N>
struct BodyHolder {
  BodyModel<Scalar, N> body;
  std::vector<Marker<Scalar, N>> markers;
};

/// The kernels of one mode count. `holder` is the BodyHolder<Scalar, N> they were made for;
/// q = [R, theta, p] and v = [R_dot, w, p_dot] point at the body's coordinates and velocities.
template <class Scalar>
struct BodyKernels {
  int fixed_modes;  ///< the N instantiated (Eigen::Dynamic: the bounded fallback)
  /// Evaluates markers [first, first + count) of the body (their parts[k] only).
  void (*markers)(const void* holder, const Scalar* q, const Scalar* v, const Mat3<Scalar>& a,
                  bool rates, const unsigned* parts, MarkerState<Scalar>* out);
  /// Mass matrix block (nv x nv, column-major) and the applied force Q_e - Q_v - K p - D p_dot.
  void (*dynamics)(const void* holder, const Scalar* q, const Scalar* v, const Mat3<Scalar>& a,
                   const BodyEffects& effects, const Vec3<Scalar>& gravity, Scalar* mass,
                   Scalar* force);
  /// Writes `count` Jacobian rows of marker `marker` (rows of a column-major block with leading
  /// dimension ld): [rigid | sum_v weight_v^T Psi_v].
  void (*jacobian_rows)(const void* holder, int marker, const RowSide<Scalar>* sides, int count,
                        Scalar* block, int ld);
  /// block += k_factor K + c_factor D on the modal block of an iteration matrix (column-major,
  /// leading dimension ld, pointing at the body's first modal row and column).
  void (*add_stiffness_damping)(const void* holder, Scalar k_factor, Scalar c_factor, bool damping,
                                Scalar* block, int ld);
  /// Kinetic energy 1/2 v^T M v, elastic energy 1/2 p^T K p, the gravity potential and the
  /// power p_dot^T D p_dot the modal damping takes out.
  void (*energies)(const void* holder, const Scalar* q, const Scalar* v, const Mat3<Scalar>& a,
                   const Vec3<Scalar>& gravity, Scalar* kinetic, Scalar* elastic, Scalar* potential,
                   Scalar* damping_power);
};

namespace detail {

template <class Scalar, int N>
struct BodyKernelImpl {
  using Holder = BodyHolder<Scalar, N>;
  using Body = BodyModel<Scalar, N>;
  using Kin = BodyKinematics<Scalar, N>;

  static const Holder& holder(const void* h) { return *static_cast<const Holder*>(h); }

  static void kinematics(const Body& b, const Scalar* q, const Scalar* v, const Mat3<Scalar>& a,
                         Kin& k) {
    const int n = b.modes();
    k.position = Eigen::Map<const Vec3<Scalar>>(q);
    k.rotation = a;
    k.velocity = Eigen::Map<const Vec3<Scalar>>(v);
    k.omega = Eigen::Map<const Vec3<Scalar>>(v + 3);
    if constexpr (N != 0) {
      k.p = Eigen::Map<const typename Body::VecN>(q + 7, n);
      k.p_dot = Eigen::Map<const typename Body::VecN>(v + 6, n);
    }
  }

  static void markers(const void* h, const Scalar* q, const Scalar* v, const Mat3<Scalar>& a,
                      bool rates, const unsigned* parts, MarkerState<Scalar>* out) {
    const Holder& hb = holder(h);
    Kin k;
    kinematics(hb.body, q, v, a, k);
    MarkerEval<Scalar, N> e;
    for (std::size_t m = 0; m < hb.markers.size(); ++m) {
      if (parts[m] == 0) continue;
      e.evaluate(hb.markers[m], k, rates || (parts[m] & marker_needs_rates) != 0,
                 parts[m] & MarkerParts::all);
      out[m].origin = e.origin;
      out[m].x = e.x;
      out[m].y = e.y;
      out[m].z = e.z;
      out[m].rotation = a;
    }
  }

  static void dynamics(const void* h, const Scalar* q, const Scalar* v, const Mat3<Scalar>& a,
                       const BodyEffects& effects, const Vec3<Scalar>& gravity, Scalar* mass,
                       Scalar* force) {
    const Body& body = holder(h).body;
    const int n = body.modes(), nv = 6 + n;
    Kin k;
    kinematics(body, q, v, a, k);
    typename Body::Terms terms;
    body.compute_terms(k, terms);
    Eigen::Map<Mat<Scalar, Body::nv, Body::nv>> m(mass, nv, nv);
    body.mass_matrix(k, terms, m);
    typename Body::VecV fb = Body::VecV::Zero(nv);
    if (effects.gravity) body.gravity_force(k, terms, gravity, fb);
    if (effects.quadratic_velocity) {
      typename Body::VecV qv;
      body.quadratic_velocity(k, terms, qv);
      fb -= qv;
    }
    if constexpr (N != 0) {
      auto fp = fb.template segment<N>(6, n);
      fp.noalias() -= body.modal_stiffness().lazyProduct(k.p);
      if (effects.modal_damping) fp.noalias() -= body.modal_damping().lazyProduct(k.p_dot);
    }
    Eigen::Map<typename Body::VecV>(force, nv) = fb;
  }

  static void jacobian_rows(const void* h, int marker, const RowSide<Scalar>* sides, int count,
                            Scalar* block, int ld) {
    const Holder& hb = holder(h);
    const int n = hb.body.modes();
    const auto& mk = hb.markers[static_cast<std::size_t>(marker)];
    const BodyVector<Scalar, N>* vectors[4] = {&mk.origin, &mk.x, &mk.y, &mk.z};
    Eigen::Map<Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>, 0, Eigen::OuterStride<>> b(
        block, count, 6 + n, Eigen::OuterStride<>(ld));
    for (int r = 0; r < count; ++r) {
      const RowSide<Scalar>& s = sides[r];
      b.row(r).template head<6>() = s.rigid;
      if constexpr (N != 0) {
        typename ModalSizes<Scalar, N>::RowN modal = ModalSizes<Scalar, N>::RowN::Zero(n);
        for (std::size_t v = 0; v < 4; ++v)
          if (!s.weight[v].isZero(0)) modal.noalias() += s.weight[v].transpose() * vectors[v]->psi;
        b.row(r).tail(n) = modal;
      }
    }
  }

  static void add_stiffness_damping(const void* h, Scalar k_factor, Scalar c_factor, bool damping,
                                    Scalar* block, int ld) {
    if constexpr (N != 0) {
      const Body& body = holder(h).body;
      const int n = body.modes();
      Eigen::Map<Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>, 0, Eigen::OuterStride<>> b(
          block, n, n, Eigen::OuterStride<>(ld));
      b += k_factor * body.modal_stiffness();
      if (damping) b += c_factor * body.modal_damping();
    } else {
      (void)h, (void)k_factor, (void)c_factor, (void)damping, (void)block, (void)ld;
    }
  }

  static void energies(const void* h, const Scalar* q, const Scalar* v, const Mat3<Scalar>& a,
                       const Vec3<Scalar>& gravity, Scalar* kinetic, Scalar* elastic,
                       Scalar* potential, Scalar* damping_power) {
    const Body& body = holder(h).body;
    Kin k;
    kinematics(body, q, v, a, k);
    *kinetic = body.kinetic_energy(k);
    *elastic = body.elastic_energy(k);
    *potential = body.gravity_potential(k, gravity);
    *damping_power = Scalar(0);
    if constexpr (N != 0) *damping_power = k.p_dot.dot(body.modal_damping() * k.p_dot);
  }

  static constexpr BodyKernels<Scalar> table{
      N, &markers, &dynamics, &jacobian_rows, &add_stiffness_damping, &energies};

  // ---- setup (may allocate) ----------------------------------------------------------------
  /// Adds a marker at `node` (-1: the body frame) with a rigid offset and axes; -1 if the body
  /// has no such node.
  static int add_marker(void* h, Index node, const Vec3<Scalar>& offset, const Mat3<Scalar>& axes) {
    Holder& hb = *static_cast<Holder*>(h);
    if (node >= hb.body.num_nodes() || node < -1) return -1;
    hb.markers.push_back(make_marker(hb.body, node, offset, axes));
    return static_cast<int>(hb.markers.size()) - 1;
  }
};

}  // namespace detail

/// The kernels instantiated for N modes (Eigen::Dynamic: any count, bounded storage).
template <class Scalar, int N>
const BodyKernels<Scalar>& body_kernels() {
  return detail::BodyKernelImpl<Scalar, N>::table;
}

}  // namespace flexstress
