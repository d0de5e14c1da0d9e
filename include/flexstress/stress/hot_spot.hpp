// Structural hot-spot stress by surface extrapolation to the weld toe (IIW recommendations,
// Hobbacher, IIW-2259-15 section 2.2.3; Niemi, Fricke & Maddox, IIW designer's guide).
//
// A rule is a set of read-out distances d_i from the toe along the plate surface, normal to the
// toe line; the hot-spot stress is the Lagrange extrapolation of the surface stresses s(d_i) to
// d = 0, sum_i w_i s(d_i). The weights are computed, not tabulated: the IIW's printed 1.67 and
// 0.67 are 5/3 and 2/3 rounded, and user read-out points (the paper reads 4 mm and 10 mm) use
// the same formula.
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"

namespace flexstress::stress {

enum class HotSpotRule {
  iiw_type_a_linear,     ///< fine mesh (element <= 0.4 t): 0.4 t, 1.0 t
  iiw_type_a_quadratic,  ///< fine mesh: 0.4 t, 0.9 t, 1.4 t
  iiw_type_a_coarse,     ///< higher-order elements of length t: 0.5 t, 1.5 t
  iiw_type_b_fine,       ///< transverse toe at a plate edge: 4, 8, 12 mm
  iiw_type_b_coarse,     ///< higher-order elements of 10 mm: 5, 15 mm
  user_points,           ///< the distances given by the user
};

inline const char* name(HotSpotRule r) {
  switch (r) {
    case HotSpotRule::iiw_type_a_linear: return "IIW type a, linear (0.4t, 1.0t)";
    case HotSpotRule::iiw_type_a_quadratic: return "IIW type a, quadratic (0.4t, 0.9t, 1.4t)";
    case HotSpotRule::iiw_type_a_coarse: return "IIW type a, coarse (0.5t, 1.5t)";
    case HotSpotRule::iiw_type_b_fine: return "IIW type b, fine (4, 8, 12 mm)";
    case HotSpotRule::iiw_type_b_coarse: return "IIW type b, coarse (5, 15 mm)";
    case HotSpotRule::user_points: return "user read-out points";
  }
  return "unknown";
}

/// Read-out distances (m) and extrapolation weights of a rule.
struct ExtrapolationRule {
  std::vector<double> distances;
  std::vector<double> weights;
};

/// Lagrange weights that extrapolate values at `distances` to distance 0: exact for
/// polynomials of degree distances.size() - 1. Fails for fewer than two points, repeated or
/// non-positive distances.
inline Result<ExtrapolationRule> extrapolation_to_toe(const std::vector<double>& distances) {
  if (distances.size() < 2 || distances.size() > 4)
    return make_error(ErrorCode::invalid_argument, "hot-spot rule: ", distances.size(),
                      " read-out points given, 2 to 4 needed");
  for (std::size_t i = 0; i < distances.size(); ++i) {
    if (!(distances[i] > 0.0) || !std::isfinite(distances[i]))
      return make_error(ErrorCode::invalid_argument, "hot-spot rule: read-out distance ", i, " is ",
                        distances[i], " m; distances from the toe must be positive");
    for (std::size_t j = 0; j < i; ++j)
      if (std::abs(distances[i] - distances[j]) <= 1e-12 * distances[i])
        return make_error(ErrorCode::invalid_argument, "hot-spot rule: read-out points ", j,
                          " and ", i, " are at the same distance ", distances[i], " m");
  }
  ExtrapolationRule r;
  r.distances = distances;
  for (std::size_t i = 0; i < distances.size(); ++i) {
    double w = 1.0;
    for (std::size_t j = 0; j < distances.size(); ++j)
      if (j != i) w *= (0.0 - distances[j]) / (distances[i] - distances[j]);
    r.weights.push_back(w);
  }
  return r;
}

/// The read-out distances and weights of an IIW rule for plate thickness t (m). For
/// HotSpotRule::user_points pass the distances in `user`.
inline Result<ExtrapolationRule> hot_spot_rule(HotSpotRule rule, double t,
                                               const std::vector<double>& user = {}) {
  const bool needs_t = rule == HotSpotRule::iiw_type_a_linear ||
                       rule == HotSpotRule::iiw_type_a_quadratic ||
                       rule == HotSpotRule::iiw_type_a_coarse;
  if (needs_t && !(t > 0.0 && std::isfinite(t)))
    return make_error(ErrorCode::invalid_argument, "hot-spot rule '", name(rule),
                      "': plate thickness ", t, " m must be positive");
  switch (rule) {
    case HotSpotRule::iiw_type_a_linear: return extrapolation_to_toe({0.4 * t, 1.0 * t});
    case HotSpotRule::iiw_type_a_quadratic:
      return extrapolation_to_toe({0.4 * t, 0.9 * t, 1.4 * t});
    case HotSpotRule::iiw_type_a_coarse: return extrapolation_to_toe({0.5 * t, 1.5 * t});
    case HotSpotRule::iiw_type_b_fine: return extrapolation_to_toe({0.004, 0.008, 0.012});
    case HotSpotRule::iiw_type_b_coarse: return extrapolation_to_toe({0.005, 0.015});
    case HotSpotRule::user_points: return extrapolation_to_toe(user);
  }
  return make_error(ErrorCode::invalid_argument, "hot-spot rule: unknown rule");
}

/// A hot spot on a plate surface: the toe point, the unit direction along the surface away
/// from the toe (normal to the toe line), and the rule.
struct HotSpotLocation {
  Vector3d toe = Vector3d::Zero();
  Vector3d away = Vector3d::UnitX();  ///< along the surface, normal to the toe line
  double thickness = 0.0;             ///< plate thickness t for the type a rules
  HotSpotRule rule = HotSpotRule::iiw_type_a_linear;
  std::vector<double> user_distances;  ///< for HotSpotRule::user_points
};

/// The physical read-out points of a hot spot, toe + d_i away.
inline Result<std::vector<Vector3d>> readout_points(const HotSpotLocation& h,
                                                    const ExtrapolationRule& r) {
  const double n = h.away.norm();
  if (!(n > 0.0) || !h.away.allFinite() || !h.toe.allFinite())
    return make_error(ErrorCode::invalid_argument,
                      "hot spot: the toe point and the direction away from the toe must be "
                      "finite and the direction non-zero");
  std::vector<Vector3d> pts;
  for (double d : r.distances) pts.push_back(h.toe + d * h.away / n);
  return pts;
}

}  // namespace flexstress::stress
