// flexstress::compiled, double and float: the model, its builder, read-outs and outputs.
#include "instantiate.hpp"

namespace flexstress {
FLEXSTRESS_COMPILED_MODEL_SETUP(template, double)
FLEXSTRESS_COMPILED_MODEL_SETUP(template, float)
}  // namespace flexstress
