// A model built at run time: bodies, markers, joints and drivers, force elements, inputs and
// the effects that run, fixed after ModelBuilder::finalize(). Everything that changes while it
// runs lives in a Data (model/data.hpp); algorithms are free functions over (model, data).
//
// Global velocities v = [v_0; v_1; ...], v_b = [R_dot (global); w (body); p_dot]; coordinates
// q = [q_0; q_1; ...], q_b = [R; theta (Euler parameters); p]; constraints Phi(q, t) = 0 with
// Jacobian B (nc x nv), stored as one dense block per joint and body it touches.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "flexstress/core/envelope_cholesky.hpp"
#include "flexstress/core/euler_parameters.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/dynamics/hydraulic_cylinder.hpp"
#include "flexstress/dynamics/step_settings.hpp"
#include "flexstress/fatigue/streaming_damage.hpp"
#include "flexstress/model/body_kernels.hpp"
#include "flexstress/model/handles.hpp"
#include "flexstress/model/joint_rows.hpp"
#include "flexstress/model/motion_law.hpp"

namespace flexstress {

/// Parameters of a spring-damper between two marker origins: tension
/// f = k (L - L0) + c L_dot + preload along the line.
template <class Scalar>
struct SpringDamperParams {
  Scalar stiffness = Scalar(0);
  Scalar damping = Scalar(0);
  Scalar rest_length = Scalar(0);
  Scalar preload = Scalar(0);
};

enum class ForceKind : std::uint8_t { spring_damper, hydraulic_cylinder, point_load };

/// A load at a marker computed by the user each evaluation (a C-compatible callback with user
/// data): from the time and the marker's global position and velocity (3 each) it writes the
/// force (global, 3) and the moment (global, 3), both zeroed before the call. It runs inside
/// the step: it must not allocate, throw or block, and it is called from the thread stepping
/// the Data.
using PointLoadFunction = void (*)(double t, const double* position, const double* velocity,
                                   double* force, double* moment, void* user);

/// The damage meter a model attaches to an output: streaming rainflow on 128 classes and
/// Palmgren-Miner damage (fatigue/streaming_damage.hpp).
template <class Scalar>
using DamageMeter = fatigue::StreamingDamage<Scalar, 128>;

/// A prescribed motion of the ground frame (a crane on a ship or a truck): its origin follows
/// the laws x(t), y(t), z(t) (global) and it turns by angle(t) about a fixed unit axis. Joints to
/// the ground then move with it (their equations become time-dependent).
struct GroundMotion {
  bool moving = false;
  int x = -1, y = -1, z = -1, angle = -1;  ///< indices of the laws in Data::laws
};

template <class Scalar>
class Model {
 public:
  using scalar_type = Scalar;

