// Per-step stress recovery, the paper's central idea made fast. With output rows R (outputs x
// 6 k, from StressOutputs) and boundary modes Phi_b (6 k x n, from boundary_modes), the outputs
// at modal coordinates p are
//   influence form:  y = R (Phi_b p)         (6 k n + outputs 6 k multiply-adds)
//   fused form:      y = (R Phi_b) p = F p   (n multiply-adds per output)
// Both are exact rewrites of the quasi-static sub-model solve; neither allocates. Non-linear
// measures (principal stresses) come from fused tensor outputs, one 3x3 eigenproblem each.
#pragma once

#include <cmath>

#include <Eigen/Core>

#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/fe/stress_measures.hpp"

namespace flexstress::stress {

template <int NModes, class Scalar = double>
class FusedStress {
 public:
  using ModalVector = Eigen::Matrix<Scalar, NModes, 1>;
  using Rows = Eigen::Matrix<Scalar, Eigen::Dynamic, NModes>;
  using Output = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

  /// F = R Phi_b with the first NModes columns of Phi_b. Fails if Phi_b has fewer columns or
  /// R and Phi_b do not fit.
  static Result<FusedStress> build(const MatrixXd& rows, const MatrixXd& boundary_modes) {
    if (rows.cols() != boundary_modes.rows())
      return make_error(ErrorCode::size_mismatch, "fused stress: ", rows.cols(),
                        " boundary DOFs in the output rows but ", boundary_modes.rows(),
                        " in the boundary modes");
    if (boundary_modes.cols() < NModes)
      return make_error(ErrorCode::size_mismatch, "fused stress: the host body has ",
                        boundary_modes.cols(), " modes, the template asks for ", NModes);
    FusedStress f;
    f.rows_ = (rows * boundary_modes.leftCols(NModes)).template cast<Scalar>();
    f.influence_ = rows.template cast<Scalar>();
    f.phi_b_ = boundary_modes.leftCols(NModes).template cast<Scalar>();
    f.u_b_.setZero(boundary_modes.rows());
    return f;
  }

  Index num_outputs() const { return rows_.rows(); }
  const Rows& rows() const { return rows_; }

  /// All outputs, fused form: out = F p. `out` must have num_outputs() entries.
  template <class Out>
  void evaluate(const ModalVector& p, Out&& out) const {
    out.noalias() = rows_ * p;
  }
  /// One output, fused form: a dot product of length NModes.
  Scalar evaluate(Index i, const ModalVector& p) const { return rows_.row(i).dot(p); }

  /// All outputs, influence form: u_b = Phi_b p, out = R u_b (the paper's route).
  template <class Out>
  void evaluate_by_influence(const ModalVector& p, Out&& out) const {
    u_b_.noalias() = phi_b_ * p;
    out.noalias() = influence_ * u_b_;
  }

  /// Six consecutive outputs starting at `first` (an add_tensor block) as a Voigt tensor.
  Vec6<Scalar> tensor(Index first, const ModalVector& p) const {
    return rows_.template middleRows<6>(first) * p;
  }

 private:
  Rows rows_;
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> influence_;
  Eigen::Matrix<Scalar, Eigen::Dynamic, NModes> phi_b_;
  mutable Output u_b_;  // scratch of the influence form, sized once
};

/// The principal stress whose direction is within `max_angle` (radians; IIW: 60 degrees) of
/// the unit vector n, the largest in magnitude if several are; if none is, the normal
/// component n^T sigma n.
template <class Scalar>
Scalar principal_near_direction(const Vec6<Scalar>& voigt, const Vec3<Scalar>& n,
                                Scalar max_angle) {
  const auto ps = fe::principal_stresses(voigt);
  const Scalar cos_limit = std::cos(max_angle);
  Scalar best = Scalar(0);
  bool found = false;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(ps.directions.col(k).dot(n)) < cos_limit) continue;
    if (!found || std::abs(ps.values(k)) > std::abs(best)) best = ps.values(k);
    found = true;
  }
  if (found) return best;
  return n.dot(fe::stress_tensor(voigt) * n);
}

}  // namespace flexstress::stress
