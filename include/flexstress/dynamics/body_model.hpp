// Body models of the floating frame of reference formulation (FFRF): rigid bodies and flexible
// bodies with a compile-time number of deformation modes, one implementation for both (a rigid
// body is a flexible body with zero modes). NModes = Eigen::Dynamic is a mode count chosen at
// run time (from_modal_data's `modes`), its per-step terms in storage bounded by
// max_runtime_modes: the same code, without the unrolling a fixed count allows.
//
// Coordinates: R (frame origin, global), Euler parameters theta, modal coordinates p.
// Velocities v = [R_dot (global); w (body frame); p_dot]. Equations of motion (FFRF reference
// sheet; Shabana, Dynamics of Multibody Systems, ch. 5):
//   M(theta, p) v_dot + Q_v + [0; 0; K p + D p_dot] + C_v^T lambda = Q_e
// with every p-dependent term built from the inertia integrals of the reduced FE model:
//   W_k(p) = Lambda_0k + sum_l p_l Lambda_lk = sum m u phi_k^T,      S(p) = S0 + S_Phi p,
//   U(p)   = Lambda_00 + sum_k p_k (Lambda_0k^T + W_k) = sum m u u^T, J = tr(U) 1 - U,
//   C_k    = sum m u x phi_k = -2 unskew(W_k),                      M_ff = [tr Lambda_kl],
//   M = [[m 1, -A skew(S), A S_Phi], [skew(S) A^T, J, C], [S_Phi^T A^T, C^T, M_ff]],
//   Q_v,R = A (w x (w x S) + 2 w x S_Phi p_dot),
//   Q_v,w = w x J w + 2 (w tr V - V^T w),  V = sum_k p_dot_k W_k,
//   Q_v,p = [w^T W_k w - |w|^2 tr W_k]_k + 2 G(w) p_dot,  G_kl = -2 w . unskew(Lambda_lk).
// Nothing is dropped for orthonormal modes: S_Phi and the antisymmetric part of Lambda_0k
// vanish then, and the general expressions simply evaluate to zero there.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include "flexstress/core/skew.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/dynamics/body_vector.hpp"
#include "flexstress/reduction/modal_body.hpp"
#include "flexstress/reduction/modal_geometric_stiffness_data.hpp"

namespace flexstress {

template <class Scalar, int NModes>
class BodyModel {
  static_assert(NModes >= 0 || NModes == Eigen::Dynamic,
                "BodyModel: the number of modes is a non-negative count or Eigen::Dynamic");
  using Sizes = ModalSizes<Scalar, NModes>;
  static constexpr int bound = Sizes::bound;
  /// Model constants that scale with N^2 or more: inline for a fixed count, on the heap (set
  /// up once) for a runtime one, whose bound would make them large.
  template <int Rows, int Cols>
  using ConstMat = Eigen::Matrix<Scalar, Rows, Cols>;

 public:
  using scalar_type = Scalar;
  static constexpr int num_modes = NModes;
  static constexpr int nv = size_sum(NModes, 6);  ///< velocities
  static constexpr int nq = size_sum(NModes, 7);  ///< coordinates (R, theta, p)
  using VecN = typename Sizes::VecN;
  using MatN = typename Sizes::MatN;
  using MatV = typename Sizes::MatV;
  using VecV = typename Sizes::VecV;
  using Mat3N = typename Sizes::Mat3N;
  using Kinematics = BodyKinematics<Scalar, NModes>;
  using Vector = BodyVector<Scalar, NModes>;

  BodyModel() = default;

  /// A rigid body (NModes == 0): mass, centre of mass and inertia tensor about the centre of
  /// mass, in the body frame.
  static BodyModel rigid(Scalar mass, const Vec3<Scalar>& center_of_mass,
                         const Mat3<Scalar>& inertia_about_com) {
    static_assert(NModes == 0, "BodyModel::rigid is for bodies with zero modes");
    BodyModel b;
    b.mass_ = mass;
    b.s0_ = mass * center_of_mass;
    // Inertia about the frame origin (parallel axis), then the equivalent second moment
    // Lambda_00 with tr(L) 1 - L = J.
    const Mat3<Scalar> j =
        inertia_about_com + mass * (center_of_mass.squaredNorm() * Mat3<Scalar>::Identity() -
                                    center_of_mass * center_of_mass.transpose());
    b.lambda00_ = Scalar(0.5) * j.trace() * Mat3<Scalar>::Identity() - j;
    return b;
  }

