// Builds a Model at run time and returns typed handles to its parts.
//
//   ModelBuilder<double> b;
//   BodyId boom = b.add_flexible_body("boom", boom_data, 10);
//   MarkerId a_boom = b.add_marker("A on boom", boom, node_a);
//   MarkerId a_ground = b.add_marker("A on ground", b.ground(), -1, Vector3d::Zero());
//   JointId a = b.add_joint("A", JointKind::revolute, a_ground, a_boom);
//   Result<Model<double>> model = b.finalize();  // every check, with the part's name
//
// A mistake (a node the body does not have, a mode count the data lacks, a law that is not
// finite, a joint between markers of one body) is recorded with the part's name and returned
// by finalize(), so building code reads straight through.
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/model/body_holder_ops.hpp"
#include "flexstress/model/body_kernels.hpp"
#include "flexstress/model/model.hpp"
#include "flexstress/reduction/modal_body.hpp"
#include "flexstress/reduction/mode_truncation.hpp"

#ifndef FLEXSTRESS_MODE_COUNTS
/// Mode counts whose body kernels are compiled with a fixed size (unrolled, vectorized); any
/// other count runs the bounded-size kernels. A build choice: each count costs compile time.
#define FLEXSTRESS_MODE_COUNTS 10, 16
#endif

namespace flexstress {

template <class Scalar>
class ModelBuilder {
 public:
  using ModelType = Model<Scalar>;

  /// The ground (fixed): markers on it take node -1 and an offset (the position).
  BodyId ground() const { return BodyId{-1}; }

  /// A rigid body: mass, centre of mass and inertia about the centre of mass (body frame); its
  /// frame starts at the global origin, unrotated (set_initial_pose moves it).
  BodyId add_rigid_body(const std::string& name, Scalar mass, const Vec3<Scalar>& center_of_mass,
                        const Mat3<Scalar>& inertia_about_com);

  /// A flexible body from reduced FE data keeping its lowest `modes` deformation modes (any
  /// count the data has, up to max_runtime_modes; reduction::truncation_warning's warning if
  /// they lose static flexibility at an interface node). Damping: the data's ratios.
  BodyId add_flexible_body(const std::string& name, const reduction::ModalBodyData& data,
                           int modes);

  /// Geometric stiffening of a flexible body under its own inertial and gravity loads: K_G
  /// from modal geometric stiffness per unit load case (reduction/modal_geometric_stiffness.hpp;
  /// at least the body's modes). What a fast-spinning or strongly accelerated body needs (the
  /// spin-up beam's stiffening); it costs one K_G per body and evaluation.
  void add_geometric_stiffening(BodyId b, const reduction::ModalGeometricStiffness& g) {
    Pending& p = body_entry(b, "add_geometric_stiffening");
    if (&p == &scratch_ || !p.holder) return;
    if (Status s = p.ops.set_geometric(p.holder.get(), g); !s.ok())
      fail(s.error().code, "body '", p.body.name, "': ", s.error().message);
    else
      p.body.effects.geometric_stiffening = true;
  }

  /// Flexible bodies added from now on run the bounded-size kernels even when their mode count
  /// has fixed-size ones: the same arithmetic in other storage, for checking one against the
  /// other (no faster, no smaller).
  void use_bounded_kernels(bool on = true) { bounded_kernels_ = on; }

  /// Sets the modal damping ratio of every mode of a flexible body.
  void set_damping_ratio(BodyId b, Scalar zeta) { body_entry(b, "set_damping_ratio").zeta = zeta; }
  /// Where a body's frame starts (the ground frame by default).
  void set_initial_pose(
      BodyId b, const Vec3<Scalar>& position,
      const EulerParameters<Scalar>& orientation = identity_euler_parameters<Scalar>()) {
    auto& e = body_entry(b, "set_initial_pose");
    e.body.initial_position = position;
    e.body.initial_orientation = orientation;
  }

