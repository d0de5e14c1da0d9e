// The explicit instantiations that flexstress/model/compiled.hpp declares extern: the runtime
// model for double and float, compiled once into flexstress::compiled.
#ifndef FLEXSTRESS_COMPILED
#error "build this file through the flexstress_compiled target (it defines FLEXSTRESS_COMPILED)"
#endif

#include "flexstress/model/compiled.hpp"

namespace flexstress {

#define FLEXSTRESS_COMPILED_KERNEL_DEFINE(S, N) FLEXSTRESS_COMPILED_KERNEL(template, S, N)
#define FLEXSTRESS_COMPILED_ADOPT_DEFINE(S, N) FLEXSTRESS_COMPILED_ADOPT(template, S, N)

FLEXSTRESS_COMPILED_KERNELS(FLEXSTRESS_COMPILED_KERNEL_DEFINE, double)
FLEXSTRESS_COMPILED_KERNELS(FLEXSTRESS_COMPILED_KERNEL_DEFINE, float)
FLEXSTRESS_COMPILED_FIXED(FLEXSTRESS_COMPILED_ADOPT_DEFINE, double)
FLEXSTRESS_COMPILED_FIXED(FLEXSTRESS_COMPILED_ADOPT_DEFINE, float)
FLEXSTRESS_COMPILED_MODEL(template, double)
FLEXSTRESS_COMPILED_MODEL(template, float)

}  // namespace flexstress

template class Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>;