  /// A flexible body from reduced FE data, keeping its lowest NModes deformation modes (cast to
  /// Scalar); with NModes = Eigen::Dynamic its lowest `modes` (all of them if negative). Fails
  /// if the data has fewer modes than that, or a runtime count exceeds max_runtime_modes.
  static Result<BodyModel> from_modal_data(const reduction::ModalBodyData& d,
                                           Index modes = NModes) {
    if (NModes != Eigen::Dynamic && modes != NModes)
      return make_error(ErrorCode::size_mismatch, "FFRF body with ", NModes, " modes: asked for ",
                        modes);
    if (modes < 0) modes = d.num_modes;
    if (modes > bound)
      return make_error(ErrorCode::size_mismatch, "FFRF body with ", modes,
                        " modes: above the runtime bound of ", bound,
                        " (define FLEXSTRESS_MAX_MODES to raise it)");
    if (d.num_modes < modes)
      return make_error(ErrorCode::size_mismatch, "FFRF body with ", modes,
                        " modes: the modal data has only ", d.num_modes,
                        " (reduce with more interface DOFs or fixed-interface modes)");
    const int n = static_cast<int>(modes);
    BodyModel b;
    b.resize_modes(n);
    const auto& in = d.inertia;
    b.mass_ = static_cast<Scalar>(in.mass);
    b.s0_ = in.first[0].cast<Scalar>();
    b.lambda00_ = in.lambda(0, 0).cast<Scalar>();
    for (int k = 0; k < n; ++k) {
      b.s_phi_.col(k) = in.first[static_cast<std::size_t>(k + 1)].cast<Scalar>();
      b.lambda0_.template block<3, 3>(0, 3 * k) = in.lambda(0, k + 1).cast<Scalar>();
      for (int l = 0; l < n; ++l) {
        const Matrix3d& llk = in.lambda(l + 1, k + 1);
        // Column l of the (9N x N) map p -> vec(W_1..W_N) holds vec(Lambda_lk) at block k.
        for (int c = 0; c < 3; ++c)
          for (int r = 0; r < 3; ++r)
            b.w_map_(9 * k + 3 * c + r, l) = static_cast<Scalar>(llk(r, c));
        b.mass_ff_(k, l) = static_cast<Scalar>(in.lambda(k + 1, l + 1).trace());
        const Vector3d g = -2.0 * unskew(in.lambda(l + 1, k + 1));
        for (int a = 0; a < 3; ++a)
          b.gyro_[static_cast<std::size_t>(a)](k, l) = static_cast<Scalar>(g(a));
      }
    }
    if (d.modal_stiffness.rows() < n || d.modal_stiffness.cols() < n)
      return make_error(ErrorCode::size_mismatch, "FFRF body: modal stiffness matrix is ",
                        d.modal_stiffness.rows(), "x", d.modal_stiffness.cols(), ", need ", n);
    b.stiffness_ = d.modal_stiffness.topLeftCorner(n, n).cast<Scalar>();
    b.stiffness_ = (Scalar(0.5) * (b.stiffness_ + b.stiffness_.transpose())).eval();
    b.zeta_ = d.damping_ratios.head(n).cast<Scalar>();
    b.update_damping();
    b.node_positions_.resize(static_cast<std::size_t>(d.num_nodes()));
    for (Index n = 0; n < d.num_nodes(); ++n)
      b.node_positions_[static_cast<std::size_t>(n)] =
          d.node_positions[static_cast<std::size_t>(n)].cast<Scalar>();
    b.node_has_rotation_ = d.node_has_rotation;
    b.phi_r_ = d.phi_translation.leftCols(n).cast<Scalar>();
    b.phi_theta_ = d.phi_rotation.leftCols(n).cast<Scalar>();
    b.update_displacement_scale();
    return b;
  }

