// flexstress::compiled, double and float: the body kernels of 16 modes.
#include "instantiate.hpp"

namespace flexstress {
FLEXSTRESS_INSTANTIATE_FIXED(double, 16)
FLEXSTRESS_INSTANTIATE_FIXED(float, 16)
}  // namespace flexstress
