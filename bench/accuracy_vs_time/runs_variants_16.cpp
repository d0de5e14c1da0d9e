// Float and the effect lists at 16 modes (the base of those knobs), and the dispatcher.
#include "variants.hpp"

namespace study {

RunResult run_variants_8(const Knobs& k);

RunResult run_variant(const Knobs& k) {
  if (k.modes == 16) return run_variant_at<16>(k);
  if (k.modes == 8) return run_variants_8(k);
  return not_compiled(k);
}

}  // namespace study