  // ---- constant data --------------------------------------------------------------------
  /// Number of deformation modes (NModes, or the runtime count).
  int modes() const { return static_cast<int>(stiffness_.rows()); }
  int velocities() const { return 6 + modes(); }
  Scalar mass() const { return mass_; }
  const Vec3<Scalar>& first_moment() const { return s0_; }
  /// Modal stiffness K (N x N; diag(omega^2) for orthonormal modes).
  const MatN& modal_stiffness() const { return stiffness_; }
  /// Modal damping D (N x N): D = M_ff^(1/2) 2 zeta Omega M_ff^(1/2) in the eigenbasis of
  /// (K, M_ff), which is diag(2 zeta omega) for orthonormal modes.
  const MatN& modal_damping() const { return damping_; }
  /// Sets the same modal damping ratio for every mode (no reallocation).
  void set_damping_ratio(Scalar zeta) {
    zeta_.setConstant(zeta);
    update_damping();
  }
  /// Highest angular frequency of the modes, sqrt of the largest eigenvalue of (K, M_ff) (0 for a
  /// rigid body).
  Scalar max_frequency() const { return max_frequency_; }
  /// Largest nodal translation (m) per unit of each modal coordinate, at least the mode's
  /// mass-weighted RMS translation: what turns a modal coordinate's Newton correction into
  /// metres (the implicit integrator's tolerance). Modal units depend on how the modes are
  /// normalized; metres do not.
  const VecN& modal_displacement_scale() const { return displacement_scale_; }
  Index num_nodes() const { return static_cast<Index>(node_positions_.size()); }
  const Vec3<Scalar>& node_position(Index n) const {
    return node_positions_[static_cast<std::size_t>(n)];
  }
  bool node_has_rotation(Index n) const {
    return node_has_rotation_[static_cast<std::size_t>(n)] != 0;
  }
  /// Translational and rotational mode shapes (3 x NModes) at a node.
  Mat3N phi_r(Index node) const { return phi_r_.template middleRows<3>(3 * node); }
  Mat3N phi_theta(Index node) const { return phi_theta_.template middleRows<3>(3 * node); }

  /// Modal geometric stiffness per unit inertial load case, for geometric stiffening
  /// (ModelBuilder::add_geometric_stiffening; reduction/modal_geometric_stiffness.hpp). Fails if
  /// the data has fewer modes than the body or is not finite.
  Status set_geometric_stiffness(const reduction::ModalGeometricStiffness& g) {
    const int n = modes();
    if (g.num_modes < n)
      return make_error(ErrorCode::size_mismatch, "geometric stiffness for a body with ", n,
                        " modes: the data has only ", g.num_modes);
    geometric_.resize(n, reduction::num_inertial_load_cases * n);
    for (int j = 0; j < reduction::num_inertial_load_cases; ++j) {
      const MatrixXd& c = g.cases[static_cast<std::size_t>(j)];
      if (c.rows() < n || c.cols() < n || !c.allFinite())
        return make_error(ErrorCode::invalid_argument, "geometric stiffness: load case ", j, " is ",
                          c.rows(), "x", c.cols(), " or not finite (need ", n, "x", n, ")");
      geometric_.template middleCols<NModes>(n * j, n) =
          c.topLeftCorner(n, n).template cast<Scalar>();
    }
    return Status::success();
  }
  bool has_geometric_stiffness() const { return geometric_.cols() > 0; }
  /// K_G = sum_j c_j G_j for the body's rigid-body inertial load: frame acceleration minus
  /// gravity a_g and angular acceleration alpha (body axes), angular velocity w (body). Zero if
  /// no geometric stiffness was set.
  void geometric_stiffness(const Vec3<Scalar>& a_g, const Vec3<Scalar>& alpha,
                           const Vec3<Scalar>& w, MatN& kg) const {
    kg.setZero(modes(), modes());
    if constexpr (NModes != 0) {
      if (!has_geometric_stiffness()) return;
      const Scalar w2 = w.squaredNorm();
      const Scalar c[reduction::num_inertial_load_cases] = {
          a_g(0),           a_g(1),      a_g(2),           alpha(0),
          alpha(1),         alpha(2),    w(0) * w(0) - w2, w(1) * w(1) - w2,
          w(2) * w(2) - w2, w(0) * w(1), w(1) * w(2),      w(2) * w(0)};
      for (int j = 0; j < reduction::num_inertial_load_cases; ++j)
        if (c[j] != Scalar(0))
          kg += c[j] * geometric_.template middleCols<NModes>(modes() * j, modes());
    }
  }

