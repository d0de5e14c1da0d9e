// The runtime model's templates compiled once, in the flexstress::compiled library (the
// fmt/spdlog pattern). Linking flexstress::compiled defines FLEXSTRESS_COMPILED, and every unit
// that includes the model headers then declares the double and float instantiations extern:
// it parses the templates but does not instantiate and optimize them again (the step, the
// equilibrium solver and the per-mode-count body kernels are most of a unit's compile time).
// src/compiled/*.cpp hold the matching definitions. Without FLEXSTRESS_COMPILED
// this header declares nothing and the library stays header-only.
#pragma once

#include <type_traits>
#include <utility>

#include <Eigen/Eigenvalues>

#include "flexstress/model/checkpoint.hpp"
#include "flexstress/model/data.hpp"
#include "flexstress/model/energy_balance.hpp"
#include "flexstress/model/equilibrium.hpp"
#include "flexstress/model/explicit_step.hpp"
#include "flexstress/model/implicit_step.hpp"
#include "flexstress/model/model.hpp"
#include "flexstress/model/model_builder.hpp"
#include "flexstress/model/motion_law.hpp"
#include "flexstress/model/outputs.hpp"
#include "flexstress/model/pipeline.hpp"
#include "flexstress/model/readouts.hpp"
#include "flexstress/model/step.hpp"

/// The mode counts the compiled library instantiates kernels for; a unit that changes
/// FLEXSTRESS_MODE_COUNTS must not use the compiled library (ModelBuilder would differ).
#define FLEXSTRESS_COMPILED_MODE_COUNTS 10, 16

// X(Scalar, N) for each fixed mode count, and for every body kernel: rigid, the fixed counts
// and the bounded one.
#define FLEXSTRESS_COMPILED_FIXED(X, S) \
  X(S, 10)                              \
  X(S, 16)
#define FLEXSTRESS_COMPILED_KERNELS(X, S) \
  X(S, 0)                                 \
  FLEXSTRESS_COMPILED_FIXED(X, S)         \
  X(S, Eigen::Dynamic)

// A body kernel's templates; D is `extern template` or `template`.
#define FLEXSTRESS_COMPILED_KERNEL(D, S, N)                                            \
  D struct detail::BodyKernelImpl<S, N>;                                               \
  D const BodyKernels<S>& body_kernels<S, N>();                                        \
  D std::pair<std::shared_ptr<void>, const BodyKernels<S>*> detail::make_holder<S, N>( \
      BodyModel<S, N>);

// The fixed counts also have ModelBuilder's adoption of modal data.
#define FLEXSTRESS_COMPILED_ADOPT(D, S, N)                                         \
  D void detail::adopt_flexible<S, N>(const reduction::ModalBodyData&, int, bool&, \
                                      std::shared_ptr<void>&, const BodyKernels<S>*&, Error&);

// The model layer's templates for one Scalar, in two parts compiled apart (each unit stays
// small): what builds and reads a model, and what evaluates and steps it. D is
// `extern template` or `template`.
#define FLEXSTRESS_COMPILED_MODEL_SETUP(D, S)                                                     \
  D struct MotionLaw<S>;                                                                          \
  D class Model<S>;                                                                               \
  D struct Data<S>;                                                                               \
  D class ModelBuilder<S>;                                                                        \
  D Vec3<S> body_position<S>(const Model<S>&, const Data<S>&, BodyId);                            \
  D EulerParameters<S> body_orientation<S>(const Model<S>&, const Data<S>&, BodyId);              \
  D Vec3<S> body_velocity<S>(const Model<S>&, const Data<S>&, BodyId);                            \
  D Vec3<S> body_angular_velocity<S>(const Model<S>&, const Data<S>&, BodyId);                    \
  D DataSegment<S> modal_coordinates<S>(const Model<S>&, const Data<S>&, BodyId);                 \
  D DataSegment<S> modal_velocities<S>(const Model<S>&, const Data<S>&, BodyId);                  \
  D MarkerState<S> marker_state<S>(const Model<S>&, const Data<S>&, MarkerId);                    \
  D Frame<S> marker_frame<S>(const Model<S>&, const Data<S>&, MarkerId);                          \
  D Frame<S> marker_frame_in_body<S>(const Model<S>&, const Data<S>&, MarkerId);                  \
  D Reaction<S> joint_reaction<S>(const Model<S>&, const Data<S>&, JointId);                      \
  D S constraint_violation<S>(const Model<S>&, const Data<S>&);                                   \
  D S velocity_violation<S>(const Model<S>&, const Data<S>&);                                     \
  D Energy<S> energy<S>(const Model<S>&, Data<S>&);                                               \
  D Energy<S> body_energy<S>(const Model<S>&, const Data<S>&, BodyId);                            \
  D void set_joint_active<S>(const Model<S>&, Data<S>&, JointId, bool);                           \
  D bool joint_active<S>(const Data<S>&, JointId);                                                \
  D Status anchor_joint_at<S>(const Model<S>&, Data<S>&, JointId);                                \
  D Momentum<S> momentum<S>(const Model<S>&, const Data<S>&, BodyId);                             \
  D S driver_effort<S>(const Model<S>&, const Data<S>&, JointId);                                 \
  D JointEquations<S> joint_equations<S>(const Model<S>&, const Data<S>&, JointId);               \
  D void set_body_velocity<S>(const Model<S>&, Data<S>&, BodyId, const Vec3<S>&, const Vec3<S>&); \
  D StepStatus set_input<S>(const Model<S>&, Data<S>&, InputId, S, S, S);                         \
  D Status set_law<S>(const Model<S>&, Data<S>&, JointId, MotionLaw<S>);                          \
  D Eigen::Matrix<S, 12, 1> body_inertia_coordinates<S>(const Model<S>&, const Data<S>&, int);    \
  D StepStatus evaluate_outputs<S>(const Model<S>&, Data<S>&, bool);                              \
  D S meter_damage<S>(const Data<S>&, MeterId, fatigue::CycleClosure);                            \
  D std::int64_t meter_refused_samples<S>(const Data<S>&, MeterId);                               \
  D std::vector<ModelPart> describe_model<S>(const Model<S>&);                                    \
  D Result<std::vector<unsigned char>> save_checkpoint<S>(const Model<S>&, const Data<S>&);       \
  D Status restore_checkpoint<S>(const Model<S>&, Data<S>&, const unsigned char*, std::size_t,    \
                                 const std::string&);

