// flexstress::compiled, double: the rigid and the bounded (any mode count) body kernels,
// and the modal damping's eigen solver.
#include "instantiate.hpp"

namespace flexstress {
FLEXSTRESS_INSTANTIATE_KERNEL(double, 0)
FLEXSTRESS_INSTANTIATE_KERNEL(double, Eigen::Dynamic)
}  // namespace flexstress

template class Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>;
