// Everything that changes while a model runs: coordinates, velocities, multipliers, the
// evaluated workspace, runtime switches, current laws and inputs, the integrator's history and
// its scratch. Allocated once, when a Data is made for its Model; a step writes only into it.
// Many Data can share one Model (one per thread of a batch).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "flexstress/core/envelope_cholesky.hpp"
#include "flexstress/core/euler_parameters.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/dynamics/motion_laws.hpp"
#include "flexstress/dynamics/step_settings.hpp"
#include "flexstress/model/joint_rows.hpp"
#include "flexstress/model/model.hpp"
#include "flexstress/model/motion_law.hpp"

namespace flexstress {

template <class Scalar>
struct Data {
  using VectorX = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using MatrixX = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  // ---- state --------------------------------------------------------------------------------
  Scalar t = Scalar(0);
  VectorX q;       ///< coordinates [R; theta; p] per body
  VectorX v;       ///< velocities [R_dot; w; p_dot] per body
  VectorX v_dot;   ///< accelerations
  VectorX a;       ///< algorithmic accelerations (generalized-alpha)
  VectorX lambda;  ///< constraint multipliers (M v_dot + B^T lambda = Q)

  // ---- runtime changes (by handle: set_joint_active, set_law, set_input) ------------------
  std::vector<unsigned char> joint_active;
  std::vector<MotionLaw<Scalar>> laws;      ///< the drivers' current laws
  std::vector<MotionValue<Scalar>> inputs;  ///< by InputId: for the end of the next step
  std::vector<unsigned char> input_set;     ///< whether set_input was called for it
  /// The inputs at d.t, or at the start of a step under way (the last step's end, or as set
  /// when initialize() ran), and the step's span [input_t0, input_t1] (input_value).
  std::vector<MotionValue<Scalar>> inputs_start;
  Scalar input_t0 = 0, input_t1 = 0;
  std::vector<MarkerAnchor<Scalar>> anchors;  ///< by marker slot (anchor_joint_at)
  std::uint64_t revision = 0;                 ///< counts runtime changes to the topology
  /// Internal states of the force elements (hydraulic chamber pressures), by ForceId: the
  /// last accepted step's.
  std::vector<HydraulicState<Scalar>> force_states;

  // ---- outputs (evaluate_outputs) ---------------------------------------------------------
  VectorX outputs;                          ///< by OutputId
  std::vector<DamageMeter<Scalar>> meters;  ///< by MeterId
  /// Samples each meter refused (outside its class window, or not finite), by MeterId.
  std::vector<std::int64_t> meter_refused;

  // ---- workspace (what an evaluation writes) -----------------------------------------------
  /// The ground frame at t (prescribed motion): origin, its velocity and acceleration, rotation,
  /// angular velocity and acceleration (global). At rest unless the model moves it.
  struct Ground {
    Vec3<Scalar> position = Vec3<Scalar>::Zero(), velocity = Vec3<Scalar>::Zero(),
                 acceleration = Vec3<Scalar>::Zero();
    Mat3<Scalar> rotation = Mat3<Scalar>::Identity();
    Vec3<Scalar> omega = Vec3<Scalar>::Zero(), alpha = Vec3<Scalar>::Zero();
  } ground;
  std::vector<Mat3<Scalar>> rotation;        ///< A per body
  std::vector<MarkerState<Scalar>> markers;  ///< by Model::Marker::slot
  VectorX mass;       ///< per body its nv x nv mass block, column-major (Body::mass_offset)
  VectorX force;      ///< Q_e - Q_v - (K + K_G) p - D p_dot, force elements, point loads
  VectorX geometric;  ///< per body with geometric stiffening its K_G (Body::geometric_offset)
  VectorX jacobian;   ///< per joint and body its rows x nv block, row-major (Joint::jac_i, jac_j)
  VectorX phi, phi_t, conv;
  VectorX row_scratch;           ///< one body's row (force elements)
  VectorX row_scratch_j;         ///< the other body's row of a spring-damper (iteration matrix)
  JointRows<Scalar> joint_rows;  ///< one joint's rows (update_constraints; not zeroed per call)

