// Per-body kernels of a runtime model, compiled for the body's mode count.
//
// A model's structure (which bodies, joints and forces) is data, but the work per body stays
// fixed-size: a body with N modes is a BodyModel<Scalar, N> with its markers, and a table of
// function pointers (BodyKernels) instantiated for N does everything that depends on N:
// markers, mass matrix and forces, Jacobian columns, iteration-matrix blocks. Which counts get
// their own instantiation is a build choice (FLEXSTRESS_MODE_COUNTS); any other count up to
// max_runtime_modes runs the same code with N = Eigen::Dynamic in bounded storage.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <tuple>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "flexstress/core/binary_io.hpp"
#include "flexstress/core/euler_parameters.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/dynamics/body_model.hpp"
#include "flexstress/dynamics/marker.hpp"
#include "flexstress/model/joint_rows.hpp"
#include "flexstress/reduction/modal_body.hpp"
#include "flexstress/reduction/modal_geometric_stiffness_data.hpp"

namespace flexstress {

/// A marker-slot flag beside the MarkerParts bits: evaluate its rates even in a Newton
/// iterate (force elements with damping read velocities).
inline constexpr unsigned marker_needs_rates = 16u;

/// What a body's dynamics stage includes (Model::effects, decided at finalize).
struct BodyEffects {
  bool gravity = false;
  bool quadratic_velocity = true;
  bool modal_damping = false;
  /// K_G p under the body's own inertial and gravity loads (BodyModel::geometric_stiffness).
  bool geometric_stiffening = false;
};

/// A marker moved at run time (anchor_joint_at): its constant body-frame parts c of the origin
/// and the three axes replace the model's; its mode shapes stay.
template <class Scalar>
struct MarkerAnchor {
  bool active = false;
  std::array<Vec3<Scalar>, 4> c{Vec3<Scalar>::Zero(), Vec3<Scalar>::Zero(), Vec3<Scalar>::Zero(),
                                Vec3<Scalar>::Zero()};
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
  /// A hash of the body's data (mass properties, modal matrices, markers): checkpoints tell
  /// models apart by it. Setup-time (allocates).
  std::uint64_t (*fingerprint)(const void* holder);
  /// Evaluates the body's markers (their parts[k] only), moved where anchors[k] is active.
  void (*markers)(const void* holder, const Scalar* q, const Scalar* v, const Mat3<Scalar>& a,
                  bool rates, const unsigned* parts, const MarkerAnchor<Scalar>* anchors,
                  MarkerState<Scalar>* out);
  /// Evaluates one marker in full (all parts and rates), moved if `anchor` is active.
  void (*marker)(const void* holder, int marker, const Scalar* q, const Scalar* v,
                 const Mat3<Scalar>& a, const MarkerAnchor<Scalar>& anchor,
                 MarkerState<Scalar>& out);
  /// The constant parts c that put marker `marker` at the global origin and axes of `target`
  /// at coordinates q: c = A^T (value - R) - Psi p for the origin, A^T value - Psi p for axes.
  void (*anchor)(const void* holder, int marker, const Scalar* q, const Mat3<Scalar>& a,
                 const MarkerState<Scalar>& target, MarkerAnchor<Scalar>& out);
  /// Mass matrix block (nv x nv, column-major) and the applied force
  /// Q_e - Q_v - (K + K_G) p - D p_dot; with geometric stiffening K_G (modes x modes,
  /// column-major) is written to `geometric`, its load factors from the accelerations v_dot.
  void (*dynamics)(const void* holder, const Scalar* q, const Scalar* v, const Scalar* v_dot,
                   const Mat3<Scalar>& a, const BodyEffects& effects, const Vec3<Scalar>& gravity,
                   Scalar* mass, Scalar* force, Scalar* geometric);
  /// Writes `count` Jacobian rows of marker `marker` into a row-major block (count x nv):
  /// [rigid | sum_v weight_v^T Psi_v], v over the marker vectors in `parts` (MarkerParts).
  void (*jacobian_rows)(const void* holder, int marker, unsigned parts,
                        const RowSide<Scalar>* sides, int count, Scalar* block);
  // Block operations on the body's own columns (nv = 6 + modes), at the fixed size:
  /// y += M x with the body's mass block (column-major nv x nv).
  void (*mass_times)(int nv, const Scalar* mass, const Scalar* x, Scalar* y);
  /// y += B^T x for `count` rows of a row-major block (count x nv).
  void (*transpose_times)(int nv, const Scalar* rows, int count, const Scalar* x, Scalar* y);
  /// y += B x for `count` rows of a row-major block.
  void (*rows_times)(int nv, const Scalar* rows, int count, const Scalar* x, Scalar* y);
  /// s(body rows, other columns) += alpha B^T C for `count` rows of B (this body, row-major,
  /// count x nv) and C (another body's, count x nc): column by column of a column-major s with
  /// leading dimension ld.
  void (*add_gram)(int nv, const Scalar* rows, int count, const Scalar* other, int nc, Scalar alpha,
                   Scalar* s, int ld);
  /// block += k_factor (K + K_G) + c_factor D on the modal block of an iteration matrix
  /// (column-major, leading dimension ld, pointing at the body's first modal row and column);
  /// K_G from the last dynamics, or none if `geometric` is null.
  void (*add_stiffness_damping)(const void* holder, Scalar k_factor, Scalar c_factor, bool damping,
                                const Scalar* geometric, Scalar* block, int ld);
  /// Kinetic energy 1/2 v^T M v, elastic energy 1/2 p^T K p, the gravity potential and the
  /// power p_dot^T D p_dot the modal damping takes out.
  void (*energies)(const void* holder, const Scalar* q, const Scalar* v, const Mat3<Scalar>& a,
                   const Vec3<Scalar>& gravity, Scalar* kinetic, Scalar* elastic, Scalar* potential,
                   Scalar* damping_power);
  /// Linear momentum and angular momentum about the global origin (both global).
  void (*momentum)(const void* holder, const Scalar* q, const Scalar* v, const Mat3<Scalar>& a,
                   Vec3<Scalar>* linear, Vec3<Scalar>* angular);
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
                      bool rates, const unsigned* parts, const MarkerAnchor<Scalar>* anchors,
                      MarkerState<Scalar>* out) {
    markers_of(h, q, v, a, rates, parts, anchors, 0, static_cast<int>(holder(h).markers.size()),
               out);
  }
  /// Markers [first, last); parts, anchors and out point at marker `first`'s.
  static void markers_of(const void* h, const Scalar* q, const Scalar* v, const Mat3<Scalar>& a,
                         bool rates, const unsigned* parts, const MarkerAnchor<Scalar>* anchors,
                         int first, int last, MarkerState<Scalar>* out) {
    const Holder& hb = holder(h);
    Kin k;
    kinematics(hb.body, q, v, a, k);
    for (int index = first; index < last; ++index) {
      const unsigned p = parts[index - first];
      if (p == 0) continue;
      const bool with_rates = rates || (p & marker_needs_rates) != 0;
      const MarkerAnchor<Scalar>& anchor = anchors[index - first];
      const Marker<Scalar, N>& marker = hb.markers[static_cast<std::size_t>(index)];
      MarkerState<Scalar>& o = out[index - first];
      VectorEval<Scalar>* evaluated[4] = {&o.origin, &o.x, &o.y, &o.z};
      const BodyVector<Scalar, N>* vectors[4] = {&marker.origin, &marker.x, &marker.y, &marker.z};
      for (int v = 0; v < 4; ++v) {
        const bool wanted = (p & (1u << v)) != 0;
        if (anchor.active && wanted) {  // anchored where it was caught: c moved
          BodyVector<Scalar, N> moved = *vectors[v];
          moved.c = anchor.c[static_cast<std::size_t>(v)];
          evaluate_vector(moved, k, *evaluated[v], with_rates, true);
        } else {
          evaluate_vector(*vectors[v], k, *evaluated[v], with_rates, wanted);
        }
      }
      o.rotation = a;
    }
  }