  /// A marker on `body` at `node` (-1: the body frame; on the ground, the ground frame) with a
  /// rigid offset and axes (columns: marker axes in the body frame).
  MarkerId add_marker(const std::string& name, BodyId body, Index node,
                      const Vec3<Scalar>& offset = Vec3<Scalar>::Zero(),
                      const Mat3<Scalar>& axes = Mat3<Scalar>::Identity()) {
    typename ModelType::Marker m;
    m.name = name;
    m.body = body.index;
    if (!offset.allFinite() || !axes.allFinite()) {
      fail(ErrorCode::invalid_argument, "marker '", name, "': offset or axes not finite");
    } else if (body.index < -1 || body.index >= static_cast<int>(bodies_.size())) {
      fail(ErrorCode::invalid_argument, "marker '", name, "': no body with index ", body.index);
    } else if (body.index < 0) {
      if (node != -1)
        fail(ErrorCode::invalid_argument, "marker '", name,
             "': a ground marker has no node (use -1 and the offset)");
      m.local = static_cast<int>(ground_.size());
      MarkerState<Scalar> g;
      const auto set = [](VectorEval<Scalar>& e, const Vec3<Scalar>& value) {
        e.value = e.local = value;
        e.velocity.setZero();
        e.convective.setZero();
      };
      set(g.origin, offset);
      set(g.x, axes.col(0));
      set(g.y, axes.col(1));
      set(g.z, axes.col(2));
      ground_.push_back(g);
    } else {
      Pending& p = bodies_[static_cast<std::size_t>(body.index)];
      m.local = p.holder ? p.ops.add_marker(p.holder.get(), node, offset, axes) : -1;
      if (m.local < 0 && p.holder)
        fail(ErrorCode::invalid_mesh, "marker '", name, "': body '", p.body.name, "' has no node ",
             node, " (-1 is the body frame, the only node of a rigid body)");
    }
    markers_.push_back(std::move(m));
    return MarkerId{static_cast<int>(markers_.size()) - 1};
  }

  /// A joint of `kind` between marker i and marker j (on different bodies). Drivers take a law
  /// (add_driver); a distance joint its length (add_distance).
  JointId add_joint(const std::string& name, JointKind kind, MarkerId i, MarkerId j) {
    typename ModelType::Joint jt;
    jt.name = name;
    jt.kind = kind;
    jt.marker_i = i.index;
    jt.marker_j = j.index;
    if (is_driver(kind))
      fail(ErrorCode::invalid_argument, "joint '", name, "': a ", to_string(kind),
           " needs a motion law (add_driver)");
    joints_.push_back(std::move(jt));
    return JointId{static_cast<int>(joints_.size()) - 1};
  }
  /// |r_j - r_i| = length.
  JointId add_distance(const std::string& name, MarkerId i, MarkerId j, Scalar length) {
    const JointId id = add_joint(name, JointKind::distance, i, j);
    joints_.back().length = length;
    if (!(length > Scalar(0)) || !std::isfinite(double(length)))
      fail(ErrorCode::invalid_argument, "joint '", name, "': distance ", double(length),
           " must be positive and finite");
    return id;
  }
  /// A driver: prismatic ((r_j - r_i) . z_i = s(t), with a prismatic or cylindrical joint) or
  /// revolute (the angle from x_i to x_j about z_i = phi(t), with a revolute joint).
  JointId add_driver(const std::string& name, JointKind kind, MarkerId i, MarkerId j,
                     MotionLaw<Scalar> law) {
    typename ModelType::Joint jt;
    jt.name = name;
    jt.kind = kind;
    jt.marker_i = i.index;
    jt.marker_j = j.index;
    if (!is_driver(kind))
      fail(ErrorCode::invalid_argument, "joint '", name, "': ", to_string(kind),
           " is not a driver kind");
    jt.law = static_cast<int>(laws_.size());
    laws_.push_back(std::move(law));
    joints_.push_back(std::move(jt));
    return JointId{static_cast<int>(joints_.size()) - 1};
  }

  /// A spring-damper between the origins of two markers.
  ForceId add_spring_damper(const std::string& name, MarkerId i, MarkerId j,
                            const SpringDamperParams<Scalar>& params) {
    typename ModelType::Force f;
    f.name = name;
    f.marker_i = i.index;
    f.marker_j = j.index;
    f.params = params;
    if (!std::isfinite(double(params.stiffness)) || !std::isfinite(double(params.damping)) ||
        !std::isfinite(double(params.rest_length)) || !std::isfinite(double(params.preload)))
      fail(ErrorCode::invalid_argument, "force '", name,
           "': stiffness, damping, rest_length and preload must be finite");
    forces_.push_back(std::move(f));
    return ForceId{static_cast<int>(forces_.size()) - 1};
  }

