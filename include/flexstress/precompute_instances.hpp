// Compile flexstress's precompute once per program instead of once per translation unit.
//
// The precompute functions (FLEXSTRESS_PRECOMPUTE) are templates, instantiated in every
// translation unit that calls them, and they pull in Eigen's sparse and dense solvers: tens of
// seconds of compile time each. A project with several such translation units can compile them
// once:
//   - in exactly one .cpp file:   #define FLEXSTRESS_INSTANTIATE_PRECOMPUTE
//                                 #include <flexstress/precompute_instances.hpp>
//     (or in FLEXSTRESS_PRECOMPUTE_PARTS files, compiled in parallel and in less memory each:
//     the same with #define FLEXSTRESS_INSTANTIATE_PRECOMPUTE 1, 2, ...)
//   - everywhere else, define FLEXSTRESS_EXTERN_PRECOMPUTE (e.g. on the command line) and
//     include this header after the flexstress headers (or force-include it).
// Without either macro this header only includes the precompute headers. flexstress's own tests,
// examples and benchmarks build this way.
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

// X(part, return type, qualified name, parameter list) for each precompute entry point. Parts
// group what shares Eigen's heavier templates, so that each compiles in about 1 GB (GCC's
// front end alone needs 0.6 GB for these headers, and up to 0.45 GB more per entry point):
// FE assembly (1), constraints (2), element matrices (3), eigen solutions (4), stress
// operators (5), stress fields and output (6), component modes (7), orthonormalization (8),
// modal geometric stiffness and stress modes (9), sub-models (10), the static solver (11),
// modal bodies (12).
#define FLEXSTRESS_PRECOMPUTE_PARTS 12
#define FLEXSTRESS_PRECOMPUTE_INSTANCES(X)                                                        \
  X(1, Result<fe::SparseMatrixd>, fe::assemble_stiffness, (const fe::Mesh&, const fe::DofMap&))   \
  X(1, Result<fe::SparseMatrixd>, fe::assemble_mass,                                              \
    (const fe::Mesh&, const fe::DofMap&, const fe::MassOptions&))                                 \
  X(1, Result<fe::AssembledModel>, fe::assemble,                                                  \
    (const fe::Mesh&, const fe::BoundaryConditions&, const fe::MassOptions&))                     \
  X(1, Result<VectorXd>, fe::load_vector, (const fe::DofMap&, const std::vector<fe::NodalLoad>&)) \
  X(1, Result<fe::DofMap>, fe::DofMap::build, (const fe::Mesh&))                                  \
  X(2, Result<fe::ConstraintTransform>, fe::ConstraintTransform::build,                           \
    (const fe::Mesh&, const fe::DofMap&, const fe::BoundaryConditions&))                          \
  X(11, Result<fe::StaticSolver>, fe::StaticSolver::factorize,                                    \
    (const fe::Mesh&, const fe::AssembledModel&))                                                 \
  X(11, VectorXd, fe::StaticSolver::solve_free, (const VectorXd&) const)                          \
  X(11, VectorXd, fe::StaticSolver::solve, (const VectorXd&, const VectorXd&) const)              \
  X(11, VectorXd, fe::StaticSolver::solve, (const VectorXd&) const)                               \
  X(3, Result<fe::Matrix24d>, fe::hex8_stiffness,                                                 \
    (const fe::Hex8Coordinates&, const fe::Material&, fe::Hex8Formulation, Index))                \
  X(3, Result<fe::Matrix24d>, fe::hex8_mass,                                                      \
    (const fe::Hex8Coordinates&, double, fe::MassLumping, Index))                                 \
  X(3, fe::Matrix12d, fe::beam_stiffness, (const fe::Mesh&, const fe::BeamElement&))              \
  X(3, fe::Matrix12d, fe::beam_mass,                                                              \
    (const fe::Mesh&, const fe::BeamElement&, const fe::MassOptions&))                            \
  X(3, Result<fe::Hex8Kinematics>, fe::hex8_kinematics, (const fe::Hex8Coordinates&, Index))      \
  X(3, void, fe::BeamGeometry::interpolation, (double, fe::Matrix3x12d&, fe::Matrix3x12d&) const) \
  X(4, Result<fe::SparseMatrixd>, fe::assemble_geometric_stiffness,                               \
    (const fe::Mesh&, const fe::DofMap&, const VectorXd&))                                        \
  X(4, Result<fe::EigenSolution>, fe::solve_eigen,                                                \
    (const fe::SparseMatrixd&, const fe::SparseMatrixd&, const fe::EigenOptions&))                \
  X(4, MatrixXd, fe::rigid_body_modes, (const fe::Mesh&, const fe::DofMap&, const Vector3d&))     \
  X(4, Result<fe::RhsAttachmentMesh>, fe::make_rhs_attachment_mesh,                               \
    (const fe::RhsAttachmentSpec&))                                                               \
  X(5, Result<fe::Hex8StressOperator>, fe::hex8_stress_operator,                                  \
    (const fe::Hex8Coordinates&, const fe::Material&, fe::Hex8Formulation, const Vector3d&,       \
     Index))                                                                                      \
  X(5, Result<fe::BrickLocator>, fe::BrickLocator::build, (const fe::Mesh&, double))              \
  X(5, Result<fe::BrickPoint>, fe::BrickLocator::locate, (const Vector3d&) const)                 \
  X(5, Result<fe::SparseMatrixd>, fe::nodal_stress_operator,                                      \
    (const fe::Mesh&, const fe::DofMap&, const std::vector<Index>&))                              \
  X(5, Result<fe::SparseMatrixd>, fe::point_stress_operator,                                      \
    (const fe::Mesh&, const fe::DofMap&, const std::vector<fe::BrickPoint>&))                     \
  X(5, Result<fe::SparseMatrixd>, fe::point_stress_operator,                                      \
    (const fe::Mesh&, const fe::DofMap&, const fe::BrickLocator&, const std::vector<Vector3d>&))  \
  X(6, Result<fe::NodalStresses>, fe::nodal_stresses,                                             \
    (const fe::Mesh&, const fe::DofMap&, const VectorXd&))                                        \
  X(6, Result<std::vector<fe::Hex8GaussStresses>>, fe::gauss_point_stresses,                      \
    (const fe::Mesh&, const fe::DofMap&, const VectorXd&))                                        \
  X(6, Result<fe::Vector6d>, fe::stress_at_point,                                                 \
    (const fe::Mesh&, const fe::DofMap&, const fe::BrickLocator&, const VectorXd&,                \
     const Vector3d&))                                                                            \
  X(6, Result<fe::VtkData>, fe::standard_fields,                                                  \
    (const fe::Mesh&, const fe::DofMap&, const VectorXd&))                                        \
  X(6, Status, fe::write_vtu,                                                                     \
    (const std::string&, const fe::Mesh&, const fe::VtkData&, const fe::VtkOptions&))             \
  X(7, Result<reduction::ComponentModes>, reduction::craig_bampton,                               \
    (const fe::Mesh&, const std::vector<reduction::InterfaceNode>&,                               \
     const reduction::ModeSelection&, const fe::MassOptions&, const fe::EigenOptions&))           \
  X(7, Result<reduction::ComponentModes>, reduction::craig_chang,                                 \
    (const fe::Mesh&, const std::vector<reduction::InterfaceNode>&,                               \
     const reduction::ModeSelection&, const fe::MassOptions&, const fe::EigenOptions&))           \
  X(8, Result<reduction::DeformationModes>, reduction::orthonormalize,                            \
    (const fe::Mesh&, const reduction::ComponentModes&))                                          \
  X(12, Result<reduction::InertiaIntegrals>, reduction::inertia_integrals,                        \
    (const fe::Mesh&, const fe::DofMap&, const MatrixXd&, const fe::MassOptions&))                \
  X(12, Result<reduction::ModalBodyData>, reduction::make_modal_body,                             \
    (const fe::Mesh&, const reduction::ComponentModes&, const reduction::ReductionSpec&))         \
  X(12, Result<reduction::ModalBodyData>, reduction::reduce,                                      \
    (const fe::Mesh&, const reduction::ReductionSpec&))                                           \
  X(9, Result<reduction::ModalGeometricStiffness>, reduction::modal_geometric_stiffness,          \
    (const fe::Mesh&, const reduction::ModalBodyData&, const fe::BoundaryConditions&))            \
  X(9, Result<MatrixXd>, reduction::all_dof_mode_shapes,                                          \
    (const fe::Mesh&, const fe::DofMap&, const reduction::ModalBodyData&))                        \
  X(9, Result<reduction::BodyStressModes>, reduction::body_stress_modes,                          \
    (const fe::Mesh&, const reduction::ModalBodyData&, const std::vector<Vector3d>&))             \
  X(10, Result<MatrixXd>, stress::section_force_modes,                                            \
    (const fe::Mesh&, const reduction::ModalBodyData&, Index, Index))                             \
  X(10, Result<stress::SubModelInertia<double>>, stress::SubModelInertia<double>::build,          \
    (const stress::SubModel&, const stress::StressOutputs&))                                      \
  X(10, Result<MatrixXd>, stress::boundary_modes,                                                 \
    (const reduction::ModalBodyData&, const std::vector<stress::HostPoint>&))                     \
  X(10, Result<stress::SubModel>, stress::SubModel::build,                                        \
    (fe::Mesh, const std::vector<stress::SubModelAttachment>&))                                   \
  X(10, Result<MatrixXd>, stress::SubModel::stress_influence,                                     \
    (const std::vector<Vector3d>&) const)                                                         \
  X(10, Result<MatrixXd>, stress::SubModel::stress_influence,                                     \
    (const std::vector<Vector3d>&, const MatrixXd&) const)                                        \
  X(10, Result<MatrixXd>, stress::SubModel::displacement_influence,                               \
    (const std::vector<Vector3d>&) const)                                                         \
  X(10, Result<MatrixXd>, stress::SubModel::displacement_influence,                               \
    (const std::vector<Vector3d>&, const MatrixXd&) const)                                        \
  X(10, MatrixXd, stress::SubModel::inertia_fields, () const)                                     \
  X(10, VectorXd, stress::SubModel::solve, (const VectorXd&) const)                               \
  X(10, VectorXd, stress::SubModel::load_response, (const VectorXd&) const)                       \
  X(10, Result<VectorXd>, stress::SubModel::stresses_by_resolve,                                  \
    (const std::vector<Vector3d>&, const VectorXd&) const)                                        \
  X(10, Result<MatrixXd>, stress::StressOutputs::rows, (const stress::SubModel&) const)           \
  X(10, Result<MatrixXd>, stress::StressOutputs::rows,                                            \
    (const stress::SubModel&, const MatrixXd&) const)

