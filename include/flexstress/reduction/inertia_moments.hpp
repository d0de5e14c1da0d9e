// The inertia shape integrals of a flexible body as data: what the FFRF equations read
// (reduction/inertia_integrals.hpp computes them from an FE model).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "flexstress/core/types.hpp"

namespace flexstress::reduction {

/// First and second moments of the fields u0 (index 0) and the modes (1..n).
struct InertiaIntegrals {
  Index num_modes = 0;
  double mass = 0.0;
  std::vector<Vector3d> first;   ///< S_a, a = 0..n
  std::vector<Matrix3d> second;  ///< Lambda_ab, row-major over (a, b), a, b = 0..n

  const Matrix3d& lambda(Index a, Index b) const {
    return second[static_cast<std::size_t>(a * (num_modes + 1) + b)];
  }
  Matrix3d& lambda(Index a, Index b) {
    return second[static_cast<std::size_t>(a * (num_modes + 1) + b)];
  }
};

}  // namespace flexstress::reduction
