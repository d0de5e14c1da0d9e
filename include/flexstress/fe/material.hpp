// Isotropic linear-elastic material and its elasticity matrix.
#pragma once

#include <cmath>
#include <string>

#include <Eigen/Core>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/status.hpp"

namespace flexstress::fe {

/// Isotropic linear-elastic material (SI units: Pa, -, kg/m^3).
struct Material {
  double youngs_modulus = 210e9;
  double poissons_ratio = 0.3;
  double density = 7850.0;

  double shear_modulus() const { return youngs_modulus / (2.0 * (1.0 + poissons_ratio)); }
};

/// Structural steel as in the paper's Table 2 (E = 210 GPa, nu = 0.3, rho = 7850 kg/m^3).
inline Material steel() {
  return Material{210e9, 0.3, 7850.0};
}

/// Checks that E > 0, -1 < nu < 0.5, rho >= 0 and all are finite. `where` names the material
/// in the message (e.g. "material 2").
FLEXSTRESS_PRECOMPUTE
Status validate(const Material& m, const std::string& where) {
  if (!std::isfinite(m.youngs_modulus) || !(m.youngs_modulus > 0.0))
    return make_error(ErrorCode::invalid_argument, where,
                      ": Young's modulus must be positive and finite, got ", m.youngs_modulus);
  if (!std::isfinite(m.poissons_ratio) || !(m.poissons_ratio > -1.0) || !(m.poissons_ratio < 0.5))
    return make_error(ErrorCode::invalid_argument, where,
                      ": Poisson's ratio must lie in (-1, 0.5), got ", m.poissons_ratio);
  if (!std::isfinite(m.density) || m.density < 0.0)
    return make_error(ErrorCode::invalid_argument, where,
                      ": density must be non-negative and finite, got ", m.density);
  return Status::success();
}

/// 6x6 isotropic elasticity matrix D, sigma = D eps, in Voigt order
/// (xx, yy, zz, xy, yz, zx) with engineering shear strains (gamma = 2 eps).
FLEXSTRESS_PRECOMPUTE
Eigen::Matrix<double, 6, 6> elasticity_matrix(const Material& m) {
  const double e = m.youngs_modulus, nu = m.poissons_ratio;
  const double lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  const double mu = e / (2.0 * (1.0 + nu));
  Eigen::Matrix<double, 6, 6> d = Eigen::Matrix<double, 6, 6>::Zero();
  d.topLeftCorner<3, 3>().setConstant(lambda);
  d.topLeftCorner<3, 3>().diagonal().array() += 2.0 * mu;
  d.bottomRightCorner<3, 3>().diagonal().setConstant(mu);
  return d;
}

}  // namespace flexstress::fe
