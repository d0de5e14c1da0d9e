// Palmgren-Miner damage, damage per work cycle, equivalent constant-amplitude stress range and
// predicted life.
//
// Palmgren-Miner (linear damage accumulation; IIW-2259-15 chapter 4, EN 1993-1-9 Annex A):
//   D = sum_i n_i / N_i,
// n_i the count of cycles of range Delta_sigma_i, N_i the cycles to failure at that range on the
// S-N curve. Failure is predicted at D = D_lim (1 by definition of the rule; design codes may ask
// for less, e.g. IIW for variable amplitude - pass it as miner_limit).
//
// Factors, all folded into the range read on the characteristic curve (DamageModel):
//   Delta_sigma_read = gamma_Ff * gamma_Mf * Delta_sigma_corrected / f(t),
// gamma_Ff the partial factor on the stress ranges, gamma_Mf the one on the fatigue strength
// (EN 1993-1-9 section 3, Table 3.1; the IIW safety considerations), f(t) the thickness factor
// (sn_curve.hpp), Delta_sigma_corrected the range after the mean-stress correction
// (mean_stress.hpp). Scaling the resistance by k = f(t) / gamma_Mf is the same as dividing the
// range by k, so one characteristic curve serves every design situation.
//
// Damage per work cycle: count the history of one work cycle as a repeating history (ASTM
// E1049-85 section 5.4.5, CycleClosure::repeating), so the residue - the largest ranges, which
// dominate the damage - is closed into full cycles instead of being dropped or halved.
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "flexstress/core/status.hpp"
#include "flexstress/fatigue/cycle.hpp"
#include "flexstress/fatigue/mean_stress.hpp"
#include "flexstress/fatigue/rainflow.hpp"
#include "flexstress/fatigue/sn_curve.hpp"

namespace flexstress::fatigue {

/// Compensated (Kahan) sum: damage is a sum of many small terms of very different size, and
/// float accumulators would otherwise lose the small ones. Also makes batch and streaming sums
/// (which add the same terms in a different order) agree to rounding.
template <class Scalar>
class KahanSum {
 public:
  void add(Scalar x) noexcept {
    const Scalar y = x - carry_;
    const Scalar t = sum_ + y;
    carry_ = (t - sum_) - y;
    sum_ = t;
  }
  Scalar value() const noexcept { return sum_; }
  /// The running compensation (what a checkpoint saves besides the value).
  Scalar carry() const noexcept { return carry_; }
  static KahanSum restored(Scalar sum, Scalar carry) noexcept {
    KahanSum k;
    k.sum_ = sum;
    k.carry_ = carry;
    return k;
  }

 private:
  Scalar sum_ = Scalar(0);
  Scalar carry_ = Scalar(0);
};

/// Factors of a damage evaluation (see the file comment). Defaults: characteristic values, no
/// mean-stress correction.
template <class Scalar>
struct DamageOptions {
  Scalar gamma_ff = Scalar(1);  ///< Partial factor on stress ranges (gamma_Ff).
  Scalar gamma_mf = Scalar(1);  ///< Partial factor on fatigue strength (gamma_Mf).
  Scalar thickness_factor =
      Scalar(1);  ///< f(t), multiplies the resistance (<= 1 for thick plates).
  MeanStressCorrection mean_stress = MeanStressCorrection::none;
};

/// An S-N curve with its factors: the damage of a cycle. Immutable; evaluation never allocates.
template <class Scalar>
class DamageModel {
 public:
  /// Errors: a partial factor or the thickness factor not positive and finite.
  static Result<DamageModel> create(const SnCurve<Scalar>& curve,
                                    const DamageOptions<Scalar>& options = {}) {
    if (!positive(options.gamma_ff))
      return make_error(ErrorCode::invalid_argument, "gamma_Ff must be positive, got ",
                        options.gamma_ff);
    if (!positive(options.gamma_mf))
      return make_error(ErrorCode::invalid_argument, "gamma_Mf must be positive, got ",
                        options.gamma_mf);
    if (!positive(options.thickness_factor))
      return make_error(ErrorCode::invalid_argument, "thickness factor must be positive, got ",
                        options.thickness_factor);
    return DamageModel(curve, options);
  }

  /// Factor from a (mean-stress corrected) load range to the range read on the
  /// characteristic curve: gamma_Ff gamma_Mf / f(t).
  Scalar range_factor() const noexcept { return factor_; }

  /// The range of cycle c read on the characteristic curve (MPa).
  Scalar effective_range(const Cycle<Scalar>& c) const {
    return factor_ * corrected_range(c, options_.mean_stress);
  }

  /// Miner damage of cycle c: count / N(effective range).
  Scalar damage(const Cycle<Scalar>& c) const {
    return c.count * curve_.damage_per_cycle(effective_range(c));
  }

  const SnCurve<Scalar>& curve() const noexcept { return curve_; }
  const DamageOptions<Scalar>& options() const noexcept { return options_; }

 private:
  DamageModel(const SnCurve<Scalar>& curve, const DamageOptions<Scalar>& options)
      : curve_(curve),
        options_(options),
        factor_(options.gamma_ff * options.gamma_mf / options.thickness_factor) {}

  static bool positive(Scalar x) { return std::isfinite(x) && x > Scalar(0); }

