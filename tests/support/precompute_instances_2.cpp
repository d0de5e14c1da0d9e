// flexstress's precompute for the tests, examples and benchmarks, part 2 of 4: eigen solves, stress recovery and output
// (see flexstress/precompute_instances.hpp). Four units compile in parallel, each in a
// fraction of the memory of one.
#define FLEXSTRESS_INSTANTIATE_PRECOMPUTE 2
#include <flexstress/precompute_instances.hpp>
