// Cross-section properties of a 3D beam, and the rectangular hollow section helper.
//
// Local beam axes: x along the beam, y and z the principal axes of the section. Bending in the
// local x-y plane (deflection v, rotation theta_z) is resisted by iz = integral of y^2 dA; bending
// in the x-z plane (w, theta_y) by iy = integral of z^2 dA.
#pragma once

#include <cmath>
#include <string>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/status.hpp"

namespace flexstress::fe {

/// Section properties (SI: m^2, m^4).
struct BeamSection {
  double area = 0.0;              ///< A
  double iy = 0.0;                ///< integral z^2 dA (bending in the x-z plane)
  double iz = 0.0;                ///< integral y^2 dA (bending in the x-y plane)
  double torsion_constant = 0.0;  ///< St. Venant J
  double shear_area_y = 0.0;  ///< Shear area for forces along y (Timoshenko); 0 = rigid in shear
  double shear_area_z = 0.0;  ///< Shear area for forces along z
  /// Outer half-dimensions, for fibre stresses at the section's extreme points (0 if unknown).
  double half_height_y = 0.0;
  double half_width_z = 0.0;

  /// Polar moment iy + iz (rotary inertia about the beam axis per unit density and length).
  double polar_moment() const { return iy + iz; }
};

/// Thin-walled rectangular hollow section with outer height h (along local y), outer width b
/// (along local z) and wall thickness t, sharp corners. Area and second moments are exact for
/// the sharp-cornered tube; the torsion constant is Bredt's thin-walled formula
/// J = 4 A_m^2 t / p_m (A_m, p_m: area enclosed by and perimeter of the wall's mid-line); the
/// shear areas are those of the webs, 2 (h - t) t for y and 2 (b - t) t for z.
/// Crane check (paper, Table 2): 150 x 100 x 4 mm gives A = 1.936e-3 m^2, iz = 6.17e-6 m^4,
/// iy = 3.29e-6 m^4.
FLEXSTRESS_PRECOMPUTE
BeamSection rectangular_hollow_section(double h, double b, double t) {
  BeamSection s;
  const double hi = h - 2.0 * t, bi = b - 2.0 * t;
  s.area = h * b - hi * bi;
  s.iz = (b * h * h * h - bi * hi * hi * hi) / 12.0;
  s.iy = (h * b * b * b - hi * bi * bi * bi) / 12.0;
  const double am = (h - t) * (b - t), pm = 2.0 * ((h - t) + (b - t));
  s.torsion_constant = 4.0 * am * am * t / pm;
  s.shear_area_y = 2.0 * (h - t) * t;
  s.shear_area_z = 2.0 * (b - t) * t;
  s.half_height_y = 0.5 * h;
  s.half_width_z = 0.5 * b;
  return s;
}

/// Solid rectangle h (along y) by b (along z); torsion constant by the series approximation
/// J = b' h'^3 (1/3 - 0.21 h'/b' (1 - h'^4 / (12 b'^4))) with h' the smaller side (Roark).
FLEXSTRESS_PRECOMPUTE
BeamSection rectangular_section(double h, double b) {
  BeamSection s;
  s.area = h * b;
  s.iz = b * h * h * h / 12.0;
  s.iy = h * b * b * b / 12.0;
  const double lo = h < b ? h : b, hi = h < b ? b : h;
  const double r = lo / hi;
  s.torsion_constant = hi * lo * lo * lo * (1.0 / 3.0 - 0.21 * r * (1.0 - r * r * r * r / 12.0));
  s.shear_area_y = s.shear_area_z = s.area * 5.0 / 6.0;
  s.half_height_y = 0.5 * h;
  s.half_width_z = 0.5 * b;
  return s;
}

/// Checks that A, iy, iz, J are positive and finite and shear areas non-negative.
FLEXSTRESS_PRECOMPUTE
Status validate(const BeamSection& s, const std::string& where) {
  const double positive[] = {s.area, s.iy, s.iz, s.torsion_constant};
  const char* names[] = {"area", "iy", "iz", "torsion constant"};
  for (int i = 0; i < 4; ++i)
    if (!std::isfinite(positive[i]) || !(positive[i] > 0.0))
      return make_error(ErrorCode::invalid_argument, where, ": section ", names[i],
                        " must be positive and finite, got ", positive[i]);
  if (!std::isfinite(s.shear_area_y) || s.shear_area_y < 0.0 || !std::isfinite(s.shear_area_z) ||
      s.shear_area_z < 0.0)
    return make_error(ErrorCode::invalid_argument, where,
                      ": shear areas must be non-negative and finite (0 disables shear)");
  return Status::success();
}

}  // namespace flexstress::fe