  static std::uint64_t fingerprint(const void* h) {
    const Holder& hb = holder(h);
    binary::Writer w;
    const auto put = [&](const auto& m) {  // column by column, whatever the storage order
      for (Index c = 0; c < m.cols(); ++c)
        for (Index r = 0; r < m.rows(); ++r) w.put(m(r, c));
    };
    // The mass matrix at rest (p = 0, frame at the origin, not turned): mass, first moment,
    // inertia, and the modal couplings and modal mass.
    Kin k;
    k.position.setZero();
    k.rotation.setIdentity();
    k.velocity.setZero();
    k.omega.setZero();
    if constexpr (N != 0) {
      k.p = ModalSizes<Scalar, N>::VecN::Zero(hb.body.modes());
      k.p_dot = k.p;
    }
    typename Body::Terms terms;
    hb.body.compute_terms(k, terms);
    Mat<Scalar, Body::nv, Body::nv> mass(hb.body.velocities(), hb.body.velocities());
    hb.body.mass_matrix(k, terms, mass);
    put(mass);
    w.put(static_cast<std::int32_t>(hb.body.modes()));
    put(hb.body.modal_stiffness());
    put(hb.body.modal_damping());
    for (const auto& mk : hb.markers)
      for (const BodyVector<Scalar, N>* v : {&mk.origin, &mk.x, &mk.y, &mk.z}) {
        put(v->c);
        put(v->psi);
      }
    return binary::fnv1a(w.buffer.data(), w.buffer.size());
  }

