// The crane's batch mode (--operators): many operators drive the same crane through their own
// versions of the work cycle, in parallel threads (core/batch.hpp), each with its own damage
// meter. The model (boom reduction, sub-model, fused stress rows) is built once and shared
// read-only; each job has its own Data (state, integrator, meter, and the driver's stroke
// table as its law). Operator k's cycle depends on k only, so the results do not depend on the
// thread count or on how a campaign is split into ranges of operators (--first-operator): a job
// array on a cluster runs ranges and concatenates their operators.csv files (docs/scaling.md).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "boom_model.hpp"

namespace crane {

/// Operator k's version of the base cycle (t, ds): operator 0 drives it as it is; the others
/// lift to 60-100 % of its height at 80-125 % of its pace, with their own small corrections
/// (up to 4 mm) while the boom is up. Deterministic in k (golden-ratio sequences, no random
/// generator), and kept within the cylinder's travel.
inline void operator_cycle(int k, const CraneSpec& spec, const std::vector<double>& t,
                           const std::vector<double>& ds, std::vector<double>& tk,
                           std::vector<double>& dk) {
  tk = t;
  dk = ds;
  if (k == 0) return;
  auto frac = [](double x) { return x - std::floor(x); };
  const double height = 0.6 + 0.4 * frac(0.5 + 0.6180339887 * k);
  const double pace = 0.8 + 0.45 * frac(0.5 + 0.4142135624 * k);
  const double lo = -spec.hydraulics.initial_position,
               hi = spec.hydraulics.stroke - spec.hydraulics.initial_position;
  for (std::size_t i = 0; i < t.size(); ++i) {
    tk[i] = t[0] + (t[i] - t[0]) / pace;
    const double correction = ds[i] != 0.0 ? 0.004 * std::sin(1.3 * k + double(i)) : 0.0;
    dk[i] = std::clamp(ds[i] * height + correction, lo, hi);
  }
}

}  // namespace crane
