// The definitions of crane::Session (crane_session.hpp), for the one unit that instantiates the
// 10-mode stroke-driven crane (run_modes_10.cpp): the session adds no scene type of its own.
#pragma once

#include <utility>

#include "crane_run.hpp"
#include "crane_session.hpp"

namespace crane {

struct Session::Impl {
  using CraneT = Crane<10, fixed_storage_limit, double, CraneEffects>;
  using SceneT = CraneT::SceneT;
  CraneT crane;
  typename SceneT::State state;
  ImplicitIntegrator<SceneT> integrator;
  DamageMeter meter;
  VectorXd y;
  std::vector<double> stresses;
  std::vector<std::string> names;
  double step_size, end;
  std::string error;

  Impl(CraneT&& c, const RunOptions& o, DamageMeter&& m)
      : crane(std::move(c)),
        state(crane.initial),
        integrator(crane.scene, settings(o.step)),
        meter(std::move(m)),
        y(VectorXd::Zero(crane.fused->num_outputs())),
        stresses(static_cast<std::size_t>(crane.fused->num_outputs()), 0.0),
        step_size(o.step),
        end(o.t.back()) {
    for (Index i = 0; i < crane.outputs.num_outputs(); ++i) {
      const std::string& label = crane.outputs.label(i);
      names.push_back(label.empty() ? "output " + std::to_string(i) : label);
    }
  }
  static typename ImplicitIntegrator<SceneT>::Settings settings(double h) {
    typename ImplicitIntegrator<SceneT>::Settings s;
    s.step = h;
    return s;
  }
};

SessionOptions Session::default_options() {
  const RunOptions defaults;
  SessionOptions o;
  o.payload_kg = defaults.spec.payload_mass;
  o.step_s = defaults.step;
  o.submodel_density = defaults.spec.submodel_density;
  return o;
}

std::unique_ptr<Session> Session::create(const SessionOptions& options, std::string& error) {
  RunOptions o;
  o.spec.payload_mass = options.payload_kg;
  o.spec.submodel_density = options.submodel_density;
  o.step = options.step_s;
  if (options.cycle_time.empty()) {
    synthetic_cycle(o.t, o.ds);
  } else {
    o.t = options.cycle_time;
    o.ds = options.cycle_stroke;
    // The piston stays in its cylinder (the crane program's rule for stroke files).
    const double start = o.spec.hydraulics.initial_position, travel = o.spec.hydraulics.stroke;
    for (std::size_t i = 0; i < o.ds.size(); ++i)
      if (!(o.ds[i] >= -start && o.ds[i] <= travel - start)) {
        error = "cycle_stroke[" + std::to_string(i) + "] = " + std::to_string(o.ds[i]) +
                " m takes the piston out of the cylinder (the stroke may range from " +
                std::to_string(-start) + " to " + std::to_string(travel - start) + " m)";
        return nullptr;
      }
  }
  auto made = make_crane<10, fixed_storage_limit, double, CraneEffects>(o.spec, o.t, o.ds);
  if (!made) {
    error = made.error().what();
    return nullptr;
  }
  auto meter = make_damage_meter();
  if (!meter) {
    error = meter.error().what();
    return nullptr;
  }
  auto impl = std::make_unique<Impl>(std::move(*made), o, std::move(*meter));
  if (Status st = impl->integrator.initialize(impl->state); !st) {
    error = st.error().what();
    return nullptr;
  }
  impl->crane.fused->evaluate(impl->state.coordinates<0>().p, impl->y);
  for (std::size_t i = 0; i < impl->stresses.size(); ++i)
    impl->stresses[i] = impl->y(static_cast<Index>(i));
  return std::unique_ptr<Session>(new Session(std::move(impl)));
}

Session::Session(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Session::~Session() = default;

Session::Step Session::step() {
  Impl& m = *impl_;
  if (!m.error.empty()) return Step::failed;
  if (m.state.t >= m.end - 0.5 * m.step_size) return Step::cycle_over;
  if (const StepStatus st = m.integrator.step(m.state); st != StepStatus::ok) {
    m.error = std::string("step at t = ") + std::to_string(m.state.t) + " s: " + to_string(st);
    return Step::failed;
  }
  m.crane.fused->evaluate(m.state.coordinates<0>().p, m.y);
  for (std::size_t i = 0; i < m.stresses.size(); ++i) m.stresses[i] = m.y(static_cast<Index>(i));
  (void)m.meter.push(m.y(m.crane.hot_spot_row) / 1e6);  // the meter counts in MPa
  return Step::ok;
}

double Session::time() const {
  return impl_->state.t;
}
double Session::cycle_end() const {
  return impl_->end;
}
const std::vector<double>& Session::stresses() const {
  return impl_->stresses;
}
const std::vector<std::string>& Session::output_names() const {
  return impl_->names;
}
int Session::hot_spot_index() const {
  return static_cast<int>(impl_->crane.hot_spot_row);
}
double Session::damage_closed() const {
  return impl_->meter.closed_damage();
}
double Session::damage_per_cycle() const {
  return impl_->meter.damage(fatigue::CycleClosure::repeating);
}
const std::string& Session::error() const {
  return impl_->error;
}

}  // namespace crane