  /// A valve-controlled hydraulic cylinder (dynamics/hydraulic_cylinder.hpp) between marker i
  /// (on the cylinder) and marker j (on the rod), the valve driven by `command` (u in -1..1),
  /// its chambers starting at pressures p_cap and p_rod (Pa). Its pressures are solved inside
  /// the implicit step.
  ForceId add_hydraulic_cylinder(const std::string& name, MarkerId i, MarkerId j,
                                 const HydraulicParams<Scalar>& params, MotionLaw<Scalar> command,
                                 Scalar p_cap, Scalar p_rod) {
    typename ModelType::Force f;
    f.name = name;
    f.kind = ForceKind::hydraulic_cylinder;
    f.marker_i = i.index;
    f.marker_j = j.index;
    f.hydraulic = params;
    f.initial_state.p1 = p_cap;
    f.initial_state.p2 = p_rod;
    if (const char* bad = hydraulics::check<Scalar>(params))
      fail(ErrorCode::invalid_argument, "force '", name, "': ", bad);
    if (!std::isfinite(double(p_cap)) || !std::isfinite(double(p_rod)))
      fail(ErrorCode::invalid_argument, "force '", name, "': chamber pressures must be finite");
    f.law = static_cast<int>(laws_.size());
    laws_.push_back(std::move(command));
    forces_.push_back(std::move(f));
    return ForceId{static_cast<int>(forces_.size()) - 1};
  }

  /// A force and moment at a marker on a body, computed each evaluation by `load` (see
  /// PointLoadFunction) with `user` passed through: wind, a tool's reaction, contact computed
  /// outside. Its work counts in EnergyBalance.
  ForceId add_point_load(const std::string& name, MarkerId marker, PointLoadFunction load,
                         void* user = nullptr) {
    typename ModelType::Force f;
    f.name = name;
    f.kind = ForceKind::point_load;
    f.marker_i = marker.index;
    f.load = load;
    f.user = user;
    if (load == nullptr) fail(ErrorCode::invalid_argument, "force '", name, "': no load function");
    forces_.push_back(std::move(f));
    return ForceId{static_cast<int>(forces_.size()) - 1};
  }

  /// Stress outputs of a flexible body: y = F p with F (outputs x the body's modes, e.g.
  /// stress::FusedStress rows), one name per row. Returns the set's outputs: [k] is row k's.
  OutputRange add_stress_outputs(const std::string& name, BodyId body,
                                 const Eigen::MatrixXd& fused_rows,
                                 const std::vector<std::string>& names = {}) {
    typename ModelType::OutputSet set;
    set.name = name;
    set.body = body.index;
    set.rows = fused_rows.cast<Scalar>();
    set.names = names;
    set.names.resize(static_cast<std::size_t>(fused_rows.rows()));
    for (std::size_t k = 0; k < set.names.size(); ++k)
      if (set.names[k].empty()) set.names[k] = name + "[" + std::to_string(k) + "]";
    if (body.index < 0 || body.index >= static_cast<int>(bodies_.size()))
      fail(ErrorCode::invalid_argument, "outputs '", name, "': no body with index ", body.index);
    else if (!fused_rows.allFinite())
      fail(ErrorCode::invalid_argument, "outputs '", name, "': rows not finite");
    set.first = num_outputs_;
    num_outputs_ += static_cast<int>(fused_rows.rows());
    const int first = set.first;
    const int count = static_cast<int>(set.rows.rows());
    output_sets_.push_back(std::move(set));
    return OutputRange{OutputId{first}, count};
  }
  /// Adds the sub-model's own weight and inertia to the outputs of the set that `first`
  /// starts: y += G g (stress::SubModelInertia rows, outputs x 12).
  void add_output_inertia(OutputId first, const Eigen::MatrixXd& inertia_rows) {
    for (auto& set : output_sets_)
      if (set.first == first.index) {
        if (inertia_rows.rows() != set.rows.rows() || inertia_rows.cols() != 12)
          fail(ErrorCode::size_mismatch, "outputs '", set.name, "': inertia rows are ",
               inertia_rows.rows(), "x", inertia_rows.cols(), ", need ", set.rows.rows(), "x12");
        set.inertia = inertia_rows.cast<Scalar>();
        return;
      }
    fail(ErrorCode::invalid_argument, "add_output_inertia: output ", first.index,
         " does not start a set");
  }
  /// A damage meter fed with scale * output after each step (evaluate_outputs).
  MeterId add_damage_meter(const std::string& name, OutputId output,
                           const DamageMeter<Scalar>& empty_meter, Scalar scale = Scalar(1)) {
    if (!output.valid())
      fail(ErrorCode::invalid_argument, "meter '", name,
           "': invalid output handle (a row outside its output set?)");
    else if (output.index >= num_outputs_)
      fail(ErrorCode::invalid_argument, "meter '", name, "': no output ", output.index);
    meters_.push_back({name, output.index, scale, empty_meter});
    return MeterId{static_cast<int>(meters_.size()) - 1};
  }

