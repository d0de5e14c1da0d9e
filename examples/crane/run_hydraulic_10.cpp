// The crane's run with the hydraulic drive and 10 boom modes (crane_run.hpp), in its own unit.
#include "crane_run.hpp"

// Built in run_modes_10.cpp: the units compile in parallel, and this one does not compile the
// stroke-driven crane's static equilibrium again.
extern template crane::Result<
    crane::Crane<10, crane::fixed_storage_limit, double, crane::CraneEffects>>
crane::make_stroke_crane<10, crane::fixed_storage_limit, double, crane::CraneEffects>(
    const crane::CraneSpec&, const std::vector<double>&, const std::vector<double>&);

template int crane::run<10, crane::fixed_storage_limit, crane::CraneHydraulicEffects>(
    const crane::RunOptions&);