  // ---- integrator -------------------------------------------------------------------------
  ImplicitSettings<Scalar> settings;
  StepStatistics statistics;
  struct Integrator {
    Scalar alpha_m = 0, alpha_f = 0, gamma = 0, beta = 0;
    Scalar beta_prime = 0, gamma_prime = 0, penalty = 0, tol_x = 0;
    /// The step the constants above are set for: settings.step, or a piece of it (step()).
    Scalar h = 0;
    /// The pieces the next step starts with, step / 2^piece_level (0: the whole step first);
    /// step() keeps the size that last passed, so a hard phase does not fail each step whole.
    int piece_level = 0;
    /// The local error estimate of the last step or piece that converged (m, rad).
    Scalar last_error_estimate = 0;
    /// The model's acceleration scale for the Newton tolerance: the larger of |g| and the
    /// largest acceleration at initialize() (ImplicitSettings::relative_acceleration_tolerance).
    Scalar acceleration_scale = 0;
    bool have_factorization = false, has_previous = false;
    bool predict_linear = true;  ///< the linear predictor missed less than a constant one
    int converged_multipliers = 0;
    /// Steps that refactorize at their start after reused matrices went stale in a row, and
    /// how many of them are left (ImplicitSettings::refactor_backoff_limit).
    int reuse_backoff = 0, fresh_starts_left = 0;
    /// The penalty's factor over ImplicitSettings::penalty_factor, raised within a step where
    /// the multiplier updates contract slowly; kept for penalty_hold_steps steps after that.
    Scalar penalty_boost = 1;
    Scalar penalty_boost_start = 1;  ///< the boost the step under way started from
    int boost_age = 0;               ///< steps since the penalty was last raised or lowered
    int boost_age_start = 0;         ///< the age the step under way started from
    std::uint64_t revision = 0;      ///< the Data revision the history was built for
    bool initialized = false;
    MatrixX iteration;
    EnvelopeCholesky<Scalar, Eigen::Dynamic> cholesky;
    std::vector<Mat3<Scalar>> factorized_rotations;
    VectorX correction_scale;
    VectorX r, dx, v_n, vd_n, a_n, a1, tmp, vd_prev, v_save, vd_save, q_n, q_save;
    /// lambda_last: the augmented Lagrangian's lambda* at the end of the last step (the next
    /// step starts from it; d.lambda is the multipliers, lambda* + alpha Phi); lambda_increment:
    /// the change the predictor adds to it (ImplicitSettings::multiplier_trend_memory).
    /// lambda_pass: a correction's multiplier update on the linearized constraints
    /// (ImplicitSettings::linearized_multipliers).
    VectorX e, lambda_star, lambda_last, lambda_increment, lambda_save, lambda_pass;
    /// The state at the start of a step retried in pieces (max_step_halvings), restored when
    /// a piece fails: coordinates, velocities, accelerations, multipliers and their history.
    VectorX q_split, v_split, vd_split, a_split, vd_prev_split, lambda_split, lambda_last_split,
        lambda_increment_split;
    std::vector<HydraulicState<Scalar>> force_states_split;
  } integrator;

  /// The explicit integrator's stages (explicit_step): stage velocities and accelerations.
  struct RungeKutta {
    std::array<VectorX, 4> v, k;
  } rk4;

  /// The reason of the last failure (initialization, a step's restart), for a caller that
  /// only sees a status; fixed storage, written without allocating. A step that passed in
  /// pieces leaves it empty.
  std::array<char, 512> message{};

  Data() = default;
  /// Allocates everything for `model` and puts the bodies at their initial poses, at rest.
  explicit Data(const Model<Scalar>& model) { reset(model); }