  /// A value set before each step (set_input), for MotionLaw::from_input.
  InputId add_input(const std::string& name) {
    inputs_.push_back(name);
    return InputId{static_cast<int>(inputs_.size()) - 1};
  }

  /// Moves the ground frame (see GroundMotion): its origin along x(t), y(t), z(t) and its turn
  /// by angle(t) about `axis` (global). Joints to the ground then move with it.
  void set_ground_motion(MotionLaw<Scalar> x, MotionLaw<Scalar> y, MotionLaw<Scalar> z,
                         MotionLaw<Scalar> angle,
                         const Vec3<Scalar>& axis = Vec3<Scalar>::UnitZ()) {
    if (!axis.allFinite() || !(axis.norm() > Scalar(0))) {
      fail(ErrorCode::invalid_argument, "ground motion: the axis must be finite and non-zero");
      return;
    }
    ground_axis_ = axis.normalized();
    ground_motion_.moving = true;
    int* index[4] = {&ground_motion_.x, &ground_motion_.y, &ground_motion_.z,
                     &ground_motion_.angle};
    MotionLaw<Scalar>* laws[4] = {&x, &y, &z, &angle};
    for (int k = 0; k < 4; ++k) {
      *index[k] = static_cast<int>(laws_.size());
      laws_.push_back(std::move(*laws[k]));
    }
  }

  /// Uniform gravity (global frame); without a call there is none.
  void set_gravity(const Vec3<Scalar>& g) {
    if (!g.allFinite()) fail(ErrorCode::invalid_argument, "gravity is not finite");
    gravity_ = g;
    has_gravity_ = true;
  }
  /// Leaves out the quadratic velocity vector (centrifugal, Coriolis and gyroscopic terms): an
  /// approximation, stated as one. Exact only for motions slow enough that they do not matter.
  void approximate_without_quadratic_velocity() { quadratic_velocity_ = false; }

  /// Integrator settings every Data of the model starts with.
  ImplicitSettings<Scalar>& settings() { return settings_; }

