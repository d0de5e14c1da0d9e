// FLEXSTRESS_PRECOMPUTE marks the heavy precompute functions (element integration, assembly,
// solvers, reductions, mesh generation) as templates with a defaulted, unused parameter. Their
// Eigen instantiations are then compiled only in translation units that call them: a simulator
// that includes flexstress.hpp for the time step does not pay compile time for the FE kernel
// it never calls. Callers are unaffected (f(x) still works).
//
// Member functions so marked are defined outside their class: a definition in the class body is
// implicitly inline, and GCC instantiates an inline function even where it is declared
// `extern template` (flexstress/precompute_instances.hpp), to be able to inline it, Eigen
// solvers and all (tests/fe/test_stress_recovery.cpp with GCC 12: 1.77 GB and 41 s with the
// bodies in the classes, 1.20 GB and 21 s without).
#pragma once

#define FLEXSTRESS_PRECOMPUTE template <class = void>
