// The data of geometric stiffening (ModelBuilder::add_geometric_stiffening): modal geometric
// stiffness matrices per unit inertial load case (computed by modal_geometric_stiffness.hpp; kept
// apart so that the dynamics layer does not include the FE solvers).
#pragma once

#include <array>

#include <Eigen/Core>

#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"

namespace flexstress::reduction {

/// The 12 unit load cases of the modal geometric stiffness, in this order.
enum class InertialLoadCase : int {
  accel_x,
  accel_y,
  accel_z,  ///< frame acceleration minus gravity, body axes
  alpha_x,
  alpha_y,
  alpha_z,  ///< angular acceleration, body axes
  spin_xx,
  spin_yy,
  spin_zz,  ///< diagonal of w w^T - |w|^2 1
  spin_xy,
  spin_yz,
  spin_zx,  ///< off-diagonal pairs of w w^T - |w|^2 1
};
inline constexpr int num_inertial_load_cases = 12;

struct ModalGeometricStiffness {
  Index num_modes = 0;
  /// G_j (num_modes x num_modes, symmetric) per InertialLoadCase.
  std::array<MatrixXd, num_inertial_load_cases> cases;

  /// The same data for the lowest k modes.
  Result<ModalGeometricStiffness> truncated(Index k) const {
    if (k < 0 || k > num_modes)
      return make_error(ErrorCode::size_mismatch, "geometric stiffness truncation to ", k,
                        " modes: the data has ", num_modes);
    ModalGeometricStiffness t;
    t.num_modes = k;
    for (int j = 0; j < num_inertial_load_cases; ++j)
      t.cases[static_cast<std::size_t>(j)] = cases[static_cast<std::size_t>(j)].topLeftCorner(k, k);
    return t;
  }
};

}  // namespace flexstress::reduction
