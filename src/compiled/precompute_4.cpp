// flexstress::compiled: the precompute (FE kernel, reductions, sub-models), part 4: stress fields
// and output, modal geometric stiffness and stress modes, sub-models, modal bodies (see
// flexstress/precompute_instances.hpp: the parts compile in parallel, each in under 1.5 GB).
#define FLEXSTRESS_INSTANTIATE_PRECOMPUTE 4
#include <flexstress/precompute_instances.hpp>
