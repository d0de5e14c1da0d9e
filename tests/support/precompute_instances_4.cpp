// flexstress's precompute for the tests, examples and benchmarks, part 4 of 4: sub-models
// (see flexstress/precompute_instances.hpp). Four units compile in parallel, each in a
// fraction of the memory of one.
#define FLEXSTRESS_INSTANTIATE_PRECOMPUTE 4
#include <flexstress/precompute_instances.hpp>
