// Interaction checks for combined normal and shear stress ranges at one detail.
//
// EN 1993-1-9:2005 section 8(3), eq. (8.3), for equivalent ranges at 2e6 cycles:
//   (gamma_Ff Delta_sigma_E,2 / (Delta_sigma_C / gamma_Mf))^3
//     + (gamma_Ff Delta_tau_E,2 / (Delta_tau_C / gamma_Mf))^5 <= 1.
// Each term is the Miner damage of its equivalent range on the single-slope line through the
// detail category (m = 3 normal, m = 5 shear), so eq. (8.3) is the damage sum D_sigma + D_tau <= 1
// (en1993_interaction_from_damage), with D_sigma, D_tau from miner_damage on the curves of
// sn_curve.hpp (their equivalent ranges at 2e6 are equivalent_stress_range).
//
// IIW (Hobbacher, IIW-2259-15 chapter 4, combined normal and shear stress; the Gough-Pollard
// ellipse): for normal and shear ranges
// Delta_sigma, Delta_tau and the design resistances Delta_sigma_R, Delta_tau_R at the same
// number of cycles,
//   (Delta_sigma / Delta_sigma_R)^2 + (Delta_tau / Delta_tau_R)^2 <= CV.
// CV (comparison value) is 1.0 for proportional loading; IIW gives smaller values for
// non-proportional loading and for variable amplitude. They are not built in: pass the CV of
// your case (docs/fatigue.md lists the values and what was verified).
// In damage form (iiw_interaction_from_damage) each ratio is replaced by the one of its
// damage-equivalent range on a single slope m: Delta_sigma / Delta_sigma_R = D^(1/m), giving
// D_sigma^(2/m_sigma) + D_tau^(2/m_tau) <= CV. This is the same check written in damages (our
// derivation, exact for ranges on the slope m), not a separate IIW formula.
#pragma once

#include <cmath>

#include "flexstress/core/status.hpp"
#include "flexstress/fatigue/sn_curve.hpp"

