// flexstress::compiled, double and float: the body kernels of 10 modes.
#include "instantiate.hpp"

namespace flexstress {
FLEXSTRESS_INSTANTIATE_FIXED(double, 10)
FLEXSTRESS_INSTANTIATE_FIXED(float, 10)
}  // namespace flexstress