  // ---- body vectors (markers) -------------------------------------------------------------
  /// A point of the body: for a flexible body at a node (plus a rigid offset carried by the
  /// node's rotation), for a rigid body anywhere (node < 0, `offset` = position).
  Vector point(Index node, const Vec3<Scalar>& offset = Vec3<Scalar>::Zero()) const {
    Vector v;
    v.psi.setZero(3, modes());
    v.is_point = true;
    if (node < 0) {
      v.c = offset;
      return v;
    }
    v.c = node_position(node) + offset;
    if constexpr (NModes != 0) v.psi = phi_r(node) - skew(offset) * phi_theta(node);
    return v;
  }
  /// A direction e0 (body frame) at a node, turned by the node's deformation rotation.
  Vector direction(Index node, const Vec3<Scalar>& e0) const {
    Vector v;
    v.psi.setZero(3, modes());
    v.is_point = false;
    v.c = e0;
    if constexpr (NModes != 0)
      if (node >= 0) v.psi = -skew(e0) * phi_theta(node);
    return v;
  }

  // ---- state-dependent terms ---------------------------------------------------------------
  /// Per-step quantities shared by the mass matrix and the force terms.
  struct Terms {
    Vec3<Scalar> s;                                                  ///< S(p)
    BoundedMat<Scalar, 3, size_product(NModes, 3), 3, 3 * bound> w;  ///< [W_1 ... W_N]
    Mat3<Scalar> j;  ///< J(p), about the frame origin, body frame
    Mat3N c;         ///< C(p)
  };

  void compute_terms(const Kinematics& k, Terms& t) const {
    if constexpr (NModes == 0) {
      t.s = s0_;
      t.j = lambda00_.trace() * Mat3<Scalar>::Identity() - lambda00_;
    } else {
      const int n = modes();
      t.s = s0_ + s_phi_ * k.p;
      const BoundedMat<Scalar, size_product(NModes, 9), 1, 9 * bound, 1> wv =
          w_map_.lazyProduct(k.p);
      t.w.resize(3, 3 * n);
      t.c.resize(3, n);
      Mat3<Scalar> u = lambda00_;
      for (int m = 0; m < n; ++m) {
        const Eigen::Map<const Mat3<Scalar>> dw(wv.data() + 9 * m);
        auto wm = t.w.template block<3, 3>(0, 3 * m);
        wm = lambda0_.template block<3, 3>(0, 3 * m) + dw;
        u += k.p(m) * (lambda0_.template block<3, 3>(0, 3 * m).transpose() + wm);
        t.c.col(m) = Scalar(-2) * unskew(Mat3<Scalar>(wm));
      }
      t.j = u.trace() * Mat3<Scalar>::Identity() - u;
    }
  }

  /// Mass matrix (nv x nv), symmetric.
  /// M is MatV or a map of nv x nv storage.
  template <class M>
  void mass_matrix(const Kinematics& k, const Terms& t, M& m) const {
    const int n = modes();
    if constexpr (NModes == Eigen::Dynamic) m.resize(6 + n, 6 + n);
    const Mat3<Scalar>& a = k.rotation;
    m.template topLeftCorner<3, 3>() = mass_ * Mat3<Scalar>::Identity();
    const Mat3<Scalar> r_w = -a * skew(t.s);
    m.template block<3, 3>(0, 3) = r_w;
    m.template block<3, 3>(3, 0) = r_w.transpose();
    m.template block<3, 3>(3, 3) = t.j;
    if constexpr (NModes != 0) {
      const Mat3N r_p = a * s_phi_;
      m.template block<3, NModes>(0, 6, 3, n) = r_p;
      m.template block<NModes, 3>(6, 0, n, 3) = r_p.transpose();
      m.template block<3, NModes>(3, 6, 3, n) = t.c;
      m.template block<NModes, 3>(6, 3, n, 3) = t.c.transpose();
      m.template block<NModes, NModes>(6, 6, n, n) = mass_ff_;
    }
  }