namespace flexstress::fatigue {

/// Outcome of an interaction check: value = normal_term + shear_term, passed when
/// value <= limit.
template <class Scalar>
struct InteractionCheck {
  Scalar normal_term = Scalar(0);
  Scalar shear_term = Scalar(0);
  Scalar value = Scalar(0);
  Scalar limit = Scalar(1);
  bool passed() const noexcept { return value <= limit; }
  /// value / limit: above 1 fails.
  Scalar utilization() const noexcept { return value / limit; }
};

namespace detail {
template <class Scalar>
Status check_non_negative(Scalar x, const char* name) {
  if (!std::isfinite(x) || x < Scalar(0))
    return make_error(ErrorCode::invalid_argument, name, " must be finite and >= 0, got ", x);
  return Status::success();
}
template <class Scalar>
Status check_positive(Scalar x, const char* name) {
  if (!std::isfinite(x) || !(x > Scalar(0)))
    return make_error(ErrorCode::invalid_argument, name, " must be positive, got ", x);
  return Status::success();
}
template <class Scalar>
Status check_cv(Scalar cv) {
  if (!std::isfinite(cv) || !(cv > Scalar(0)) || cv > Scalar(1))
    return make_error(ErrorCode::invalid_argument, "comparison value CV must be in (0, 1], got ",
                      cv);
  return Status::success();
}
}  // namespace detail

/// EN 1993-1-9 eq. (8.3) with equivalent ranges at 2e6 cycles (MPa) and the detail categories
/// of the normal and shear curves. Errors: negative ranges, non-positive categories or factors.
template <class Scalar>
Result<InteractionCheck<Scalar>> en1993_interaction(Scalar delta_sigma_e2, Scalar delta_tau_e2,
                                                    Scalar delta_sigma_c, Scalar delta_tau_c,
                                                    Scalar gamma_ff = Scalar(1),
                                                    Scalar gamma_mf = Scalar(1)) {
  for (Status s :
       {detail::check_non_negative(delta_sigma_e2, "Delta_sigma_E,2"),
        detail::check_non_negative(delta_tau_e2, "Delta_tau_E,2"),
        detail::check_positive(delta_sigma_c, "Delta_sigma_C"),
        detail::check_positive(delta_tau_c, "Delta_tau_C"),
        detail::check_positive(gamma_ff, "gamma_Ff"), detail::check_positive(gamma_mf, "gamma_Mf")})
    if (!s) return s.error();
  using std::pow;
  InteractionCheck<Scalar> r;
  r.normal_term = pow(gamma_ff * delta_sigma_e2 / (delta_sigma_c / gamma_mf), Scalar(3));
  r.shear_term = pow(gamma_ff * delta_tau_e2 / (delta_tau_c / gamma_mf), Scalar(5));
  r.value = r.normal_term + r.shear_term;
  r.limit = Scalar(1);
  return r;
}

/// EN 1993-1-9 eq. (8.3) in damage form: D_sigma + D_tau <= 1, the damages computed with
/// gamma_Ff and gamma_Mf included (DamageModel). Errors: a negative or non-finite damage.
template <class Scalar>
Result<InteractionCheck<Scalar>> en1993_interaction_from_damage(Scalar d_sigma, Scalar d_tau) {
  for (Status s :
       {detail::check_non_negative(d_sigma, "D_sigma"), detail::check_non_negative(d_tau, "D_tau")})
    if (!s) return s.error();
  InteractionCheck<Scalar> r;
  r.normal_term = d_sigma;
  r.shear_term = d_tau;
  r.value = d_sigma + d_tau;
  r.limit = Scalar(1);
  return r;
}

/// IIW Gough-Pollard check with ranges and design resistances at the same cycle count (MPa).
/// Errors: negative ranges, non-positive resistances, CV outside (0, 1].
template <class Scalar>
Result<InteractionCheck<Scalar>> iiw_interaction(Scalar delta_sigma, Scalar delta_tau,
                                                 Scalar delta_sigma_r, Scalar delta_tau_r,
                                                 Scalar cv) {
  for (Status s : {detail::check_non_negative(delta_sigma, "Delta_sigma"),
                   detail::check_non_negative(delta_tau, "Delta_tau"),
                   detail::check_positive(delta_sigma_r, "Delta_sigma_R"),
                   detail::check_positive(delta_tau_r, "Delta_tau_R"), detail::check_cv(cv)})
    if (!s) return s.error();
  InteractionCheck<Scalar> r;
  const Scalar a = delta_sigma / delta_sigma_r;
  const Scalar b = delta_tau / delta_tau_r;
  r.normal_term = a * a;
  r.shear_term = b * b;
  r.value = r.normal_term + r.shear_term;
  r.limit = cv;
  return r;
}

/// IIW Gough-Pollard check at n cycles, the resistances read on the normal and shear curves
/// (characteristic) and divided by gamma_Mf. Errors: as iiw_interaction, n not positive.
template <class Scalar>
Result<InteractionCheck<Scalar>> iiw_interaction(Scalar delta_sigma, Scalar delta_tau, Scalar n,
                                                 const SnCurve<Scalar>& normal_curve,
                                                 const SnCurve<Scalar>& shear_curve, Scalar cv,
                                                 Scalar gamma_mf = Scalar(1)) {
  for (Status s :
       {detail::check_positive(n, "cycle count"), detail::check_positive(gamma_mf, "gamma_Mf")})
    if (!s) return s.error();
  return iiw_interaction(delta_sigma, delta_tau, normal_curve.stress_range_at(n) / gamma_mf,
                         shear_curve.stress_range_at(n) / gamma_mf, cv);
}

/// IIW Gough-Pollard check in damage form, D_sigma^(2/m_sigma) + D_tau^(2/m_tau) <= CV (see the
/// file comment; m the slopes the damages are referred to: 3 and 5 for steel). Errors: negative
/// damages, non-positive slopes, CV outside (0, 1].
template <class Scalar>
Result<InteractionCheck<Scalar>> iiw_interaction_from_damage(Scalar d_sigma, Scalar d_tau,
                                                             Scalar m_sigma, Scalar m_tau,
                                                             Scalar cv) {
  for (Status s :
       {detail::check_non_negative(d_sigma, "D_sigma"), detail::check_non_negative(d_tau, "D_tau"),
        detail::check_positive(m_sigma, "m_sigma"), detail::check_positive(m_tau, "m_tau"),
        detail::check_cv(cv)})
    if (!s) return s.error();
  using std::pow;
  InteractionCheck<Scalar> r;
  r.normal_term = pow(d_sigma, Scalar(2) / m_sigma);
  r.shear_term = pow(d_tau, Scalar(2) / m_tau);
  r.value = r.normal_term + r.shear_term;
  r.limit = cv;
  return r;
}

}  // namespace flexstress::fatigue