  static void marker(const void* h, int index, const Scalar* q, const Scalar* v,
                     const Mat3<Scalar>& a, const MarkerAnchor<Scalar>& anchor,
                     MarkerState<Scalar>& out) {
    const unsigned parts = MarkerParts::all;
    markers_of(h, q, v, a, true, &parts, &anchor, index, index + 1, &out);
  }

  static void anchor(const void* h, int marker, const Scalar* q, const Mat3<Scalar>& a,
                     const MarkerState<Scalar>& target, MarkerAnchor<Scalar>& out) {
    const Holder& hb = holder(h);
    const auto& mk = hb.markers[static_cast<std::size_t>(marker)];
    const Vec3<Scalar> position = Eigen::Map<const Vec3<Scalar>>(q);
    const BodyVector<Scalar, N>* vectors[4] = {&mk.origin, &mk.x, &mk.y, &mk.z};
    const Vec3<Scalar>* values[4] = {&target.origin.value, &target.x.value, &target.y.value,
                                     &target.z.value};
    for (std::size_t v = 0; v < 4; ++v) {
      const Vec3<Scalar> global = v == 0 ? Vec3<Scalar>(*values[v] - position) : *values[v];
      Vec3<Scalar> local = a.transpose() * global;
      if constexpr (N != 0) {
        const int n = hb.body.modes();
        local -= vectors[v]->psi * Eigen::Map<const typename ModalSizes<Scalar, N>::VecN>(q + 7, n);
      }
      out.c[v] = local;
    }
    out.active = true;
  }

