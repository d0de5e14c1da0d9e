// The variant scene types of the study (float, fewer effects) for N modes; compiled in
// runs_variants_16.cpp and runs_variants_8.cpp.
#pragma once

#include "study.hpp"

namespace study {

template <int N>
inline RunResult run_variant_at(const Knobs& k) {
  using namespace flexstress;
  if (k.single_precision)
    return k.effects == EffectSet::all ? run_crane<N, float, crane::CraneEffects>(k)
                                       : not_compiled(k);
  switch (k.effects) {
    case EffectSet::no_quadratic_velocity:
      return run_crane<N, double, Effects<Gravity, ModalDamping>>(k);
    case EffectSet::no_damping:
      if constexpr (N == 16) return run_crane<N, double, Effects<Gravity, QuadraticVelocity>>(k);
      break;
    case EffectSet::gravity_only:
      if constexpr (N == 16) return run_crane<N, double, Effects<Gravity>>(k);
      break;
    case EffectSet::with_stiffening:
      if constexpr (N == 16)
        return run_crane<N, double,
                         Effects<Gravity, QuadraticVelocity, ModalDamping, GeometricStiffening>>(k);
      break;
    default: break;
  }
  return not_compiled(k);
}

}  // namespace study
