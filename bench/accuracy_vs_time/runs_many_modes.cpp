// Double precision, all crane effects, 10 to 24 boom modes.
#include "study.hpp"

namespace study {

RunResult run_many_modes(const Knobs& k) {
  using E = crane::CraneEffects;
  switch (k.modes) {
    case 10: return run_crane<10, double, E>(k);
    case 12: return run_crane<12, double, E>(k);
    case 16: return run_crane<16, double, E>(k);
    case 24: return run_crane<24, double, E>(k);
    default: return not_compiled(k);
  }
}

}  // namespace study