  /// Checks the model and builds it; the error names the first part that is wrong.
  Result<ModelType> finalize() const {
    if (!first_error_.message.empty()) return first_error_;
    if (bodies_.empty()) return make_error(ErrorCode::invalid_argument, "a model needs a body");
    ModelType m;
    const auto steps = settings_;
    if (Status checked = check_settings(steps); !checked) return checked.error();
    m.settings_ = steps;
    m.gravity_ = gravity_;
    m.has_gravity_ = has_gravity_;
    m.quadratic_velocity_ = quadratic_velocity_;
    m.warnings_ = warnings_;
    m.inputs_ = inputs_;
    m.ground_motion_ = ground_motion_;
    m.ground_axis_ = ground_axis_;
    if (ground_motion_.moving)
      for (int k : {ground_motion_.x, ground_motion_.y, ground_motion_.z, ground_motion_.angle}) {
        const auto& law = laws_[static_cast<std::size_t>(k)];
        if (const char* bad = law.check(static_cast<int>(inputs_.size())))
          return make_error(ErrorCode::invalid_argument, "ground motion: ", bad);
        if (const std::string fast = law.check_step(steps.step); !fast.empty())
          return make_error(ErrorCode::invalid_argument, "ground motion: ", fast);
      }
    // Bodies: offsets, effects, copies of the holders (a Model owns its bodies; builders may
    // go on adding to theirs).
    int nv = 0, nq = 0, mass = 0, geometric = 0;
    for (const Pending& p : bodies_) {
      typename ModelType::Body b = p.body;
      b.holder =
          p.ops.clone(p.holder.get(), p.zeta, b.displacement_scale, b.max_frequency, b.modes);
      b.nv = 6 + b.modes;
      b.v_offset = nv;
      b.q_offset = nq;
      b.mass_offset = mass;
      nv += b.nv;
      nq += 7 + b.modes;
      mass += b.nv * b.nv;
      b.effects.gravity = has_gravity_;
      b.effects.quadratic_velocity = quadratic_velocity_;
      b.effects.modal_damping = b.modes > 0 && p.ops.damps(p.holder.get(), p.zeta);
      if (b.effects.geometric_stiffening && b.modes > 0) {
        b.geometric_offset = geometric;
        geometric += b.modes * b.modes;
      } else {
        b.effects.geometric_stiffening = false;
      }
      m.bodies_.push_back(std::move(b));
    }
    m.geometric_size_ = geometric;
    m.nv_ = nv;
    m.nq_ = nq;
    m.mass_size_ = mass;
    // Marker slots: each body's markers together (its kernel evaluates them in one call), then
    // the ground's.
    m.markers_ = markers_;
    std::vector<int> count(bodies_.size(), 0);
    for (const auto& mk : markers_)
      if (mk.body >= 0) ++count[static_cast<std::size_t>(mk.body)];
    int slot = 0;
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
      m.bodies_[b].first_slot = slot;
      m.bodies_[b].num_markers = count[b];
      slot += count[b];
    }
    for (auto& mk : m.markers_)
      mk.slot = mk.body >= 0 ? m.bodies_[static_cast<std::size_t>(mk.body)].first_slot + mk.local
                             : slot + mk.local;
    m.slot_parts_.assign(static_cast<std::size_t>(slot) + ground_.size(), 0u);
    m.ground_markers_ = ground_;
    for (std::size_t g = 0; g < ground_.size(); ++g)
      m.ground_marker_slots_.push_back(slot + static_cast<int>(g));
    const auto marker_ok = [&](int id) {
      return id >= 0 && id < static_cast<int>(markers_.size());
    };
    // Joints: rows, Jacobian blocks, the marker parts they read.
    int row = 0, jac = 0;
    m.pattern_.block_sizes.clear();
    for (const auto& b : m.bodies_) m.pattern_.block_sizes.push_back(b.nv);
    for (const auto& src : joints_) {
      typename ModelType::Joint j = src;
      if (!marker_ok(j.marker_i) || !marker_ok(j.marker_j))
        return make_error(ErrorCode::invalid_argument, "joint '", j.name, "': its marker ",
                          marker_ok(j.marker_i) ? "j" : "i", " (handle ",
                          marker_ok(j.marker_i) ? j.marker_j : j.marker_i,
                          ") is not one of this model's ", markers_.size(), " markers");
      j.body_i = markers_[static_cast<std::size_t>(j.marker_i)].body;
      j.body_j = markers_[static_cast<std::size_t>(j.marker_j)].body;
      if (j.body_i == j.body_j)
        return make_error(ErrorCode::invalid_argument, "joint '", j.name, "': both markers are on ",
                          m.describe_body(j.body_i));
      j.equations = joint_equations(j.kind);
      j.row = row;
      row += j.equations;
      if (j.body_i >= 0) {
        j.jac_i = jac;
        jac += j.equations * m.bodies_[static_cast<std::size_t>(j.body_i)].nv;
      }
      if (j.body_j >= 0) {
        j.jac_j = jac;
        jac += j.equations * m.bodies_[static_cast<std::size_t>(j.body_j)].nv;
      }
      for (const auto& [body, block] : {std::pair{j.body_i, j.jac_i}, std::pair{j.body_j, j.jac_j}})
        if (body >= 0) {
          const auto& b = m.bodies_[static_cast<std::size_t>(body)];
          m.jacobian_blocks_.push_back({b.kernels->transpose_times, b.kernels->rows_times, b.nv,
                                        block, j.equations, j.row, b.v_offset});
        }
      if (j.body_i >= 0 && j.body_j >= 0) m.pattern_.couplings.emplace_back(j.body_i, j.body_j);
      m.slot_parts_[static_cast<std::size_t>(
          m.markers_[static_cast<std::size_t>(j.marker_i)].slot)] |= joint_parts_i(j.kind);
      m.slot_parts_[static_cast<std::size_t>(
          m.markers_[static_cast<std::size_t>(j.marker_j)].slot)] |= joint_parts_j(j.kind);
      if (j.law >= 0) {
        const auto& law = laws_[static_cast<std::size_t>(j.law)];
        if (const char* bad = law.check(static_cast<int>(inputs_.size())))
          return make_error(ErrorCode::invalid_argument, "joint '", j.name, "': ", bad);
        if (const std::string fast = law.check_step(steps.step); !fast.empty())
          return make_error(ErrorCode::invalid_argument, "joint '", j.name, "': ", fast);
      }
      m.joints_.push_back(std::move(j));
    }
    m.nc_ = row;
    m.jacobian_size_ = jac;
    for (const auto& src : forces_) {
      typename ModelType::Force f = src;
      if (f.kind == ForceKind::point_load) {
        if (!marker_ok(f.marker_i))
          return make_error(ErrorCode::invalid_argument, "force '", f.name,
                            "': the marker handle is not of this model");
        f.body_i = markers_[static_cast<std::size_t>(f.marker_i)].body;
        if (f.body_i < 0)
          return make_error(ErrorCode::invalid_argument, "force '", f.name,
                            "': a point load on the ground does nothing");
        m.slot_parts_[static_cast<std::size_t>(
            m.markers_[static_cast<std::size_t>(f.marker_i)].slot)] |=
            MarkerParts::all | marker_needs_rates;
        m.forces_.push_back(std::move(f));
        continue;
      }
      if (!marker_ok(f.marker_i) || !marker_ok(f.marker_j))
        return make_error(ErrorCode::invalid_argument, "force '", f.name, "': its marker ",
                          marker_ok(f.marker_i) ? "j" : "i", " (handle ",
                          marker_ok(f.marker_i) ? f.marker_j : f.marker_i,
                          ") is not one of this model's ", markers_.size(), " markers");
      f.body_i = markers_[static_cast<std::size_t>(f.marker_i)].body;
      f.body_j = markers_[static_cast<std::size_t>(f.marker_j)].body;
      if (f.kind == ForceKind::hydraulic_cylinder)
        if (const char* bad =
                laws_[static_cast<std::size_t>(f.law)].check(static_cast<int>(inputs_.size())))
          return make_error(ErrorCode::invalid_argument, "force '", f.name, "': ", bad);
      if (f.body_i == f.body_j)
        return make_error(ErrorCode::invalid_argument, "force '", f.name, "': both markers are on ",
                          m.describe_body(f.body_i));
      for (int mk : {f.marker_i, f.marker_j})
        m.slot_parts_[static_cast<std::size_t>(m.markers_[static_cast<std::size_t>(mk)].slot)] |=
            MarkerParts::origin | marker_needs_rates;
      // A spring-damper's tangent couples its bodies in the iteration matrix.
      auto& couplings = m.pattern_.couplings;
      if (f.kind == ForceKind::spring_damper && f.body_i >= 0 && f.body_j >= 0 &&
          std::find_if(couplings.begin(), couplings.end(), [&](const auto& c) {
            return (c.first == f.body_i && c.second == f.body_j) ||
                   (c.first == f.body_j && c.second == f.body_i);
          }) == couplings.end())
        couplings.emplace_back(f.body_i, f.body_j);
      m.forces_.push_back(std::move(f));
    }
    m.laws_ = laws_;
    for (const auto& set : output_sets_) {
      const auto& body = m.bodies_[static_cast<std::size_t>(set.body)];
      if (set.rows.cols() != body.modes)
        return make_error(ErrorCode::size_mismatch, "outputs '", set.name, "': rows have ",
                          set.rows.cols(), " columns, ", m.describe_body(set.body), " has ",
                          body.modes, " modes");
    }
    m.output_sets_ = output_sets_;
    m.meters_ = meters_;
    m.num_outputs_ = num_outputs_;
    return m;
  }

