// flexstress's precompute for the tests, examples and benchmarks, part 3 of 4: reduction
// (see flexstress/precompute_instances.hpp). Four units compile in parallel, each in a
// fraction of the memory of one.
#define FLEXSTRESS_INSTANTIATE_PRECOMPUTE 3
#include <flexstress/precompute_instances.hpp>
