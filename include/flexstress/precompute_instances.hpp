// The precompute's explicit instantiations: compile flexstress's precompute once per program
// instead of once per translation unit.
//
// The precompute functions (FLEXSTRESS_PRECOMPUTE) are templates, instantiated in every
// translation unit that calls them, and they pull in Eigen's sparse and dense solvers: tens of
// seconds of compile time and gigabytes of compiler memory each. flexstress::compiled holds
// their instantiations (src/compiled/precompute*.cpp include this header): linking it defines
// FLEXSTRESS_COMPILED, and every unit that includes the headers then declares them extern
// (core/precompute.hpp) and sees only their declarations. Without the compiled library a project
// can do the same itself:
//   - in exactly one .cpp file:   #define FLEXSTRESS_INSTANTIATE_PRECOMPUTE
//                                 #include <flexstress/precompute_instances.hpp>
//     (or in FLEXSTRESS_PRECOMPUTE_PARTS files, compiled in parallel and in less memory each:
//     the same with #define FLEXSTRESS_INSTANTIATE_PRECOMPUTE 1, 2, ...)
//   - everywhere else, define FLEXSTRESS_EXTERN_PRECOMPUTE (e.g. on the command line).
// Without FLEXSTRESS_INSTANTIATE_PRECOMPUTE this header only includes the precompute headers.
#pragma once

#include "flexstress/fe/assembly.hpp"
#include "flexstress/fe/brick_locator.hpp"
#include "flexstress/fe/eigen_solver.hpp"
#include "flexstress/fe/geometric_stiffness.hpp"
#include "flexstress/fe/hex8.hpp"
#include "flexstress/fe/rhs_attachment_mesh.hpp"
#include "flexstress/fe/static_solver.hpp"
#include "flexstress/fe/stress_recovery.hpp"
#include "flexstress/fe/vtk_writer.hpp"
#include "flexstress/reduction/body_stress_modes.hpp"
#include "flexstress/reduction/modal_body_data.hpp"
#include "flexstress/reduction/modal_geometric_stiffness.hpp"
#include "flexstress/stress/host_point.hpp"
#include "flexstress/stress/section_force_modes.hpp"
#include "flexstress/stress/stress_outputs.hpp"
#include "flexstress/stress/sub_model.hpp"
#include "flexstress/stress/sub_model_inertia.hpp"

