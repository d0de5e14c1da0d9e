// crane::Session (crane_session.hpp) on the crane's runtime model: a model, its Data, and the
// detail's stresses copied out after each step.
#include "crane_session.hpp"

#include <utility>

#include "crane_run.hpp"

namespace crane {

struct Session::Impl {
  Crane crane;
  Data<double> data;
  std::vector<double> stresses;
  std::vector<std::string> names;
  double step_size, end;
  std::string error;

  Impl(Crane&& c, const RunOptions& o)
      : crane(std::move(c)),
        data(start_data(crane, o)),
        stresses(static_cast<std::size_t>(crane.model.num_outputs()), 0.0),
        names(crane.detail.names),
        step_size(o.step),
        end(o.t.back()) {
    data.settings.refresh_workspace = true;
    data.settings.acceleration_tolerance = ImplicitSettings<double>().acceleration_tolerance;
  }
  void copy_stresses() {
    for (std::size_t i = 0; i < stresses.size(); ++i)
      stresses[i] = output_value(data, crane.output(static_cast<Index>(i)));
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
  auto made = make_crane(o.spec, o.crane, o.t, o.ds);
  if (!made) {
    error = made.error().what();
    return nullptr;
  }
  auto impl = std::make_unique<Impl>(std::move(*made), o);
  if (Status st = initialize(impl->crane.model, impl->data); !st) {
    error = st.error().what();
    return nullptr;
  }
  (void)evaluate_outputs(impl->crane.model, impl->data, /*feed_meters=*/false);
  impl->copy_stresses();
  return std::unique_ptr<Session>(new Session(std::move(impl)));
}

Session::Session(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Session::~Session() = default;

Session::Step Session::step() {
  Impl& m = *impl_;
  if (!m.error.empty()) return Step::failed;
  if (m.data.t >= m.end - 0.5 * m.step_size) return Step::cycle_over;
  if (const StepStatus st = flexstress::step(m.crane.model, m.data); st != StepStatus::ok) {
    m.error = std::string("step at t = ") + std::to_string(m.data.t) + " s: " + to_string(st);
    return Step::failed;
  }
  (void)evaluate_outputs(m.crane.model, m.data);  // the meter counts in MPa
  m.copy_stresses();
  return Step::ok;
}

double Session::time() const {
  return impl_->data.t;
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
  return static_cast<int>(impl_->crane.detail.hot_spot);
}
double Session::damage_closed() const {
  return impl_->data.meters[std::size_t(impl_->crane.hot_spot_meter.index)].closed_damage();
}
double Session::damage_per_cycle() const {
  return meter_damage(impl_->data, impl_->crane.hot_spot_meter);
}
const std::string& Session::error() const {
  return impl_->error;
}

}  // namespace crane
