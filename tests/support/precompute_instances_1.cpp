// flexstress's precompute for the tests, examples and benchmarks, part 1 of 4: FE assembly, elements and static solves
// (see flexstress/precompute_instances.hpp). Four units compile in parallel, each in a
// fraction of the memory of one.
#define FLEXSTRESS_INSTANTIATE_PRECOMPUTE 1
#include <flexstress/precompute_instances.hpp>