// X(group, return type, qualified name, parameter list) for each precompute entry point. Groups
// gather what shares Eigen's heavier templates: FE assembly (1), constraints (2), element
// matrices (3), eigen solutions (4), stress operators (5), stress fields and output (6),
// component modes (7), orthonormalization (8), modal geometric stiffness and stress modes (9),
// sub-models (10), the static solver (11), modal bodies (12). A part, one unit of
// FLEXSTRESS_PRECOMPUTE_PARTS, compiles a few groups: GCC's front end needs 0.7 GB for these
// headers alone and up to 0.6 GB more per group, and groups that share templates cost less
// together than apart (7 and 8: 36 s against 25 + 26 s), so each part stays under 1.5 GB (GCC
// 12, -O3: 1.10 to 1.42 GB) in three quarters of the CPU time of one part per group.
#define FLEXSTRESS_PRECOMPUTE_PARTS 6
#define FLEXSTRESS_PRECOMPUTE_PART_GROUPS_1 ((1 << 1) | (1 << 4))
#define FLEXSTRESS_PRECOMPUTE_PART_GROUPS_2 (1 << 2)
#define FLEXSTRESS_PRECOMPUTE_PART_GROUPS_3 ((1 << 3) | (1 << 5))
#define FLEXSTRESS_PRECOMPUTE_PART_GROUPS_4 ((1 << 6) | (1 << 9) | (1 << 10) | (1 << 12))
#define FLEXSTRESS_PRECOMPUTE_PART_GROUPS_5 ((1 << 7) | (1 << 8))
#define FLEXSTRESS_PRECOMPUTE_PART_GROUPS_6 (1 << 11)
#define FLEXSTRESS_PRECOMPUTE_INSTANCES(X)                     \
  FLEXSTRESS_PRECOMPUTE_FE_ASSEMBLY(X)                         \
  FLEXSTRESS_PRECOMPUTE_FE_DOF_MAP(X)                          \
  FLEXSTRESS_PRECOMPUTE_FE_CONSTRAINT_TRANSFORM(X)             \
  FLEXSTRESS_PRECOMPUTE_FE_STATIC_SOLVER(X)                    \
  FLEXSTRESS_PRECOMPUTE_FE_HEX8(X)                             \
  FLEXSTRESS_PRECOMPUTE_FE_BEAM3D(X)                           \
  FLEXSTRESS_PRECOMPUTE_FE_GEOMETRIC_STIFFNESS(X)              \
  FLEXSTRESS_PRECOMPUTE_FE_EIGEN_SOLVER(X)                     \
  FLEXSTRESS_PRECOMPUTE_FE_RIGID_BODY_MODES(X)                 \
  FLEXSTRESS_PRECOMPUTE_FE_RHS_ATTACHMENT_MESH(X)              \
  FLEXSTRESS_PRECOMPUTE_FE_BRICK_LOCATOR(X)                    \
  FLEXSTRESS_PRECOMPUTE_FE_STRESS_RECOVERY(X)                  \
  FLEXSTRESS_PRECOMPUTE_FE_VTK_WRITER(X)                       \
  FLEXSTRESS_PRECOMPUTE_REDUCTION_COMPONENT_MODES(X)           \
  FLEXSTRESS_PRECOMPUTE_REDUCTION_ORTHONORMALIZE(X)            \
  FLEXSTRESS_PRECOMPUTE_REDUCTION_INERTIA_INTEGRALS(X)         \
  FLEXSTRESS_PRECOMPUTE_REDUCTION_MODAL_BODY_DATA(X)           \
  FLEXSTRESS_PRECOMPUTE_REDUCTION_MODAL_GEOMETRIC_STIFFNESS(X) \
  FLEXSTRESS_PRECOMPUTE_REDUCTION_BODY_STRESS_MODES(X)         \
  FLEXSTRESS_PRECOMPUTE_STRESS_SECTION_FORCE_MODES(X)          \
  FLEXSTRESS_PRECOMPUTE_STRESS_HOST_POINT(X)                   \
  FLEXSTRESS_PRECOMPUTE_STRESS_SUB_MODEL_INERTIA(X)            \
  FLEXSTRESS_PRECOMPUTE_STRESS_SUB_MODEL(X)                    \
  FLEXSTRESS_PRECOMPUTE_STRESS_STRESS_OUTPUTS(X)

