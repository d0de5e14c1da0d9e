// flexstress::compiled: the precompute (FE kernel, reductions, sub-models), part 2: the
// constraints' transformation (see flexstress/precompute_instances.hpp: the parts compile in
// parallel, each in under 1.5 GB).
#define FLEXSTRESS_INSTANTIATE_PRECOMPUTE 2
#include <flexstress/precompute_instances.hpp>
