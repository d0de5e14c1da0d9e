// flexstress::compiled, double and float: the evaluation stages, the step, equilibrium and
// linearization.
#include "instantiate.hpp"

namespace flexstress {
FLEXSTRESS_COMPILED_MODEL_STEP(template, double)
FLEXSTRESS_COMPILED_MODEL_STEP(template, float)
}  // namespace flexstress
