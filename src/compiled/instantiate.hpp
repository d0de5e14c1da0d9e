// The head of each unit of flexstress::compiled: the declarations of model/compiled.hpp and
// the macros that turn them into explicit instantiation definitions. The library is split by
// scalar and part (rigid and bounded kernels, each fixed mode count, the model's setup and
// step halves) so that no compile job of the default build needs much memory.
#pragma once

#ifndef FLEXSTRESS_COMPILED
#error "build this file through the flexstress_compiled target (it defines FLEXSTRESS_COMPILED)"
#endif

#include "flexstress/model/compiled.hpp"

#define FLEXSTRESS_INSTANTIATE_KERNEL(S, N) FLEXSTRESS_COMPILED_KERNEL(template, S, N)
/// A fixed mode count: its kernels and ModelBuilder's adoption of modal data.
#define FLEXSTRESS_INSTANTIATE_FIXED(S, N)   \
  FLEXSTRESS_COMPILED_KERNEL(template, S, N) \
  FLEXSTRESS_COMPILED_ADOPT(template, S, N)
