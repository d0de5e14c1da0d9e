// flexstress::compiled, double: the model, its builder, read-outs and outputs.
#include "instantiate.hpp"

namespace flexstress {
FLEXSTRESS_COMPILED_MODEL_SETUP(template, double)
}  // namespace flexstress
