// Float and the effect lists at 8 modes (the fast configurations).
#include "variants.hpp"

namespace study {

RunResult run_variants_8(const Knobs& k) {
  return run_variant_at<8>(k);
}

}  // namespace study