// FLEXSTRESS_INSTANTIATE_PRECOMPUTE defined empty instantiates every part; defined as a part
// number, that part only, with the others declared extern (so it does not instantiate them
// either where it calls them).
#if defined(FLEXSTRESS_INSTANTIATE_PRECOMPUTE) || defined(FLEXSTRESS_EXTERN_PRECOMPUTE)
#if defined(FLEXSTRESS_INSTANTIATE_PRECOMPUTE)
// 0 when the macro is empty (every part), else the part number.
#define FLEXSTRESS_PRECOMPUTE_PART (0 + FLEXSTRESS_INSTANTIATE_PRECOMPUTE + 0)
#else
#define FLEXSTRESS_PRECOMPUTE_PART (-1)
#endif
#if FLEXSTRESS_PRECOMPUTE_PART == 0 || FLEXSTRESS_PRECOMPUTE_PART == 1
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_1 template
#else
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_1 extern template
#endif
#if FLEXSTRESS_PRECOMPUTE_PART == 0 || FLEXSTRESS_PRECOMPUTE_PART == 2
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_2 template
#else
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_2 extern template
#endif
#if FLEXSTRESS_PRECOMPUTE_PART == 0 || FLEXSTRESS_PRECOMPUTE_PART == 3
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_3 template
#else
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_3 extern template
#endif
#if FLEXSTRESS_PRECOMPUTE_PART == 0 || FLEXSTRESS_PRECOMPUTE_PART == 4
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_4 template
#else
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_4 extern template
#endif
#if FLEXSTRESS_PRECOMPUTE_PART == 0 || FLEXSTRESS_PRECOMPUTE_PART == 5
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_5 template
#else
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_5 extern template
#endif
#if FLEXSTRESS_PRECOMPUTE_PART == 0 || FLEXSTRESS_PRECOMPUTE_PART == 6
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_6 template
#else
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_6 extern template
#endif
#if FLEXSTRESS_PRECOMPUTE_PART == 0 || FLEXSTRESS_PRECOMPUTE_PART == 7
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_7 template
#else
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_7 extern template
#endif
#if FLEXSTRESS_PRECOMPUTE_PART == 0 || FLEXSTRESS_PRECOMPUTE_PART == 8
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_8 template
#else
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_8 extern template
#endif
#if FLEXSTRESS_PRECOMPUTE_PART == 0 || FLEXSTRESS_PRECOMPUTE_PART == 9
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_9 template
#else
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_9 extern template
#endif
#if FLEXSTRESS_PRECOMPUTE_PART == 0 || FLEXSTRESS_PRECOMPUTE_PART == 10
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_10 template
#else
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_10 extern template
#endif
#if FLEXSTRESS_PRECOMPUTE_PART == 0 || FLEXSTRESS_PRECOMPUTE_PART == 11
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_11 template
#else
#define FLEXSTRESS_PRECOMPUTE_KEYWORD_11 extern template
#endif
#if FLEXSTRESS_PRECOMPUTE_PART == 0 || FLEXSTRESS_PRECOMPUTE_PART == 12
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
