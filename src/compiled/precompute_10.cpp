// flexstress::compiled: the precompute (FE kernel, reductions, sub-models), part 10: sub-models
// (see flexstress/precompute_instances.hpp: the parts compile in parallel, each in under 1.5 GB).
#define FLEXSTRESS_INSTANTIATE_PRECOMPUTE 10
#include <flexstress/precompute_instances.hpp>
