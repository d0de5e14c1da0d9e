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

// Each header lists its precompute entry points as X(group, return type, qualified name,
// parameters) (FLEXSTRESS_PRECOMPUTE_FE_ASSEMBLY, ...; precompute_instances.hpp instantiates
// them, in parts of a few groups each) and declares them extern where their instantiations are
// compiled elsewhere: in flexstress::compiled (FLEXSTRESS_COMPILED, which linking it defines) or in
// a project's own unit (FLEXSTRESS_EXTERN_PRECOMPUTE). The unit that compiles them defines
// FLEXSTRESS_INSTANTIATE_PRECOMPUTE.
//
// A unit that declares them extern also skips their bodies (FLEXSTRESS_PRECOMPUTE_BODIES is 0;
// each listed entry point's body sits in `#if FLEXSTRESS_PRECOMPUTE_BODIES`): although such a
// body is a template that is never instantiated there, the compiler still checks the code in it
// that does not depend on the template parameter, all of it here, and instantiates every Eigen
// expression and solver class it names. A unit that meshes or reduces a body compiles in about
// two thirds of the time without them (docs/performance.md, compile time). Entry points of class
// templates (SubModelInertia<Scalar>) keep their bodies: only their double instances are
// compiled in the library.
#if (defined(FLEXSTRESS_COMPILED) || defined(FLEXSTRESS_EXTERN_PRECOMPUTE)) && \
    !defined(FLEXSTRESS_INSTANTIATE_PRECOMPUTE)
#define FLEXSTRESS_PRECOMPUTE_EXTERN_ENTRY(P, R, F, A) extern template R F<void> A;
#define FLEXSTRESS_PRECOMPUTE_BODIES 0
#else
#define FLEXSTRESS_PRECOMPUTE_EXTERN_ENTRY(P, R, F, A)
#define FLEXSTRESS_PRECOMPUTE_BODIES 1
#endif
#define FLEXSTRESS_PRECOMPUTE_EXTERN(LIST) LIST(FLEXSTRESS_PRECOMPUTE_EXTERN_ENTRY)
