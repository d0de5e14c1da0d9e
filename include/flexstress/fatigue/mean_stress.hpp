// Mean-stress (stress-ratio) corrections for welded details.
//
// Welded joints in the as-welded state carry tensile residual stresses near yield, so the
// applied mean stress hardly matters and the S-N curves are used with the full range. Where
// residual stresses are low (stress-relieved joints, small components), compressive mean
// stress helps, and the standards allow for it:
//
//   IIW (Hobbacher, IIW-2259-15 section 3.5.1): the fatigue resistance (FAT) is multiplied by an
//   enhancement factor f(R) >= 1 of the stress ratio R = sigma_min / sigma_max:
//     stress-relieved, low residual stress:  f = 1.6 for R < -1, f = -0.4 R + 1.2 for
//                                            -1 <= R <= 0.5, f = 1 for R > 0.5;
//     moderate residual stress (small thin-walled parts with short welds, thermally cut edges):
//                                            f = 1.3 for R < -1, f = -0.4 R + 0.9 for
//                                            -1 <= R <= -0.25, f = 1 for R > -0.25;
//     high residual stress (as-welded):      f = 1.
//   EN 1993-1-9:2005 section 7.2.1 (non-welded or stress-relieved welded details): the
//   effective range is the tensile part of the range plus 60 % of its compressive part.
//
// A cycle whose maximum is <= 0 is fully compressive. Its R = sigma_min / sigma_max lies above
// 1 (or is undefined at sigma_max = 0), past the compressive end of the IIW table, so it gets
// the factor of the most compressive row (R < -1). That is our reading of the table; IIW gives
// no separate row for compression-compression cycles.
#pragma once

#include <cmath>
#include <cstdint>

#include "flexstress/fatigue/cycle.hpp"

namespace flexstress::fatigue {

/// Residual-stress level of a welded detail, as in the IIW table of f(R).
enum class IiwResidualStress : std::uint8_t {
  high,      ///< As-welded, large structures: no enhancement, f = 1.
  moderate,  ///< Small thin-walled parts with short welds, thermally cut edges.
  low,       ///< Stress-relieved welded components.
};

/// IIW enhancement factor f(R) of the fatigue resistance for stress ratio R (IIW-2259-15
/// section 3.5.1; formulas in the file comment). R is sigma_min / sigma_max with sigma_max > 0.
template <class Scalar>
Scalar iiw_enhancement_factor(Scalar r, IiwResidualStress level) {
  switch (level) {
    case IiwResidualStress::low:
      if (r < Scalar(-1)) return Scalar(1.6);
      if (r <= Scalar(0.5)) return Scalar(-0.4) * r + Scalar(1.2);
      return Scalar(1);
    case IiwResidualStress::moderate:
      if (r < Scalar(-1)) return Scalar(1.3);
      if (r <= Scalar(-0.25)) return Scalar(-0.4) * r + Scalar(0.9);
      return Scalar(1);
    case IiwResidualStress::high: return Scalar(1);
  }
  return Scalar(1);
}

/// IIW enhancement factor of one cycle: f(R) with R = min / max of the cycle; a fully
/// compressive cycle (max <= 0) gets the factor of R < -1 (see the file comment).
template <class Scalar>
Scalar iiw_enhancement_factor(const Cycle<Scalar>& c, IiwResidualStress level) {
  const Scalar hi = c.max();
  if (!(hi > Scalar(0))) return iiw_enhancement_factor(Scalar(-2), level);
  return iiw_enhancement_factor(c.min() / hi, level);
}

/// EN 1993-1-9:2005 section 7.2.1 effective range of a cycle: tensile part plus 60 % of the
/// compressive part. Equals the full range for a fully tensile cycle and 0.6 times it for a
/// fully compressive one.
template <class Scalar>
Scalar en1993_effective_range(const Cycle<Scalar>& c) {
  const Scalar hi = c.max();
  const Scalar lo = c.min();
  if (lo >= Scalar(0)) return hi - lo;                  // fully tensile
  if (hi <= Scalar(0)) return Scalar(0.6) * (hi - lo);  // fully compressive
  return hi + Scalar(0.6) * (-lo);                      // crosses zero
}

/// Mean-stress correction applied by DamageModel.
enum class MeanStressCorrection : std::uint8_t {
  none,                      ///< Full range (as-welded details; the usual case).
  iiw_moderate_residual,     ///< Range / f(R), IIW moderate residual stress.
  iiw_stress_relieved,       ///< Range / f(R), IIW low residual stress (stress-relieved).
  en1993_compressive_60pct,  ///< EN 1993-1-9 section 7.2.1 effective range.
};

/// Range of a cycle after the mean-stress correction, to be read on the uncorrected S-N
/// curve. Dividing the range by f(R) is the same as multiplying the resistance by f(R).
template <class Scalar>
Scalar corrected_range(const Cycle<Scalar>& c, MeanStressCorrection correction) {
  switch (correction) {
    case MeanStressCorrection::none: return c.range();
    case MeanStressCorrection::iiw_moderate_residual:
      return c.range() / iiw_enhancement_factor(c, IiwResidualStress::moderate);
    case MeanStressCorrection::iiw_stress_relieved:
      return c.range() / iiw_enhancement_factor(c, IiwResidualStress::low);
    case MeanStressCorrection::en1993_compressive_60pct: return en1993_effective_range(c);
  }
  return c.range();
}

}  // namespace flexstress::fatigue