// FLEXSTRESS_INSTANTIATE_PRECOMPUTE defined empty instantiates every group; defined as a part
// number, that part's groups only, with the others declared extern (so it does not instantiate
// them either where it calls them). Elsewhere the headers declare them extern themselves.
#if defined(FLEXSTRESS_INSTANTIATE_PRECOMPUTE)
// 0 when the macro is empty (every group), else the part number.
#define FLEXSTRESS_PRECOMPUTE_PART (0 + FLEXSTRESS_INSTANTIATE_PRECOMPUTE + 0)
#if FLEXSTRESS_PRECOMPUTE_PART == 0
#define FLEXSTRESS_PRECOMPUTE_GROUPS 0x1ffe
#elif FLEXSTRESS_PRECOMPUTE_PART == 1
#define FLEXSTRESS_PRECOMPUTE_GROUPS FLEXSTRESS_PRECOMPUTE_PART_GROUPS_1
#elif FLEXSTRESS_PRECOMPUTE_PART == 2
#define FLEXSTRESS_PRECOMPUTE_GROUPS FLEXSTRESS_PRECOMPUTE_PART_GROUPS_2
#elif FLEXSTRESS_PRECOMPUTE_PART == 3
#define FLEXSTRESS_PRECOMPUTE_GROUPS FLEXSTRESS_PRECOMPUTE_PART_GROUPS_3
#elif FLEXSTRESS_PRECOMPUTE_PART == 4
#define FLEXSTRESS_PRECOMPUTE_GROUPS FLEXSTRESS_PRECOMPUTE_PART_GROUPS_4
#elif FLEXSTRESS_PRECOMPUTE_PART == 5
#define FLEXSTRESS_PRECOMPUTE_GROUPS FLEXSTRESS_PRECOMPUTE_PART_GROUPS_5
#elif FLEXSTRESS_PRECOMPUTE_PART == 6
#define FLEXSTRESS_PRECOMPUTE_GROUPS FLEXSTRESS_PRECOMPUTE_PART_GROUPS_6
#else
#error "FLEXSTRESS_INSTANTIATE_PRECOMPUTE: a part from 1 to FLEXSTRESS_PRECOMPUTE_PARTS, or empty"
#endif
#if (FLEXSTRESS_PRECOMPUTE_GROUPS >> 1) & 1
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_1 template
#else
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_1 extern template
#endif
#if (FLEXSTRESS_PRECOMPUTE_GROUPS >> 2) & 1
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_2 template
#else
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_2 extern template
#endif
#if (FLEXSTRESS_PRECOMPUTE_GROUPS >> 3) & 1
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_3 template
#else
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_3 extern template
#endif
#if (FLEXSTRESS_PRECOMPUTE_GROUPS >> 4) & 1
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_4 template
#else
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_4 extern template
#endif
#if (FLEXSTRESS_PRECOMPUTE_GROUPS >> 5) & 1
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_5 template
#else
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_5 extern template
#endif
#if (FLEXSTRESS_PRECOMPUTE_GROUPS >> 6) & 1
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_6 template
#else
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_6 extern template
#endif
#if (FLEXSTRESS_PRECOMPUTE_GROUPS >> 7) & 1
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_7 template
#else
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_7 extern template
#endif
#if (FLEXSTRESS_PRECOMPUTE_GROUPS >> 8) & 1
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_8 template
#else
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_8 extern template
#endif
#if (FLEXSTRESS_PRECOMPUTE_GROUPS >> 9) & 1
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_9 template
#else
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_9 extern template
#endif
#if (FLEXSTRESS_PRECOMPUTE_GROUPS >> 10) & 1
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_10 template
#else
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_10 extern template
#endif
#if (FLEXSTRESS_PRECOMPUTE_GROUPS >> 11) & 1
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_11 template
#else
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_11 extern template
#endif
#if (FLEXSTRESS_PRECOMPUTE_GROUPS >> 12) & 1
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_12 template
#else
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_12 extern template
#endif
#define FLEXSTRESS_PRECOMPUTE_INSTANCE(P, R, F, A) FLEXSTRESS_PRECOMPUTE_KEYWORD_##P R F<void> A;
namespace flexstress {
FLEXSTRESS_PRECOMPUTE_INSTANCES(FLEXSTRESS_PRECOMPUTE_INSTANCE)
}  // namespace flexstress
#undef FLEXSTRESS_PRECOMPUTE_INSTANCE
#undef FLEXSTRESS_PRECOMPUTE_PART
#undef FLEXSTRESS_PRECOMPUTE_GROUPS
#undef FLEXSTRESS_PRECOMPUTE_KEYWORD_1
#undef FLEXSTRESS_PRECOMPUTE_KEYWORD_2
#undef FLEXSTRESS_PRECOMPUTE_KEYWORD_3
#undef FLEXSTRESS_PRECOMPUTE_KEYWORD_4
#undef FLEXSTRESS_PRECOMPUTE_KEYWORD_5
#undef FLEXSTRESS_PRECOMPUTE_KEYWORD_6
#undef FLEXSTRESS_PRECOMPUTE_KEYWORD_7
#undef FLEXSTRESS_PRECOMPUTE_KEYWORD_8
#undef FLEXSTRESS_PRECOMPUTE_KEYWORD_9
#undef FLEXSTRESS_PRECOMPUTE_KEYWORD_10
#undef FLEXSTRESS_PRECOMPUTE_KEYWORD_11
#undef FLEXSTRESS_PRECOMPUTE_KEYWORD_12
#endif
