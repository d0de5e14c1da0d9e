// flexstress::compiled: the precompute (FE kernel, reductions, sub-models) in one unit
// (-DFLEXSTRESS_PRECOMPUTE_PARTS=OFF: less total compile time than the parts, more memory).
#define FLEXSTRESS_INSTANTIATE_PRECOMPUTE
#include <flexstress/precompute_instances.hpp>
