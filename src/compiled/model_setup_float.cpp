// flexstress::compiled, float: the model, its builder, read-outs and outputs (a unit of its own:
// with double in one unit, GCC needed 1.58 GB).
#include "instantiate.hpp"

namespace flexstress {
FLEXSTRESS_COMPILED_MODEL_SETUP(template, float)
}  // namespace flexstress