  SnCurve<Scalar> curve_;
  DamageOptions<Scalar> options_;
  Scalar factor_;
};

/// Palmgren-Miner damage sum of a cycle list (compensated sum).
template <class Scalar>
Scalar miner_damage(const std::vector<Cycle<Scalar>>& cycles, const DamageModel<Scalar>& model) {
  KahanSum<Scalar> d;
  for (const Cycle<Scalar>& c : cycles) d.add(model.damage(c));
  return d.value();
}

/// Damage of a stress history: rainflow (gate, closure as in options) then Miner. With
/// CycleClosure::repeating this is the damage per work cycle of a history that is one work
/// cycle. Errors: those of count_cycles (empty history, non-finite sample, bad gate).
template <class Scalar>
Result<Scalar> history_damage(const Scalar* samples, std::size_t n,
                              const DamageModel<Scalar>& model,
                              const CountOptions<Scalar>& options = {}) {
  Result<std::vector<Cycle<Scalar>>> cycles = count_cycles(samples, n, options);
  if (!cycles) return cycles.error();
  return miner_damage(*cycles, model);
}

/// Damage per work cycle: the history of one work cycle counted as a repeating history (ASTM
/// E1049-85 section 5.4.5), so its residue is closed, then Miner.
template <class Scalar>
Result<Scalar> damage_per_work_cycle(const std::vector<Scalar>& work_cycle,
                                     const DamageModel<Scalar>& model, Scalar gate = Scalar(0)) {
  return history_damage(work_cycle.data(), work_cycle.size(), model,
                        CountOptions<Scalar>{gate, CycleClosure::repeating});
}

/// Equivalent constant-amplitude stress range at n_ref cycles (2e6 by default): the range
/// which, applied n_ref times, gives the damage D on the slope of the curve at n_ref
/// (m = 3 for EN 1993-1-9 and IIW normal-stress curves, 5 for shear):
///   Delta_sigma_E = Delta_sigma_R(n_ref) * D^(1/m) / range_factor.
/// It is a load-side range (without gamma_Ff, gamma_Mf, f(t)): for EN 1993-1-9 this is
/// Delta_sigma_E,2 of section 8, and D <= 1 is the same check as
/// gamma_Ff Delta_sigma_E,2 <= Delta_sigma_C / gamma_Mf. With a mean-stress correction it is
/// the range of a cycle without mean-stress benefit. Errors: D negative or non-finite, n_ref
/// not positive or beyond a cut-off.
template <class Scalar>
Result<Scalar> equivalent_stress_range(Scalar damage, const DamageModel<Scalar>& model,
                                       Scalar n_ref = Scalar(2e6)) {
  if (!std::isfinite(damage) || damage < Scalar(0))
    return make_error(ErrorCode::invalid_argument, "damage must be finite and >= 0, got ", damage);
  const SnCurve<Scalar>& curve = model.curve();
  if (!std::isfinite(n_ref) || !(n_ref > Scalar(0)))
    return make_error(ErrorCode::invalid_argument, "reference cycle count must be positive, got ",
                      n_ref);
  const Scalar m = curve.slope_at(n_ref);
  if (!std::isfinite(m))
    return make_error(ErrorCode::invalid_argument, "reference cycle count ", n_ref,
                      " lies beyond the cut-off of the S-N curve");
  using std::pow;
  return curve.stress_range_at(n_ref) * pow(damage, Scalar(1) / m) / model.range_factor();
}

/// Predicted life from the damage of one work cycle.
template <class Scalar>
struct FatigueLife {
  Scalar damage_per_work_cycle = Scalar(0);
  Scalar work_cycles = Scalar(0);  ///< miner_limit / damage per work cycle (+inf for no damage).
  Scalar hours = Scalar(0);        ///< work_cycles * work-cycle duration / 3600.
};

/// Life in work cycles and hours: N_wc = D_lim / D_wc, hours = N_wc * T_wc / 3600 with T_wc the
/// duration of one work cycle in seconds. Errors: D_wc negative or non-finite, T_wc or D_lim
/// not positive.
template <class Scalar>
Result<FatigueLife<Scalar>> predict_life(Scalar damage_per_work_cycle, Scalar work_cycle_seconds,
                                         Scalar miner_limit = Scalar(1)) {
  if (!std::isfinite(damage_per_work_cycle) || damage_per_work_cycle < Scalar(0))
    return make_error(ErrorCode::invalid_argument,
                      "damage per work cycle must be finite and >= 0, got ", damage_per_work_cycle);
  if (!std::isfinite(work_cycle_seconds) || !(work_cycle_seconds > Scalar(0)))
    return make_error(ErrorCode::invalid_argument, "work cycle duration must be positive, got ",
                      work_cycle_seconds, " s");
  if (!std::isfinite(miner_limit) || !(miner_limit > Scalar(0)))
    return make_error(ErrorCode::invalid_argument, "Miner limit must be positive, got ",
                      miner_limit);
  FatigueLife<Scalar> life;
  life.damage_per_work_cycle = damage_per_work_cycle;
  life.work_cycles = damage_per_work_cycle > Scalar(0) ? miner_limit / damage_per_work_cycle
                                                       : std::numeric_limits<Scalar>::infinity();
  life.hours = life.work_cycles * work_cycle_seconds / Scalar(3600);
  return life;
}

}  // namespace flexstress::fatigue