 private:
  struct Pending {
    typename ModelType::Body body;
    std::shared_ptr<void> holder;
    detail::BodyHolderOps<Scalar> ops;
    std::optional<Scalar> zeta;
  };

  template <class... Parts>
  void fail(ErrorCode code, const Parts&... parts) {
    if (first_error_.message.empty()) first_error_ = make_error(code, parts...);
  }

  Pending& body_entry(BodyId b, const char* what) {
    if (b.index < 0 || b.index >= static_cast<int>(bodies_.size())) {
      fail(ErrorCode::invalid_argument, what, ": no body with index ", b.index);
      return scratch_;
    }
    return bodies_[static_cast<std::size_t>(b.index)];
  }

  template <int... Ns>
  static void adopt_compiled(const reduction::ModalBodyData& data, int modes, bool& done,
                             Pending& p, Error& error, std::integer_sequence<int, Ns...>) {
    (detail::adopt_flexible<Scalar, Ns>(data, modes, done, p.holder, p.body.kernels, error), ...);
  }

  BodyId push(Pending p) {
    if (p.body.kernels != nullptr)
      p.ops = detail::body_holder_ops_for<Scalar>(
          p.body.kernels->fixed_modes, std::integer_sequence<int, FLEXSTRESS_MODE_COUNTS>{});
    bodies_.push_back(std::move(p));
    return BodyId{static_cast<int>(bodies_.size()) - 1};
  }