  static void dynamics(const void* h, const Scalar* q, const Scalar* v, const Scalar* v_dot,
                       const Mat3<Scalar>& a, const BodyEffects& effects,
                       const Vec3<Scalar>& gravity, Scalar* mass, Scalar* force,
                       Scalar* geometric) {
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
      if (effects.geometric_stiffening) {
        // The load factors of the current iterate: its accelerations (the integrator keeps
        // v_dot at the iterate), less gravity, and its angular velocity.
        const Eigen::Map<const typename Body::VecV> vd(v_dot, nv);
        Vec3<Scalar> a_g = a.transpose() * vd.template head<3>();
        if (effects.gravity) a_g.noalias() -= a.transpose() * gravity;
        typename Body::MatN kg;
        body.geometric_stiffness(a_g, vd.template segment<3>(3), k.omega, kg);
        fp.noalias() -= kg.lazyProduct(k.p);
        Eigen::Map<typename Body::MatN>(geometric, n, n) = kg;
      }
    }
    (void)v_dot, (void)geometric;
    Eigen::Map<typename Body::VecV>(force, nv) = fb;
  }

  static void jacobian_rows(const void* h, int marker, unsigned parts, const RowSide<Scalar>* sides,
                            int count, Scalar* block) {
    const Holder& hb = holder(h);
    const int n = hb.body.modes(), nv = 6 + n;
    const auto& mk = hb.markers[static_cast<std::size_t>(marker)];
    const BodyVector<Scalar, N>* vectors[4] = {&mk.origin, &mk.x, &mk.y, &mk.z};
    for (int r = 0; r < count; ++r) {
      const RowSide<Scalar>& s = sides[r];
      Scalar* row = block + r * nv;
      Eigen::Map<Eigen::Matrix<Scalar, 1, 6>> rigid(row);
      rigid = s.rigid;
      if constexpr (N != 0) {
        // g^T Psi as a sum of Psi's rows, over the vectors the row reads (the others carry
        // no weight): whole rows of the mode count at a time.
        Eigen::Map<typename ModalSizes<Scalar, N>::RowN> modal(row + 6, n);
        const unsigned used = parts & s.parts;
        bool first = true;
        for (unsigned v = 0; v < 4; ++v) {
          if (!(used & (1u << v))) continue;
          const auto& psi = vectors[v]->psi;
          const Vec3<Scalar>& g = s.weight[v];
          if (first)
            modal.noalias() = g(0) * psi.row(0) + g(1) * psi.row(1) + g(2) * psi.row(2);
          else
            modal.noalias() += g(0) * psi.row(0) + g(1) * psi.row(1) + g(2) * psi.row(2);
          first = false;
        }
        if (first) modal.setZero();
      }
    }
  }

  using VecV = typename ModalSizes<Scalar, N>::VecV;

  static void mass_times(int nv, const Scalar* mass, const Scalar* x, Scalar* y) {
    Eigen::Map<VecV> yb(y, nv);
    yb.noalias() += Eigen::Map<const Mat<Scalar, Body::nv, Body::nv>>(mass, nv, nv)
                        .lazyProduct(Eigen::Map<const VecV>(x, nv));
  }
  static void transpose_times(int nv, const Scalar* rows, int count, const Scalar* x, Scalar* y) {
    Eigen::Map<VecV> yb(y, nv);
    for (int r = 0; r < count; ++r)
      yb.noalias() += x[r] * Eigen::Map<const VecV>(rows + r * nv, nv);
  }
  static void rows_times(int nv, const Scalar* rows, int count, const Scalar* x, Scalar* y) {
    const Eigen::Map<const VecV> xb(x, nv);
    for (int r = 0; r < count; ++r) y[r] += Eigen::Map<const VecV>(rows + r * nv, nv).dot(xb);
  }
  /// Column k of alpha B^T C is the sum over the rows r of (alpha b_r) c_rk: summed at the
  /// body's fixed size and added to s once per column.
  static void add_gram(int nv, const Scalar* rows, int count, const Scalar* other, int nc,
                       Scalar alpha, Scalar* s, int ld) {
    eigen_assert(count <= max_gram_rows);
    if (count <= 0) return;
    using Rows = BoundedMat<Scalar, Body::nv, Eigen::Dynamic, ModalSizes<Scalar, N>::nv_bound,
                            max_gram_rows>;
    const Rows scaled = alpha * Eigen::Map<const Rows>(rows, nv, count);  // alpha B^T
    for (int k = 0; k < nc; ++k) {
      VecV column = scaled.col(0) * other[k];
      for (int r = 1; r < count; ++r) column.noalias() += scaled.col(r) * other[r * nc + k];
      Eigen::Map<VecV>(s + k * ld, nv) += column;
    }
  }
  static constexpr int max_gram_rows = 6;  // a joint's equations

  static void add_stiffness_damping(const void* h, Scalar k_factor, Scalar c_factor, bool damping,
                                    const Scalar* geometric, Scalar* block, int ld) {
    if constexpr (N != 0) {
      const Body& body = holder(h).body;
      const int n = body.modes();
      Eigen::Map<Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>, 0, Eigen::OuterStride<>> b(
          block, n, n, Eigen::OuterStride<>(ld));
      b += k_factor * body.modal_stiffness();
      if (damping) b += c_factor * body.modal_damping();
      if (geometric != nullptr)
        b += k_factor * Eigen::Map<const typename Body::MatN>(geometric, n, n);
    } else {
      (void)h, (void)k_factor, (void)c_factor, (void)damping, (void)geometric, (void)block,
          (void)ld;
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

  static void momentum(const void* h, const Scalar* q, const Scalar* v, const Mat3<Scalar>& a,
                       Vec3<Scalar>* linear, Vec3<Scalar>* angular) {
    const Body& body = holder(h).body;
    Kin k;
    kinematics(body, q, v, a, k);
    *linear = body.linear_momentum(k);
    *angular = body.angular_momentum(k);
  }

  static constexpr BodyKernels<Scalar> table{
      N,         &fingerprint,           &markers,    &marker,          &anchor,
      &dynamics, &jacobian_rows,         &mass_times, &transpose_times, &rows_times,
      &add_gram, &add_stiffness_damping, &energies,   &momentum};

  // ---- setup (may allocate) ----------------------------------------------------------------
  /// Adds a marker at `node` (-1: the body frame) with a rigid offset and axes; -1 if the body
  /// has no such node.
  static int add_marker(void* h, Index node, const Vec3<Scalar>& offset, const Mat3<Scalar>& axes) {
    Holder& hb = *static_cast<Holder*>(h);
    if (node >= hb.body.num_nodes() || node < -1) return -1;
    hb.markers.push_back(make_marker(hb.body, node, offset, axes));
    return static_cast<int>(hb.markers.size()) - 1;
  }
  /// Gives the body its modal geometric stiffness (reduction/modal_geometric_stiffness.hpp).
  static Status set_geometric_stiffness(void* h, const reduction::ModalGeometricStiffness& g) {
    if constexpr (N == 0) {
      (void)h, (void)g;
      return make_error(ErrorCode::invalid_argument, "a rigid body has no geometric stiffness");
    } else {
      return static_cast<Holder*>(h)->body.set_geometric_stiffness(g);
    }
  }
};

}  // namespace detail

/// The kernels instantiated for N modes (Eigen::Dynamic: any count, bounded storage).
template <class Scalar, int N>
const BodyKernels<Scalar>& body_kernels() {
  return detail::BodyKernelImpl<Scalar, N>::table;
}

namespace detail {

/// A body's holder and kernels (ModelBuilder).
template <class Scalar, int N>
std::pair<std::shared_ptr<void>, const BodyKernels<Scalar>*> make_holder(BodyModel<Scalar, N> b) {
  auto h = std::make_shared<BodyHolder<Scalar, N>>();
  h->body = std::move(b);
  return {h, &body_kernels<Scalar, N>()};
}

template <class Scalar, int N>
void adopt_flexible(const reduction::ModalBodyData& data, int modes, bool& done,
                    std::shared_ptr<void>& holder, const BodyKernels<Scalar>*& kernels,
                    Error& error) {
  if (done || modes != N) return;
  done = true;
  auto b = BodyModel<Scalar, N>::from_modal_data(data, N);
  if (!b) {
    error = b.error();
    return;
  }
  std::tie(holder, kernels) = make_holder<Scalar, N>(std::move(*b));
}

}  // namespace detail

}  // namespace flexstress