  /// Back to the initial state of `model` (allocates: setup only).
  void reset(const Model<Scalar>& model) {
    const int nv = model.num_velocities(), nc = model.num_constraints();
    t = Scalar(0);
    q.setZero(model.num_coordinates());
    for (const auto& b : model.bodies()) {
      q.template segment<3>(b.q_offset) = b.initial_position;
      q.template segment<4>(b.q_offset + 3) = b.initial_orientation;
    }
    v.setZero(nv);
    v_dot.setZero(nv);
    a.setZero(nv);
    lambda.setZero(nc);
    joint_active.assign(model.joints().size(), 1);
    laws = model.laws();
    inputs.assign(model.inputs().size(), MotionValue<Scalar>());
    input_set.assign(model.inputs().size(), 0);
    inputs_start = inputs;
    input_t0 = input_t1 = Scalar(0);
    anchors.assign(static_cast<std::size_t>(model.num_marker_slots()), MarkerAnchor<Scalar>());
    revision = 0;
    force_states.clear();
    for (const auto& f : model.forces()) force_states.push_back(f.initial_state);
    outputs.setZero(model.num_outputs());
    meters.clear();
    for (const auto& m : model.meters()) meters.push_back(m.prototype);
    meter_refused.assign(model.meters().size(), 0);
    ground = Ground();
    rotation.assign(model.bodies().size(), Mat3<Scalar>::Identity());
    markers.assign(static_cast<std::size_t>(model.num_marker_slots()), MarkerState<Scalar>());
    for (std::size_t g = 0; g < model.ground_markers().size(); ++g)
      markers[static_cast<std::size_t>(model.ground_marker_slots()[g])] = model.ground_markers()[g];
    mass.setZero(model.mass_size());
    force.setZero(nv);
    geometric.setZero(model.geometric_size());
    jacobian.setZero(model.jacobian_size());
    phi.setZero(nc);
    phi_t.setZero(nc);
    conv.setZero(nc);
    int widest = 6;
    for (const auto& b : model.bodies()) widest = std::max(widest, b.nv);
    row_scratch.setZero(widest);
    row_scratch_j.setZero(widest);
    settings = model.settings();
    statistics = StepStatistics();
    Integrator& in = integrator;
    in = Integrator();
    in.iteration.setZero(nv, nv);
    in.cholesky.analyze(model.block_pattern());
    in.factorized_rotations.assign(model.bodies().size(), Mat3<Scalar>::Identity());
    in.correction_scale.setOnes(nv);
    for (const auto& b : model.bodies())
      for (int k = 0; k < b.modes; ++k)
        in.correction_scale(b.v_offset + 6 + k) = b.displacement_scale[static_cast<std::size_t>(k)];
    for (VectorX* x : {&in.r, &in.dx, &in.v_n, &in.vd_n, &in.a_n, &in.a1, &in.tmp, &in.vd_prev,
                       &in.v_save, &in.vd_save})
      x->setZero(nv);
    in.q_n.setZero(model.num_coordinates());
    in.q_save.setZero(model.num_coordinates());
    in.q_split.setZero(model.num_coordinates());
    in.force_states_split = force_states;  // its storage, for split steps
    for (VectorX* x : {&in.v_split, &in.vd_split, &in.a_split, &in.vd_prev_split}) x->setZero(nv);
    for (VectorX* x :
         {&in.e, &in.lambda_star, &in.lambda_last, &in.lambda_increment, &in.lambda_save,
          &in.lambda_pass, &in.lambda_split, &in.lambda_last_split, &in.lambda_increment_split})
      x->setZero(nc);
    for (int k = 0; k < 4; ++k) {
      rk4.v[static_cast<std::size_t>(k)].setZero(nv);
      rk4.k[static_cast<std::size_t>(k)].setZero(nv);
    }
    message.fill('\0');
  }
};

/// Input k at time t. set_input gives an input's value, rate and acceleration for the end of
/// the next step (d.inputs); inputs_start holds its values at the step's start (d.t when no
/// step is under way). Between them (the pieces of a split step, the stages of an explicit
/// step) the input follows the quintic through its values, rates and accelerations at the two
/// ends, as a law evaluated there would (held at the end's, an input would jump by the whole
/// step at the first piece). Outside a step, at d.t, it is the start's: what was set for the
/// next step is not yet in force.
template <class Scalar>
MotionValue<Scalar> input_value(const Data<Scalar>& d, int k, Scalar t) {
  const auto& start = d.inputs_start[static_cast<std::size_t>(k)];
  const auto& end = d.inputs[static_cast<std::size_t>(k)];
  const Scalar h = d.input_t1 - d.input_t0;
  if (!(h > Scalar(0)) || !(t > d.input_t0)) return start;
  if (!(t < d.input_t1)) return end;
  // s(tau) = sum c_i tau^i on [0, h], matching value, rate and acceleration at both ends.
  const Scalar tau = t - d.input_t0;
  const Scalar gap = end.value - start.value - start.rate * h - start.acceleration * h * h / 2;
  const Scalar rate_gap = end.rate - start.rate - start.acceleration * h;
  const Scalar acceleration_gap = end.acceleration - start.acceleration;
  const Scalar c3 = (20 * gap - 8 * rate_gap * h + acceleration_gap * h * h) / (2 * h * h * h);
  const Scalar c4 =
      (-30 * gap + 14 * rate_gap * h - 2 * acceleration_gap * h * h) / (2 * h * h * h * h);
  const Scalar c5 =
      (12 * gap - 6 * rate_gap * h + acceleration_gap * h * h) / (2 * h * h * h * h * h);
  const Scalar c2 = start.acceleration / 2;
  MotionValue<Scalar> v;
  v.value = start.value + tau * (start.rate + tau * (c2 + tau * (c3 + tau * (c4 + tau * c5))));
  v.rate = start.rate + tau * (2 * c2 + tau * (3 * c3 + tau * (4 * c4 + tau * 5 * c5)));
  v.acceleration = 2 * c2 + tau * (6 * c3 + tau * (12 * c4 + tau * 20 * c5));
  return v;
}

/// Driver law k at time t, input laws interpolated within the step (input_value).
template <class Scalar>
MotionValue<Scalar> law_value(const Data<Scalar>& d, int k, Scalar t) {
  const MotionLaw<Scalar>& law = d.laws[static_cast<std::size_t>(k)];
  if (law.kind == MotionLawKind::input) return input_value(d, law.input.index, t);
  return law(t, d.inputs.data());
}

/// A step of span h starts at d.t: input laws run from their values now to those set for its
/// end.
template <class Scalar>
void begin_input_span(Data<Scalar>& d, Scalar h) {
  d.input_t0 = d.t;
  d.input_t1 = d.t + h;
}

/// Whether a step is under way (initialize() inside it keeps its inputs' start).
template <class Scalar>
bool input_span_open(const Data<Scalar>& d) {
  return d.input_t1 > d.input_t0;
}

/// The step was taken: the inputs set for its end are the values now.
template <class Scalar>
void end_input_span(Data<Scalar>& d) {
  d.inputs_start = d.inputs;  // same sizes: no allocation
  d.input_t0 = d.input_t1 = d.t;
}

}  // namespace flexstress
