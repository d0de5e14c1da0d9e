// Compile flexstress's precompute once per program instead of once per translation unit.
//
// The precompute functions (FLEXSTRESS_PRECOMPUTE) are templates, instantiated in every
// translation unit that calls them, and they pull in Eigen's sparse and dense solvers: tens of
// seconds of compile time each. A project with several such translation units can compile them
// once:
//   - in exactly one .cpp file:   #define FLEXSTRESS_INSTANTIATE_PRECOMPUTE
//                                 #include <flexstress/precompute_instances.hpp>
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
#include "flexstress/reduction/modal_body_data.hpp"
#include "flexstress/reduction/modal_geometric_stiffness.hpp"
#include "flexstress/stress/host_point.hpp"
#include "flexstress/stress/stress_outputs.hpp"
#include "flexstress/stress/sub_model.hpp"

// X(return type, qualified name, parameter list) for each precompute entry point.
#define FLEXSTRESS_PRECOMPUTE_INSTANCES(X)                                                       \
  X(Result<fe::SparseMatrixd>, fe::assemble_stiffness, (const fe::Mesh&, const fe::DofMap&))     \
  X(Result<fe::SparseMatrixd>, fe::assemble_mass,                                                \
    (const fe::Mesh&, const fe::DofMap&, const fe::MassOptions&))                                \
  X(Result<fe::AssembledModel>, fe::assemble,                                                    \
    (const fe::Mesh&, const fe::BoundaryConditions&, const fe::MassOptions&))                    \
  X(Result<VectorXd>, fe::load_vector, (const fe::DofMap&, const std::vector<fe::NodalLoad>&))   \
  X(Result<fe::DofMap>, fe::DofMap::build, (const fe::Mesh&))                                    \
  X(Result<fe::ConstraintTransform>, fe::ConstraintTransform::build,                             \
    (const fe::Mesh&, const fe::DofMap&, const fe::BoundaryConditions&))                         \
  X(Result<fe::StaticSolver>, fe::StaticSolver::factorize,                                       \
    (const fe::Mesh&, const fe::AssembledModel&))                                                \
  X(VectorXd, fe::StaticSolver::solve_free, (const VectorXd&) const)                             \
  X(VectorXd, fe::StaticSolver::solve, (const VectorXd&, const VectorXd&) const)                 \
  X(VectorXd, fe::StaticSolver::solve, (const VectorXd&) const)                                  \
  X(Result<fe::EigenSolution>, fe::solve_eigen,                                                  \
    (const fe::SparseMatrixd&, const fe::SparseMatrixd&, const fe::EigenOptions&))               \
  X(Result<fe::Matrix24d>, fe::hex8_stiffness,                                                   \
    (const fe::Hex8Coordinates&, const fe::Material&, fe::Hex8Formulation, Index))               \
  X(Result<fe::Matrix24d>, fe::hex8_mass,                                                        \
    (const fe::Hex8Coordinates&, double, fe::MassLumping, Index))                                \
  X(Result<fe::Hex8StressOperator>, fe::hex8_stress_operator,                                    \
    (const fe::Hex8Coordinates&, const fe::Material&, fe::Hex8Formulation, const Vector3d&,      \
     Index))                                                                                     \
  X(fe::Matrix12d, fe::beam_stiffness, (const fe::Mesh&, const fe::BeamElement&))                \
  X(fe::Matrix12d, fe::beam_mass,                                                                \
    (const fe::Mesh&, const fe::BeamElement&, const fe::MassOptions&))                           \
  X(Result<fe::BrickLocator>, fe::BrickLocator::build, (const fe::Mesh&, double))                \
  X(Result<fe::BrickPoint>, fe::BrickLocator::locate, (const Vector3d&) const)                   \
  X(void, fe::BeamGeometry::interpolation, (double, fe::Matrix3x12d&, fe::Matrix3x12d&) const)   \
  X(Result<fe::SparseMatrixd>, fe::nodal_stress_operator,                                        \
    (const fe::Mesh&, const fe::DofMap&, const std::vector<Index>&))                             \
  X(Result<fe::SparseMatrixd>, fe::point_stress_operator,                                        \
    (const fe::Mesh&, const fe::DofMap&, const std::vector<fe::BrickPoint>&))                    \
  X(Result<fe::SparseMatrixd>, fe::point_stress_operator,                                        \
    (const fe::Mesh&, const fe::DofMap&, const fe::BrickLocator&, const std::vector<Vector3d>&)) \
  X(Result<fe::NodalStresses>, fe::nodal_stresses,                                               \
    (const fe::Mesh&, const fe::DofMap&, const VectorXd&))                                       \
  X(Result<std::vector<fe::Hex8GaussStresses>>, fe::gauss_point_stresses,                        \
    (const fe::Mesh&, const fe::DofMap&, const VectorXd&))                                       \
  X(Result<fe::Vector6d>, fe::stress_at_point,                                                   \
    (const fe::Mesh&, const fe::DofMap&, const fe::BrickLocator&, const VectorXd&,               \
     const Vector3d&))                                                                           \
  X(Result<fe::Hex8Kinematics>, fe::hex8_kinematics, (const fe::Hex8Coordinates&, Index))        \
  X(Result<fe::VtkData>, fe::standard_fields,                                                    \
    (const fe::Mesh&, const fe::DofMap&, const VectorXd&))                                       \
  X(MatrixXd, fe::rigid_body_modes, (const fe::Mesh&, const fe::DofMap&, const Vector3d&))       \
  X(Result<fe::RhsAttachmentMesh>, fe::make_rhs_attachment_mesh, (const fe::RhsAttachmentSpec&)) \
  X(Status, fe::write_vtu,                                                                       \
    (const std::string&, const fe::Mesh&, const fe::VtkData&, const fe::VtkOptions&))            \
  X(Result<reduction::ComponentModes>, reduction::craig_bampton,                                 \
    (const fe::Mesh&, const std::vector<reduction::InterfaceNode>&,                              \
     const reduction::ModeSelection&, const fe::MassOptions&, const fe::EigenOptions&))          \
  X(Result<reduction::ComponentModes>, reduction::craig_chang,                                   \
    (const fe::Mesh&, const std::vector<reduction::InterfaceNode>&,                              \
     const reduction::ModeSelection&, const fe::MassOptions&, const fe::EigenOptions&))          \
  X(Result<reduction::DeformationModes>, reduction::orthonormalize,                              \
    (const fe::Mesh&, const reduction::ComponentModes&))                                         \
  X(Result<reduction::InertiaIntegrals>, reduction::inertia_integrals,                           \
    (const fe::Mesh&, const fe::DofMap&, const MatrixXd&, const fe::MassOptions&))               \
  X(Result<reduction::ModalBodyData>, reduction::make_modal_body,                                \
    (const fe::Mesh&, const reduction::ComponentModes&, const reduction::ReductionSpec&))        \
  X(Result<reduction::ModalBodyData>, reduction::reduce,                                         \
    (const fe::Mesh&, const reduction::ReductionSpec&))                                          \
  X(Result<fe::SparseMatrixd>, fe::assemble_geometric_stiffness,                                 \
    (const fe::Mesh&, const fe::DofMap&, const VectorXd&))                                       \
  X(Result<reduction::ModalGeometricStiffness>, reduction::modal_geometric_stiffness,            \
    (const fe::Mesh&, const reduction::ModalBodyData&, const fe::BoundaryConditions&))           \
  X(Result<MatrixXd>, stress::boundary_modes,                                                    \
    (const reduction::ModalBodyData&, const std::vector<stress::HostPoint>&))                    \
  X(Result<stress::SubModel>, stress::SubModel::build,                                           \
    (fe::Mesh, const std::vector<stress::SubModelAttachment>&))                                  \
  X(Result<MatrixXd>, stress::SubModel::stress_influence, (const std::vector<Vector3d>&) const)  \
  X(Result<MatrixXd>, stress::SubModel::stress_influence,                                        \
    (const std::vector<Vector3d>&, const MatrixXd&) const)                                       \
  X(Result<MatrixXd>, stress::SubModel::displacement_influence,                                  \
    (const std::vector<Vector3d>&) const)                                                        \
  X(Result<MatrixXd>, stress::SubModel::displacement_influence,                                  \
    (const std::vector<Vector3d>&, const MatrixXd&) const)                                       \
  X(MatrixXd, stress::SubModel::inertia_fields, () const)                                        \
  X(VectorXd, stress::SubModel::solve, (const VectorXd&) const)                                  \
  X(Result<VectorXd>, stress::SubModel::stresses_by_resolve,                                     \
    (const std::vector<Vector3d>&, const VectorXd&) const)                                       \
  X(Result<MatrixXd>, stress::StressOutputs::rows, (const stress::SubModel&) const)              \
  X(Result<MatrixXd>, stress::StressOutputs::rows, (const stress::SubModel&, const MatrixXd&) const)

#if defined(FLEXSTRESS_INSTANTIATE_PRECOMPUTE)
#define FLEXSTRESS_PRECOMPUTE_INSTANCE(R, F, A) template R F<void> A;
namespace flexstress {
FLEXSTRESS_PRECOMPUTE_INSTANCES(FLEXSTRESS_PRECOMPUTE_INSTANCE)
}  // namespace flexstress
#undef FLEXSTRESS_PRECOMPUTE_INSTANCE
#elif defined(FLEXSTRESS_EXTERN_PRECOMPUTE)
#define FLEXSTRESS_PRECOMPUTE_INSTANCE(R, F, A) extern template R F<void> A;
namespace flexstress {
FLEXSTRESS_PRECOMPUTE_INSTANCES(FLEXSTRESS_PRECOMPUTE_INSTANCE)
}  // namespace flexstress
#undef FLEXSTRESS_PRECOMPUTE_INSTANCE
#endif
