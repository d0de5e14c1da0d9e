// One run of the crane work cycle with one choice of every knob (bench/accuracy_vs_time): the
// hot-spot history it gives, what its steps and its stress recovery cost, and how much memory
// the step path touches. main.cpp compares runs against a reference.
#pragma once

#include <algorithm>
#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include <flexstress/dynamics/explicit_integrator.hpp>
#include <flexstress/dynamics/implicit_integrator.hpp>
#include <flexstress/stress/modal_stress_modes.hpp>
#include <flexstress/stress/sub_model_inertia.hpp>

#include "../../examples/crane/crane_scene.hpp"

namespace study {

using namespace flexstress;

enum class Recovery { fused, influence, stress_modes, resolve };
enum class Integrator { implicit, explicit_rk4 };
/// Effect lists a run can use (each one is a separate scene type, compiled in runs_*.cpp).
enum class EffectSet { all, no_quadratic_velocity, no_damping, gravity_only, with_stiffening };

/// The knobs of one run. Mode count, Scalar and effects pick the compiled scene type; the rest
/// are run-time settings.
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
  double step_bytes = 0;  ///< scene, state, integrator and the recovery's per-step data
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

/// The hot spot from a nodal stress field (modal stress modes): sigma_xx along the flange
/// surface line z = 0 from the toe, read at 0.4 t and 1.0 t by linear interpolation between
/// nodes, then IIW type a linear extrapolation (1.67, -0.67).
struct NodalHotSpot {
  std::vector<double> x;     ///< node positions along the line, from the toe
  std::vector<Index> entry;  ///< their entries in the modal stress modes
  double toe = 0, t = 0;

