// The one translation unit that compiles flexstress's precompute for the tests, examples and
// benchmarks (see flexstress/precompute_instances.hpp).
#define FLEXSTRESS_INSTANTIATE_PRECOMPUTE
#include <flexstress/precompute_instances.hpp>