  /// Quadratic velocity vector Q_v (added on the left-hand side).
  void quadratic_velocity(const Kinematics& k, const Terms& t, VecV& q) const {
    const Vec3<Scalar>& w = k.omega;
    Vec3<Scalar> qr = w.cross(w.cross(t.s));
    Vec3<Scalar> qw = w.cross(t.j * w);
    const int n = modes();
    if constexpr (NModes == Eigen::Dynamic) q.resize(6 + n);
    if constexpr (NModes != 0) {
      qr += Scalar(2) * w.cross(Vec3<Scalar>(s_phi_ * k.p_dot));
      Mat3<Scalar> v = Mat3<Scalar>::Zero();
      for (int m = 0; m < n; ++m) v += k.p_dot(m) * t.w.template block<3, 3>(0, 3 * m);
      qw += Scalar(2) * (w * v.trace() - v.transpose() * w);
      const Scalar w2 = w.squaredNorm();
      MatN g = w(0) * gyro_[0] + w(1) * gyro_[1] + w(2) * gyro_[2];
      VecN qp = Scalar(2) * g.lazyProduct(k.p_dot);
      for (int m = 0; m < n; ++m) {
        const auto wm = t.w.template block<3, 3>(0, 3 * m);
        qp(m) += w.dot(wm * w) - w2 * wm.trace();
      }
      q.template segment<NModes>(6, n) = qp;
    }
    q.template head<3>() = k.rotation * qr;
    q.template segment<3>(3) = qw;
  }

  /// Generalized gravity force (added on the right-hand side): [m g; S x A^T g; S_Phi^T A^T g].
  void gravity_force(const Kinematics& k, const Terms& t, const Vec3<Scalar>& g, VecV& q) const {
    const Vec3<Scalar> gb = k.rotation.transpose() * g;
    if constexpr (NModes == Eigen::Dynamic) q.resize(6 + modes());
    q.template head<3>() = mass_ * g;
    q.template segment<3>(3) = t.s.cross(gb);
    if constexpr (NModes != 0) q.template segment<NModes>(6, modes()) = s_phi_.transpose() * gb;
  }

  /// Kinetic energy 1/2 v^T M v.
  Scalar kinetic_energy(const Kinematics& k) const {
    Terms t;
    compute_terms(k, t);
    MatV m;
    mass_matrix(k, t, m);
    VecV v(6 + modes());
    v << k.velocity, k.omega, k.p_dot;
    return Scalar(0.5) * v.dot(m * v);
  }
  /// Elastic energy 1/2 p^T K p.
  Scalar elastic_energy(const Kinematics& k) const {
    if constexpr (NModes == 0) {
      return Scalar(0);
    } else {
      return Scalar(0.5) * k.p.dot(stiffness_ * k.p);
    }
  }
  /// Potential of uniform gravity g: -g . (m R + A S(p)).
  Scalar gravity_potential(const Kinematics& k, const Vec3<Scalar>& g) const {
    Terms t;
    compute_terms(k, t);
    return -g.dot(mass_ * k.position + k.rotation * t.s);
  }
  /// Linear momentum m R_dot + A (w x S + S_Phi p_dot), global.
  Vec3<Scalar> linear_momentum(const Kinematics& k) const {
    Terms t;
    compute_terms(k, t);
    Vec3<Scalar> body = k.omega.cross(t.s);
    if constexpr (NModes != 0) body += s_phi_ * k.p_dot;
    return mass_ * k.velocity + k.rotation * body;
  }
  /// Angular momentum about the global origin: R x L + A (S x A^T R_dot + J w + C p_dot).
  Vec3<Scalar> angular_momentum(const Kinematics& k) const {
    Terms t;
    compute_terms(k, t);
    Vec3<Scalar> body =
        t.s.cross(Vec3<Scalar>(k.rotation.transpose() * k.velocity)) + t.j * k.omega;
    if constexpr (NModes != 0) body += t.c * k.p_dot;
    return k.position.cross(linear_momentum(k)) + k.rotation * body;
  }

