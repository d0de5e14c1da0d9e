// FLEXSTRESS_PRECOMPUTE marks the heavy precompute functions (element integration, assembly,
// solvers, reductions, mesh generation) as templates with a defaulted, unused parameter. Their
// Eigen instantiations are then compiled only in translation units that call them: a simulator
// that includes flexstress.hpp for the time step does not pay compile time for the FE kernel
// it never calls. Callers are unaffected (f(x) still works).
//
// Member functions so marked are defined outside their class: a definition in the class body is
// implicitly inline, and GCC instantiates an inline function even where it is declared
// `extern template` (flexstress/precompute_instances.hpp), to be able to inline it, Eigen
// solvers and all (a unit calling StaticSolver::factorize and solve: 1.0 GB and 250 s of GCC 12
// -O2 with the bodies in the class, 0.63 GB and 22 s without).
#pragma once

#define FLEXSTRESS_PRECOMPUTE template <class = void>