  struct Body {
    std::string name;
    int modes = 0;
    int nv = 6;                 ///< velocities, 6 + modes
    int v_offset = 0;           ///< first velocity in v
    int q_offset = 0;           ///< first coordinate in q
    int mass_offset = 0;        ///< first entry of its mass block in Data::mass
    int first_slot = 0;         ///< its markers' first slot in Data::markers
    int geometric_offset = -1;  ///< its K_G in Data::geometric (-1: no geometric stiffening)
    int num_markers = 0;
    BodyEffects effects;  ///< what its dynamics stage evaluates
    const BodyKernels<Scalar>* kernels = nullptr;
    std::shared_ptr<const void> holder;  ///< BodyHolder<Scalar, kernels->fixed_modes>
    Vec3<Scalar> initial_position = Vec3<Scalar>::Zero();
    EulerParameters<Scalar> initial_orientation = identity_euler_parameters<Scalar>();
    std::vector<Scalar> displacement_scale;  ///< per mode (BodyModel::modal_displacement_scale)
    Scalar max_frequency = Scalar(0);        ///< rad/s, highest modal frequency
  };
  struct Marker {
    std::string name;
    int body = -1;   ///< -1: the ground
    int local = -1;  ///< index among its body's markers
    int slot = -1;   ///< index in Data::markers
  };
  struct Joint {
    std::string name;
    JointKind kind = JointKind::spherical;
    int marker_i = -1, marker_j = -1;
    int body_i = -1, body_j = -1;
    int row = 0;                 ///< first constraint row
    int equations = 0;           ///< rows
    int jac_i = -1, jac_j = -1;  ///< offsets of its Jacobian blocks in Data::jacobian (-1: ground)
    Scalar length = Scalar(0);   ///< distance joints
    int law = -1;                ///< drivers: index in Data::laws
  };
  struct Force {
    std::string name;
    ForceKind kind = ForceKind::spring_damper;
    int marker_i = -1, marker_j = -1;
    int body_i = -1, body_j = -1;
    SpringDamperParams<Scalar> params;     ///< spring-dampers
    HydraulicParams<Scalar> hydraulic;     ///< hydraulic cylinders
    HydraulicState<Scalar> initial_state;  ///< their chamber pressures at the start
    int law = -1;                          ///< hydraulic cylinders: the valve command's law
    PointLoadFunction load = nullptr;      ///< point loads (marker_j = -1)
    void* user = nullptr;
  };
  /// Stress outputs of a flexible body: y = F p (+ G g for the sub-model's own inertia, g the
  /// body frame's 12 inertia coordinates), F fused from a sub-model's influence rows and the
  /// body's boundary modes (stress/fused_stress.hpp).
  struct OutputSet {
    std::string name;
    int body = -1;
    int first = 0;  ///< its first output's index in Data::outputs
    Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> rows;     ///< F, outputs x modes
    Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> inertia;  ///< G (outputs x 12) or empty
    std::vector<std::string> names;
  };
  struct Meter {
    std::string name;
    int output = -1;                ///< the output it counts
    Scalar scale = Scalar(1);       ///< pushed value = scale * output (e.g. 1e-6: Pa to MPa)
    DamageMeter<Scalar> prototype;  ///< its empty state, copied into each Data
  };

  /// One joint's rows on one body, as the block products B x and B^T x walk them: listed in
  /// joint order (side i, then side j) at finalize, so that a product is one pass over a flat
  /// array of fixed-size kernel calls.
  struct JacobianBlock {
    void (*transpose_times)(int nv, const Scalar* rows, int count, const Scalar* x, Scalar* y);
    void (*rows_times)(int nv, const Scalar* rows, int count, const Scalar* x, Scalar* y);
    int nv = 6;        ///< the body's velocities
    int jac = 0;       ///< offset in Data::jacobian
    int rows = 0;      ///< the joint's equations
    int row = 0;       ///< the joint's first constraint row
    int v_offset = 0;  ///< the body's first velocity
  };

  const std::vector<Body>& bodies() const { return bodies_; }
  const std::vector<JacobianBlock>& jacobian_blocks() const { return jacobian_blocks_; }
  const std::vector<Marker>& markers() const { return markers_; }
  const std::vector<Joint>& joints() const { return joints_; }
  const std::vector<Force>& forces() const { return forces_; }
  const std::vector<std::string>& inputs() const { return inputs_; }
  /// Whether a force element has internal states (the integrator then starts and commits them).
  bool has_force_states() const {
    for (const auto& f : forces_)
      if (f.kind == ForceKind::hydraulic_cylinder) return true;
    return false;
  }
  const std::vector<OutputSet>& output_sets() const { return output_sets_; }
  const std::vector<Meter>& meters() const { return meters_; }
  int num_outputs() const { return num_outputs_; }
  const Body& body(BodyId b) const { return bodies_[static_cast<std::size_t>(b.index)]; }
  const Marker& marker(MarkerId m) const { return markers_[static_cast<std::size_t>(m.index)]; }
  const Joint& joint(JointId j) const { return joints_[static_cast<std::size_t>(j.index)]; }
  const Force& force(ForceId f) const { return forces_[static_cast<std::size_t>(f.index)]; }

