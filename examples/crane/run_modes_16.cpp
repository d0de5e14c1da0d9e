// The crane's run with 16 boom modes (crane_run.hpp), in its own unit.
#include "crane_run.hpp"

template int crane::run<16, 0>(const crane::RunOptions&);
