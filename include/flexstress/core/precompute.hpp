// FLEXSTRESS_PRECOMPUTE marks the heavy precompute functions (element integration, assembly,
// solvers, reductions, mesh generation) as templates with a defaulted, unused parameter. Their
// Eigen instantiations are then compiled only in translation units that call them: a simulator
// that includes flexstress.hpp for the time step does not pay compile time for the FE kernel
// it never calls. Callers are unaffected (f(x) still works).
#pragma once

#define FLEXSTRESS_PRECOMPUTE template <class = void>
