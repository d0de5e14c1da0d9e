// Double precision, all crane effects, 2 to 8 boom modes.
#include "study.hpp"

namespace study {

RunResult run_few_modes(const Knobs& k) {
  using E = crane::CraneEffects;
  switch (k.modes) {
    case 2: return run_crane<2, double, E>(k);
    case 4: return run_crane<4, double, E>(k);
    case 6: return run_crane<6, double, E>(k);
    case 8: return run_crane<8, double, E>(k);
    default: return not_compiled(k);
  }
}

}  // namespace study