 private:
  /// Modal displacement scale: the largest nodal translation of each mode, but at least its
  /// mass-weighted RMS translation sqrt(M_ff,kk / m) (for a mode that moves no node, such as the
  /// torsion of a beam about its axis, the first is zero).
  void update_displacement_scale() {
    for (int k = 0; k < modes(); ++k) {
      Scalar largest = Scalar(0);
      for (Index n = 0; n < phi_r_.rows() / 3; ++n)
        largest = std::max(largest, phi_r_.template middleRows<3>(3 * n).col(k).norm());
      if (mass_ > Scalar(0) && mass_ff_(k, k) > Scalar(0))
        largest = std::max(largest, std::sqrt(mass_ff_(k, k) / mass_));
      displacement_scale_(k) = largest > Scalar(0) ? largest : Scalar(1);
    }
  }

  /// D from the damping ratios in the modal basis of (K, M_ff): with K Z = M_ff Z W^2 and
  /// Z^T M_ff Z = 1, D = M_ff Z (2 zeta W) Z^T M_ff. Also records the highest frequency.
  void update_damping() {
    if constexpr (NModes != 0) {
      if (modes() == 0) return;
      // Setup only: solved in dynamic double precision (one Eigen instantiation for every N).
      const MatrixXd k = stiffness_.template cast<double>(), m = mass_ff_.template cast<double>();
      Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> es(k, m);
      const VectorXd w = es.eigenvalues().cwiseMax(0.0).cwiseSqrt();
      max_frequency_ = static_cast<Scalar>(w.maxCoeff());
      const MatrixXd mz = m * es.eigenvectors();
      const VectorXd c = 2.0 * zeta_.template cast<double>().cwiseProduct(w);
      damping_ = (mz * c.asDiagonal() * mz.transpose()).template cast<Scalar>();
    }
  }

  /// Sizes every mode-dependent member for n modes, zeroed (setup).
  void resize_modes(int n) {
    s_phi_.setZero(3, n);
    lambda0_.setZero(3, 3 * n);
    w_map_.setZero(9 * n, n);
    mass_ff_.setZero(n, n);
    displacement_scale_.setOnes(n);
    for (auto& g : gyro_) g.setZero(n, n);
    stiffness_.setZero(n, n);
    damping_.setZero(n, n);
    zeta_.setZero(n);
  }

  static constexpr int n0 = NModes == Eigen::Dynamic ? 0 : NModes;  ///< before resize_modes
  Scalar mass_ = Scalar(0);
  Vec3<Scalar> s0_ = Vec3<Scalar>::Zero();
  Mat3<Scalar> lambda00_ = Mat3<Scalar>::Zero();
  Mat3N s_phi_ = Mat3N::Zero(3, n0);
  ConstMat<3, size_product(NModes, 3)> lambda0_ = decltype(lambda0_)::Zero(3, 3 * n0);
  ConstMat<size_product(NModes, 9), NModes> w_map_ = decltype(w_map_)::Zero(9 * n0, n0);
  MatN mass_ff_ = MatN::Zero(n0, n0);
  VecN displacement_scale_ = VecN::Ones(n0);
  std::array<ConstMat<NModes, NModes>, 3> gyro_{ConstMat<NModes, NModes>::Zero(n0, n0),
                                                ConstMat<NModes, NModes>::Zero(n0, n0),
                                                ConstMat<NModes, NModes>::Zero(n0, n0)};
  MatN stiffness_ = MatN::Zero(n0, n0);
  MatN damping_ = MatN::Zero(n0, n0);
  VecN zeta_ = VecN::Zero(n0);
  Scalar max_frequency_ = Scalar(0);
  std::vector<Vec3<Scalar>> node_positions_;
  std::vector<unsigned char> node_has_rotation_;
  Eigen::Matrix<Scalar, Eigen::Dynamic, NModes> phi_r_;
  Eigen::Matrix<Scalar, Eigen::Dynamic, NModes> phi_theta_;
  Eigen::Matrix<Scalar, NModes, Eigen::Dynamic> geometric_;  ///< [G_1 ... G_12], or empty
};

/// FFRFBody<10> is a flexible body with 10 modes in double; FFRFBody<10, float> in float.
template <int NModes, class Scalar = double>
using FFRFBody = BodyModel<Scalar, NModes>;
/// A rigid body (no modes).
template <class Scalar = double>
using RigidBodyT = BodyModel<Scalar, 0>;
using RigidBody = BodyModel<double, 0>;

}  // namespace flexstress