#define FLEXSTRESS_COMPILED_MODEL_STEP(D, S)                                                 \
  D void update_kinematics<S>(const Model<S>&, Data<S>&);                                    \
  D void update_markers<S>(const Model<S>&, Data<S>&, bool);                                 \
  D void update_constraints<S>(const Model<S>&, Data<S>&, bool);                             \
  D void add_marker_load<S>(const Model<S>&, Data<S>&, int, const Vec3<S>&, const Vec3<S>*); \
  D void update_dynamics<S>(const Model<S>&, Data<S>&);                                      \
  D void evaluate<S>(const Model<S>&, Data<S>&, bool);                                       \
  D int nonfinite_body<S>(const Model<S>&, const Data<S>&);                                  \
  D void set_step_size<S>(Data<S>&, S);                                                      \
  D Status initialize<S>(const Model<S>&, Data<S>&, int);                                    \
  D StepStatus step<S>(const Model<S>&, Data<S>&);                                           \
  D Status set_settings<S>(const Model<S>&, Data<S>&, const ImplicitSettings<S>&);           \
  D Eigen::MatrixXd dense_jacobian<S>(const Model<S>&, const Data<S>&);                      \
  D Status solve_static_equilibrium<S>(const Model<S>&, Data<S>&,                            \
                                       const StaticEquilibriumOptions&);                     \
  D Result<Linearization> linearize<S>(const Model<S>&, Data<S>&, double);                   \
  D const MarkerState<S>& force_marker<S>(const Model<S>&, const Data<S>&, int, bool);       \
  D S valve_command<S>(const Model<S>&, const Data<S>&, int);                                \
  D Vec3<S> force_element_force<S>(const Model<S>&, const Data<S>&, int);                    \
  D void point_load<S>(const Model<S>&, const Data<S>&, int, Vec3<S>&, Vec3<S>&);            \
  D void update_force_states<S>(const Model<S>&, Data<S>&, bool);                            \
  D class EnergyBalance<S>;                                                                  \
  D StepStatus explicit_step<S>(const Model<S>&, Data<S>&, const ExplicitSettings<S>&);

#define FLEXSTRESS_COMPILED_MODEL(D, S) \
  FLEXSTRESS_COMPILED_MODEL_SETUP(D, S) \
  FLEXSTRESS_COMPILED_MODEL_STEP(D, S)

#define FLEXSTRESS_COMPILED_KERNEL_EXTERN(S, N) FLEXSTRESS_COMPILED_KERNEL(extern template, S, N)
#define FLEXSTRESS_COMPILED_ADOPT_EXTERN(S, N) FLEXSTRESS_COMPILED_ADOPT(extern template, S, N)

#ifdef FLEXSTRESS_COMPILED
namespace flexstress {

static_assert(std::is_same_v<std::integer_sequence<int, FLEXSTRESS_MODE_COUNTS>,
                             std::integer_sequence<int, FLEXSTRESS_COMPILED_MODE_COUNTS>>,
              "flexstress::compiled was built for FLEXSTRESS_MODE_COUNTS 10, 16: a unit that "
              "changes them must use the header-only flexstress::flexstress");

FLEXSTRESS_COMPILED_KERNELS(FLEXSTRESS_COMPILED_KERNEL_EXTERN, double)
FLEXSTRESS_COMPILED_KERNELS(FLEXSTRESS_COMPILED_KERNEL_EXTERN, float)
FLEXSTRESS_COMPILED_FIXED(FLEXSTRESS_COMPILED_ADOPT_EXTERN, double)
FLEXSTRESS_COMPILED_FIXED(FLEXSTRESS_COMPILED_ADOPT_EXTERN, float)
FLEXSTRESS_COMPILED_MODEL(extern template, double)
FLEXSTRESS_COMPILED_MODEL(extern template, float)

}  // namespace flexstress

// The modal damping's eigen solve behind every flexible body (BodyModel::update_damping, inline
// and so instantiated by any unit that adds a flexible body): two seconds of a unit's compile.
extern template class Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>;
#endif
