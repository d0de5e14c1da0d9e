// One run of the crane work cycle with one choice of every knob (bench/accuracy_vs_time): the
// hot-spot history it gives, what its steps and its stress recovery cost, and how much memory
// the step path touches. main.cpp compares runs against a reference. Every knob is a run-time
// choice on one model builder (examples/crane/crane_model.hpp); float is the model's Scalar.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include <flexstress/fe/stress_recovery.hpp>
#include <flexstress/stress/sub_model_inertia.hpp>

#include <flexstress/reduction/modal_geometric_stiffness.hpp>
#include <flexstress/stress/section_force_modes.hpp>
#include <flexstress/stress/sub_model_inertia.hpp>

#include "../../examples/crane/crane_model.hpp"
#include "../../examples/crane/detail_model.hpp"

namespace study {

using namespace flexstress;

enum class Recovery { fused, influence, stress_modes, resolve };
enum class Integrator { implicit, explicit_rk4 };
/// The effect sets the study compares (CraneOptions' switches).
enum class EffectSet { all, no_quadratic_velocity, no_damping, gravity_only, with_stiffening };

/// The knobs of one run.
struct Knobs {
  std::string name;   ///< unique, for the table
  std::string group;  ///< the knob this run varies ("reference", "modes", ..., "fast")
  int modes = 10;
  bool single_precision = false;
  EffectSet effects = EffectSet::all;
  double step = 1e-3;
  Integrator integrator = Integrator::implicit;
  int max_iterations = 30;
  bool accept_at_iteration_limit = false;
  double acceleration_tolerance = 1e-5;
  Recovery recovery = Recovery::fused;
  bool submodel_inertia = false;
  crane::CraneSpec spec;
};

struct RunResult {
  std::string error;  ///< empty: the run finished
  std::vector<double> time, hot_spot;
  double precompute_ms = 0;
  double step_us_median = 0, step_us_p99 = 0, step_us_max = 0;
  double recovery_us_median = 0, recovery_us_max = 0;
  double step_bytes = 0;  ///< the Data's storage and the recovery's per-step data
  long over_budget = 0, violations = 0;
  double iterations_per_step = 0;
};

using Clock = std::chrono::steady_clock;

inline double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  const auto k = static_cast<std::size_t>(q * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

inline crane::CraneOptions crane_options(const Knobs& k) {
  crane::CraneOptions o;
  o.modes = k.modes;
  // The fused rows carry the inertia in the model; the other recoveries add it themselves.
  o.with_inertia = k.submodel_inertia && k.recovery == Recovery::fused;
  switch (k.effects) {
    case EffectSet::all: break;
    case EffectSet::no_quadratic_velocity: o.quadratic_velocity = false; break;
    case EffectSet::no_damping: o.modal_damping = false; break;
    case EffectSet::gravity_only:
      o.quadratic_velocity = false;
      o.modal_damping = false;
      break;
    case EffectSet::with_stiffening: o.geometric_stiffening = true; break;
  }
  return o;
}

/// Modal stress modes at a run-time mode count (stress::ModalStressModes takes it as a template
/// parameter): S = N_s U Phi_b, the sub-model's nodal stress field per boom mode, nodes of its
/// bricks only.
template <class Scalar>
struct StressModes {
  std::vector<Index> nodes;
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> modes;  ///< (6 nodes) x boom modes

  static Result<StressModes> build(const stress::SubModel& sub, const MatrixXd& phi_b) {
    const fe::Mesh& mesh = sub.mesh();
    std::vector<char> in_brick(static_cast<std::size_t>(mesh.num_nodes()), 0);
    for (const fe::Hex8Element& h : mesh.hexes())
      for (Index n : h.nodes) in_brick[static_cast<std::size_t>(n)] = 1;
    StressModes m;
    for (Index n = 0; n < mesh.num_nodes(); ++n)
      if (in_brick[static_cast<std::size_t>(n)]) m.nodes.push_back(n);
    auto op = fe::nodal_stress_operator(mesh, sub.model().dofs, m.nodes);
    if (!op) return op.error();
    const MatrixXd field_per_mode = sub.unit_displacements() * phi_b;
    m.modes = (*op * field_per_mode).template cast<Scalar>();
    return m;
  }
};

/// The hot spot from a nodal stress field (modal stress modes): sigma_xx along the flange
/// surface line z = 0 from the toe, read at 0.4 t and 1.0 t by linear interpolation between
/// nodes, then IIW type a linear extrapolation (1.67, -0.67).
struct NodalHotSpot {
  std::vector<double> x;     ///< node positions along the line, from the toe
  std::vector<Index> entry;  ///< their entries in the modal stress modes
  double toe = 0, t = 0;

  static NodalHotSpot build(const std::vector<Index>& nodes, const fe::Mesh& mesh, double toe,
                            double y_top, double t) {
    NodalHotSpot h;
    h.toe = toe;
    h.t = t;
    std::vector<std::pair<double, Index>> line;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const Vector3d& p = mesh.node(nodes[i]);
      if (std::abs(p.y() - y_top) < 1e-9 && std::abs(p.z()) < 1e-9 && p.x() >= toe - 1e-9 &&
          p.x() <= toe + 2 * t)
        line.emplace_back(p.x(), static_cast<Index>(i));
    }
    std::sort(line.begin(), line.end());
    for (const auto& [px, i] : line) {
      h.x.push_back(px);
      h.entry.push_back(i);
    }
    return h;
  }
  template <class Field>
  double sigma_at(const Field& field, double xq) const {
    std::size_t k = 1;
    while (k + 1 < x.size() && x[k] < xq) ++k;
    const double w = (xq - x[k - 1]) / (x[k] - x[k - 1]);
    return (1 - w) * double(field(6 * entry[k - 1])) + w * double(field(6 * entry[k]));
  }
  template <class Field>
  double operator()(const Field& field) const {
    return 1.67 * sigma_at(field, toe + 0.4 * t) - 0.67 * sigma_at(field, toe + 1.0 * t);
  }
};

/// Bytes of a Data's numeric storage: state, workspace and the integrators' history and
/// scratch (the model's body data sits behind opaque holders and is not counted).
template <class Scalar>
double data_bytes(const Data<Scalar>& d) {
  std::size_t n = 0;
  for (const auto* x : {&d.q,
                        &d.v,
                        &d.v_dot,
                        &d.a,
                        &d.lambda,
                        &d.mass,
                        &d.force,
                        &d.geometric,
                        &d.jacobian,
                        &d.phi,
                        &d.phi_t,
                        &d.conv,
                        &d.row_scratch,
                        &d.integrator.r,
                        &d.integrator.dx,
                        &d.integrator.v_n,
                        &d.integrator.vd_n,
                        &d.integrator.a_n,
                        &d.integrator.a1,
                        &d.integrator.tmp,
                        &d.integrator.vd_prev,
                        &d.integrator.v_save,
                        &d.integrator.vd_save,
                        &d.integrator.q_n,
                        &d.integrator.q_save,
                        &d.integrator.e,
                        &d.integrator.lambda_star,
                        &d.integrator.lambda_increment,
                        &d.integrator.lambda_save})
    n += static_cast<std::size_t>(x->size()) * sizeof(Scalar);
  n += static_cast<std::size_t>(d.integrator.iteration.size()) * sizeof(Scalar);
  n += d.markers.size() * sizeof(d.markers[0]) + d.rotation.size() * sizeof(d.rotation[0]);
  return double(n);
}

/// Runs the synthetic work cycle with the model in Scalar.
template <class Scalar>
RunResult run_crane(const Knobs& k) {
  using VectorS = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using MatrixS = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  RunResult r;
  std::vector<double> t, ds;
  crane::synthetic_cycle(t, ds);
  const auto t_setup = Clock::now();
  auto made = crane::make_crane<Scalar>(k.spec, crane_options(k), t, ds);
  if (!made) {
    r.error = made.error().what();
    return r;
  }
  const auto& cr = *made;
  const Model<Scalar>& model = cr.model;
  const crane::Detail& detail = cr.detail;
  const stress::SubModel& sub = *detail.model->sub;
  const Index hot_row = detail.hot_spot;
  const MatrixXd phi_b = detail.boundary_modes.leftCols(k.modes);
  MatrixS influence, phi_b_s;
  VectorS u_b, y;
  StressModes<Scalar> modes;
  VectorS field;
  NodalHotSpot nodal;
  if (k.recovery == Recovery::influence) {
    auto rows = detail.model->outputs.rows(sub);
    if (!rows) {
      r.error = rows.error().what();
      return r;
    }
    influence = rows->template cast<Scalar>();
    phi_b_s = phi_b.cast<Scalar>();
    u_b.resize(phi_b_s.rows());
    y.resize(influence.rows());
  } else if (k.recovery == Recovery::stress_modes) {
    auto m = StressModes<Scalar>::build(sub, phi_b);
    if (!m) {
      r.error = m.error().what();
      return r;
    }
    modes = std::move(*m);
    field.resize(modes.modes.rows());
    nodal = NodalHotSpot::build(modes.nodes, sub.mesh(), detail.model->mesh.weld_toe_x,
                                detail.model->mesh.flange_surface_y, k.spec.wall);
    if (nodal.x.size() < 2) {
      r.error = "no nodes along the hot-spot line";
      return r;
    }
  }
  Eigen::Matrix<Scalar, 1, 12> inertia_row = Eigen::Matrix<Scalar, 1, 12>::Zero();
  const bool own_inertia = k.submodel_inertia && k.recovery != Recovery::fused;
  if (own_inertia) {
    auto in = stress::SubModelInertia<Scalar>::build(sub, detail.model->outputs);
    if (!in) {
      r.error = in.error().what();
      return r;
    }
    inertia_row = in->rows().row(hot_row);
  }

  Data<Scalar> d = cr.initial;
  // The hot spot at d's state by the chosen recovery method.
  auto recover = [&]() -> double {
    double hot = 0;
    switch (k.recovery) {
      case Recovery::fused:
        (void)evaluate_outputs(model, d, /*feed_meters=*/false);
        hot = double(output_value(d, cr.output(hot_row)));
        break;
      case Recovery::influence:
        u_b.noalias() = phi_b_s * modal_coordinates(model, d, cr.boom_body);
        y.noalias() = influence * u_b;
        hot = double(y(hot_row));
        break;
      case Recovery::stress_modes:
        field.noalias() = modes.modes * modal_coordinates(model, d, cr.boom_body);
        hot = nodal(field);
        break;
      case Recovery::resolve: {
        const VectorXd u =
            sub.solve(phi_b * modal_coordinates(model, d, cr.boom_body).template cast<double>());
        hot = (*detail.model->outputs.rows(sub, u))(hot_row, 0);
        break;
      }
    }
    if (own_inertia)
      hot += double(inertia_row.dot(body_inertia_coordinates(model, d, cr.boom_body.index)));
    return hot / 1e6;
  };

  const auto steps = static_cast<long>(std::ceil((t.back() - t.front()) / k.step - 1e-9));
  std::vector<double> step_us, recovery_us;
  step_us.reserve(static_cast<std::size_t>(steps));
  recovery_us.reserve(static_cast<std::size_t>(steps));
  r.time.reserve(static_cast<std::size_t>(steps) + 1);
  r.hot_spot.reserve(static_cast<std::size_t>(steps) + 1);

  // The loop, shared by both integrators.
  auto run = [&](auto&& step_once) {
    r.precompute_ms = std::chrono::duration<double, std::milli>(Clock::now() - t_setup).count();
    r.step_bytes = data_bytes(d);
    switch (k.recovery) {
      case Recovery::fused:
        for (const auto& set : model.output_sets())
          r.step_bytes += double((set.rows.size() + set.inertia.size()) * sizeof(Scalar));
        break;
      case Recovery::influence:
        r.step_bytes += double((influence.size() + phi_b_s.size()) * sizeof(Scalar));
        break;
      case Recovery::stress_modes:
        r.step_bytes += double(modes.modes.size() * sizeof(Scalar));
        break;
      case Recovery::resolve: r.step_bytes = -1; break;  // the sparse factorization: not counted
    }
    r.time.push_back(double(d.t));
    r.hot_spot.push_back(recover());
    for (long i = 0; i < steps; ++i) {
      const auto a = Clock::now();
      const StepStatus st = step_once();
      const auto b = Clock::now();
      const double hot = recover();
      const auto c = Clock::now();
      if (st == StepStatus::constraint_violation) {
        ++r.violations;
      } else if (st != StepStatus::ok && st != StepStatus::budget_reached) {
        r.error = std::string("step ") + std::to_string(i) + " at t = " + std::to_string(d.t) +
                  " s: " + to_string(st);
        return;
      }
      step_us.push_back(std::chrono::duration<double, std::micro>(b - a).count());
      recovery_us.push_back(std::chrono::duration<double, std::micro>(c - b).count());
      r.time.push_back(double(d.t));
      r.hot_spot.push_back(hot);
    }
  };
  if (k.integrator == Integrator::implicit) {
    ImplicitSettings<Scalar> set = d.settings;
    set.step = Scalar(k.step);
    set.max_iterations = k.max_iterations;
    set.accept_at_iteration_limit = k.accept_at_iteration_limit;
    set.acceleration_tolerance = Scalar(k.acceleration_tolerance);
    set.relative_acceleration_tolerance = Scalar(0);  // the study's tolerances are absolute
    Status st = set_settings(model, d, set);
    if (st) st = initialize(model, d);
    if (!st) {
      r.error = st.error().what();
      return r;
    }
    run([&] { return step(model, d); });
    r.over_budget = d.statistics.over_budget;
    r.iterations_per_step =
        double(d.statistics.iterations) / double(std::max<std::size_t>(1, step_us.size()));
  } else {
    ExplicitSettings<Scalar> set;
    set.step = Scalar(k.step);
    if (stability_number(model, set.step) > set.stability_limit) {
      r.error = "h omega_max = " + std::to_string(double(stability_number(model, set.step))) +
                " is above RK4's stability limit";
      return r;
    }
    run([&] { return explicit_step(model, d, set); });
  }
  r.step_us_median = percentile(step_us, 0.5);
  r.step_us_p99 = percentile(step_us, 0.99);
  r.step_us_max = percentile(step_us, 1.0);
  r.recovery_us_median = percentile(recovery_us, 0.5);
  r.recovery_us_max = percentile(recovery_us, 1.0);
  return r;
}

inline RunResult run(const Knobs& k) {
  return k.single_precision ? run_crane<float>(k) : run_crane<double>(k);
}

}  // namespace study
