// flexstress::compiled, float: the rigid and the bounded (any mode count) body kernels.
#include "instantiate.hpp"

namespace flexstress {
FLEXSTRESS_INSTANTIATE_KERNEL(float, 0)
FLEXSTRESS_INSTANTIATE_KERNEL(float, Eigen::Dynamic)
}  // namespace flexstress