  std::vector<Pending> bodies_;
  Pending scratch_;
  std::vector<typename ModelType::Marker> markers_;
  std::vector<MarkerState<Scalar>> ground_;
  std::vector<typename ModelType::Joint> joints_;
  std::vector<typename ModelType::Force> forces_;
  std::vector<std::string> inputs_;
  std::vector<std::string> warnings_;
  std::vector<MotionLaw<Scalar>> laws_;
  std::vector<typename ModelType::OutputSet> output_sets_;
  std::vector<typename ModelType::Meter> meters_;
  int num_outputs_ = 0;
  Vec3<Scalar> gravity_ = Vec3<Scalar>::Zero();
  bool has_gravity_ = false;
  bool quadratic_velocity_ = true;
  bool bounded_kernels_ = false;
  GroundMotion ground_motion_;
  Vec3<Scalar> ground_axis_ = Vec3<Scalar>::UnitZ();
  ImplicitSettings<Scalar> settings_;
  Error first_error_{ErrorCode::invalid_argument, std::string()};
};

// Outside the class, so not inline: units that declare ModelBuilder extern (model/compiled.hpp)
// do not instantiate them, and with them every mode count's kernels (see core/precompute.hpp).
template <class Scalar>
BodyId ModelBuilder<Scalar>::add_rigid_body(const std::string& name, Scalar mass,
                                            const Vec3<Scalar>& center_of_mass,
                                            const Mat3<Scalar>& inertia_about_com) {
  Pending p;
  p.body.name = name;
  if (!(mass > Scalar(0)) || !center_of_mass.allFinite() || !inertia_about_com.allFinite())
    fail(ErrorCode::invalid_argument, "body '", name,
         "': a rigid body needs a positive mass and a finite centre of mass and inertia");
  std::tie(p.holder, p.body.kernels) = detail::make_holder<Scalar, 0>(
      BodyModel<Scalar, 0>::rigid(mass, center_of_mass, inertia_about_com));
  return push(std::move(p));
}

template <class Scalar>
BodyId ModelBuilder<Scalar>::add_flexible_body(const std::string& name,
                                               const reduction::ModalBodyData& data, int modes) {
  Pending p;
  p.body.name = name;
  if (modes < 0 || modes > data.num_modes) {
    fail(ErrorCode::size_mismatch, "body '", name, "': ", modes, " modes asked, the data has ",
         data.num_modes);
    modes = 0;
  }
  bool done = false;
  Error error;
  error.message.clear();
  if (!bounded_kernels_)
    adopt_compiled(data, modes, done, p, error,
                   std::integer_sequence<int, FLEXSTRESS_MODE_COUNTS>{});
  if (!done) {
    auto b = BodyModel<Scalar, Eigen::Dynamic>::from_modal_data(data, modes);
    if (b)
      std::tie(p.holder, p.body.kernels) =
          detail::make_holder<Scalar, Eigen::Dynamic>(std::move(*b));
    else
      error = b.error();
  }
  if (!error.message.empty())
    fail(error.code, "body '", name, "': ", error.message);
  else if (std::string w = reduction::truncation_warning(name, data, modes); !w.empty())
    warnings_.push_back(std::move(w));
  return push(std::move(p));
}

}  // namespace flexstress
