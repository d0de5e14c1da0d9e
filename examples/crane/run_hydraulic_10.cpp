// The crane's run with the hydraulic drive and 10 boom modes (crane_run.hpp), in its own unit.
#include "crane_run.hpp"

template int crane::run<10, crane::fixed_storage_limit, crane::CraneHydraulicEffects>(
    const crane::RunOptions&);
