// flexstress::compiled: the precompute (FE kernel, reductions, sub-models), part 6: the static
// solver (see flexstress/precompute_instances.hpp: the parts compile in parallel, each in under 1.5
// GB).
#define FLEXSTRESS_INSTANTIATE_PRECOMPUTE 6
#include <flexstress/precompute_instances.hpp>
