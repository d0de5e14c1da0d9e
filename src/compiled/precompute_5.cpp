// flexstress::compiled: the precompute (FE kernel, reductions, sub-models), part 5: component modes
// and their orthonormalization (see flexstress/precompute_instances.hpp: the parts compile in
// parallel, each in under 1.5 GB).
#define FLEXSTRESS_INSTANTIATE_PRECOMPUTE 5
#include <flexstress/precompute_instances.hpp>