  int num_velocities() const { return nv_; }
  int num_coordinates() const { return nq_; }
  int num_constraints() const { return nc_; }
  int num_marker_slots() const { return static_cast<int>(slot_parts_.size()); }
  int jacobian_size() const { return jacobian_size_; }
  int mass_size() const { return mass_size_; }
  /// Entries of the geometric stiffness matrices K_G (bodies with geometric stiffening).
  int geometric_size() const { return geometric_size_; }
  /// Marker parts (MarkerParts bits) evaluated per slot: what the joints and forces read.
  const std::vector<unsigned>& slot_parts() const { return slot_parts_; }
  /// Ground markers, evaluated once (the ground does not move).
  const std::vector<MarkerState<Scalar>>& ground_markers() const { return ground_markers_; }
  const std::vector<int>& ground_marker_slots() const { return ground_marker_slots_; }

  const Vec3<Scalar>& gravity() const { return gravity_; }
  const GroundMotion& ground_motion() const { return ground_motion_; }
  /// The ground's rotation axis (unit, global) when it moves.
  const Vec3<Scalar>& ground_axis() const { return ground_axis_; }
  bool has_gravity() const { return has_gravity_; }
  bool has_quadratic_velocity() const { return quadratic_velocity_; }
  /// What finalize found legal but likely wrong, a sentence each naming the part (a flexible
  /// body keeping too few of its basis's modes to take a joint's static load); empty if none.
  const std::vector<std::string>& warnings() const { return warnings_; }
  /// The laws drivers start with (a Data copies them and may swap them).
  const std::vector<MotionLaw<Scalar>>& laws() const { return laws_; }
  const ImplicitSettings<Scalar>& settings() const { return settings_; }
  /// Where the iteration matrix can be nonzero: one block per body, coupled by joints.
  const BlockPattern& block_pattern() const { return pattern_; }

  /// "joint 'A' (revolute)", for messages.
  std::string describe_joint(int k) const {
    const Joint& j = joints_[static_cast<std::size_t>(k)];
    return "joint '" + j.name + "' (" + to_string(j.kind) + ")";
  }
  std::string describe_body(int b) const {
    return b < 0 ? std::string("the ground")
                 : "body '" + bodies_[static_cast<std::size_t>(b)].name + "'";
  }
  /// The joint that owns constraint row r, or -1.
  int joint_of_row(int r) const {
    for (std::size_t k = 0; k < joints_.size(); ++k)
      if (r >= joints_[k].row && r < joints_[k].row + joints_[k].equations)
        return static_cast<int>(k);
    return -1;
  }

 private:
  template <class S>
  friend class ModelBuilder;

  std::vector<Body> bodies_;
  std::vector<Marker> markers_;
  std::vector<Joint> joints_;
  std::vector<JacobianBlock> jacobian_blocks_;
  std::vector<Force> forces_;
  std::vector<std::string> inputs_;
  std::vector<std::string> warnings_;
  std::vector<OutputSet> output_sets_;
  std::vector<Meter> meters_;
  int num_outputs_ = 0;
  std::vector<unsigned> slot_parts_;
  std::vector<MarkerState<Scalar>> ground_markers_;
  std::vector<int> ground_marker_slots_;
  std::vector<MotionLaw<Scalar>> laws_;
  Vec3<Scalar> gravity_ = Vec3<Scalar>::Zero();
  bool has_gravity_ = false;
  GroundMotion ground_motion_;
  Vec3<Scalar> ground_axis_ = Vec3<Scalar>::UnitZ();
  bool quadratic_velocity_ = true;
  ImplicitSettings<Scalar> settings_;
  BlockPattern pattern_;
  int nv_ = 0, nq_ = 0, nc_ = 0, jacobian_size_ = 0, mass_size_ = 0, geometric_size_ = 0;
};

}  // namespace flexstress