  template <class Modes>
  static NodalHotSpot build(const Modes& modes, const fe::Mesh& mesh, double toe, double y_top,
                            double t) {
    NodalHotSpot h;
    h.toe = toe;
    h.t = t;
    std::vector<std::pair<double, Index>> line;
    for (Index i = 0; i < modes.num_nodes(); ++i) {
      const Vector3d& p = mesh.node(modes.node(i));
      if (std::abs(p.y() - y_top) < 1e-9 && std::abs(p.z()) < 1e-9 && p.x() >= toe - 1e-9 &&
          p.x() <= toe + 2 * t)
        line.emplace_back(p.x(), i);
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

/// Runs the synthetic work cycle with N boom modes, Scalar and EffectList.
template <int N, class Scalar, class EffectList>
RunResult run_crane(const Knobs& k) {
  RunResult r;
  std::vector<double> t, ds;
  crane::synthetic_cycle(t, ds);
  const auto t_setup = Clock::now();
  auto made = crane::make_crane<N, fixed_storage_limit, Scalar, EffectList>(k.spec, t, ds);
  if (!made) {
    r.error = made.error().what();
    return r;
  }
  auto& cr = *made;
  using SceneT = typename std::decay_t<decltype(cr)>::SceneT;
  using ModalVector = Eigen::Matrix<Scalar, N, 1>;
  const auto& fused = *cr.fused;
  std::optional<stress::ModalStressModes<N, Scalar>> modes;
  NodalHotSpot nodal;
  if (k.recovery == Recovery::stress_modes) {
    auto m = stress::ModalStressModes<N, Scalar>::build(*cr.sub, cr.boundary_modes);
    if (!m) {
      r.error = m.error().what();
      return r;
    }
    modes.emplace(std::move(*m));
    nodal = NodalHotSpot::build(*modes, cr.sub->mesh(), cr.detail.weld_toe_x,
                                cr.detail.flange_surface_y, k.spec.wall);
    if (nodal.x.size() < 2) {
      r.error = "no nodes along the hot-spot line";
      return r;
    }
  }
  Eigen::Matrix<Scalar, 1, 12> inertia_row = Eigen::Matrix<Scalar, 1, 12>::Zero();
  if (k.submodel_inertia) {
    auto in = stress::SubModelInertia<Scalar>::build(*cr.sub, cr.outputs);
    if (!in) {
      r.error = in.error().what();
      return r;
    }
    inertia_row = in->rows().row(cr.hot_spot_row);
  }
  const MatrixXd phi_b = cr.boundary_modes.leftCols(N);
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> y(fused.num_outputs()), field;
  if (modes) field.resize(modes->modes().rows());

  // The hot spot of state s by the chosen recovery method.
  auto recover = [&](const typename SceneT::State& s) -> double {
    const ModalVector& p = s.template coordinates<0>().p;
    double hot = 0;
    switch (k.recovery) {
      case Recovery::fused:
        fused.evaluate(p, y);
        hot = double(y(cr.hot_spot_row));
        break;
      case Recovery::influence:
        fused.evaluate_by_influence(p, y);
        hot = double(y(cr.hot_spot_row));
        break;
      case Recovery::stress_modes:
        modes->evaluate(p, field);
        hot = nodal(field);
        break;
      case Recovery::resolve: {
        const VectorXd u = cr.sub->solve(phi_b * p.template cast<double>());
        hot = (*cr.outputs.rows(*cr.sub, u))(cr.hot_spot_row, 0);
        break;
      }
    }
    if (k.submodel_inertia)
      hot += double(inertia_row.dot(crane::boom_inertia_coordinates(cr.scene, s)));
    return hot / 1e6;
  };

  auto s = cr.initial;
  const auto steps = static_cast<long>(std::ceil((t.back() - t.front()) / k.step - 1e-9));
  std::vector<double> step_us, recovery_us;
  step_us.reserve(static_cast<std::size_t>(steps));
  recovery_us.reserve(static_cast<std::size_t>(steps));
  r.time.reserve(static_cast<std::size_t>(steps) + 1);
  r.hot_spot.reserve(static_cast<std::size_t>(steps) + 1);

  // The loop, shared by both integrators.
  auto run = [&](auto& integ) {
    r.precompute_ms = std::chrono::duration<double, std::milli>(Clock::now() - t_setup).count();
    r.step_bytes = double(sizeof(SceneT) + sizeof(s) + sizeof(integ));
    switch (k.recovery) {
      case Recovery::fused: r.step_bytes += double(fused.rows().size() * sizeof(Scalar)); break;
      case Recovery::influence:
        r.step_bytes += double((fused.num_outputs() * 12 + 12 * N) * sizeof(Scalar));
        break;
      case Recovery::stress_modes:
        r.step_bytes += double(modes->modes().size() * sizeof(Scalar));
        break;
      case Recovery::resolve: r.step_bytes = -1; break;  // the sparse factorization: not counted
    }
    r.time.push_back(double(s.t));
    r.hot_spot.push_back(recover(s));
    for (long i = 0; i < steps; ++i) {
      const auto a = Clock::now();
      const StepStatus st = integ.step(s);
      const auto b = Clock::now();
      const double hot = recover(s);
      const auto c = Clock::now();
      if (st == StepStatus::constraint_violation) {
        ++r.violations;
      } else if (st != StepStatus::ok) {
        r.error = std::string("step ") + std::to_string(i) + " at t = " + std::to_string(s.t) +
                  " s: " + to_string(st);
        return;
      }
      step_us.push_back(std::chrono::duration<double, std::micro>(b - a).count());
      recovery_us.push_back(std::chrono::duration<double, std::micro>(c - b).count());
      r.time.push_back(double(s.t));
      r.hot_spot.push_back(hot);
    }
  };
  if (k.integrator == Integrator::implicit) {
    typename ImplicitIntegrator<SceneT>::Settings set;
    set.step = Scalar(k.step);
    set.max_iterations = k.max_iterations;
    set.accept_at_iteration_limit = k.accept_at_iteration_limit;
    set.acceleration_tolerance = Scalar(k.acceleration_tolerance);
    ImplicitIntegrator<SceneT> integ(cr.scene, set);
    if (Status st = integ.initialize(s); !st) {
      r.error = st.error().what();
      return r;
    }
    run(integ);
    r.over_budget = integ.statistics().over_budget;
    r.iterations_per_step =
        double(integ.statistics().iterations) / double(std::max<std::size_t>(1, step_us.size()));
  } else {
    typename ExplicitIntegrator<SceneT>::Settings set;
    set.step = Scalar(k.step);
    ExplicitIntegrator<SceneT> integ(cr.scene, set);
    if (integ.stability_number() > set.stability_limit) {
      r.error = "h omega_max = " + std::to_string(double(integ.stability_number())) +
                " is above RK4's stability limit";
      return r;
    }
    run(integ);
  }
  r.step_us_median = percentile(step_us, 0.5);
  r.step_us_p99 = percentile(step_us, 0.99);
  r.step_us_max = percentile(step_us, 1.0);
  r.recovery_us_median = percentile(recovery_us, 0.5);
  r.recovery_us_max = percentile(recovery_us, 1.0);
  return r;
}

/// The compiled scene types, in units that compile in parallel: double with all effects at 2-8
/// modes (runs_few_modes.cpp) and 10-24 modes (runs_many_modes.cpp); float or fewer effects at
/// 16 and 8 modes (runs_variants_*.cpp). Each fails for a combination it does not compile.
RunResult run_few_modes(const Knobs& k);
RunResult run_many_modes(const Knobs& k);
RunResult run_variant(const Knobs& k);

inline RunResult run(const Knobs& k) {
  if (k.single_precision || k.effects != EffectSet::all) return run_variant(k);
  return k.modes < 10 ? run_few_modes(k) : run_many_modes(k);
}

inline RunResult not_compiled(const Knobs& k) {
  RunResult r;
  r.error = "no scene type compiled for " + std::to_string(k.modes) + " modes" +
            (k.single_precision ? ", float" : "") + " with these effects";
  return r;
}

}  // namespace study
