// The C interface (flexstress/flexstress.h) over the runtime model: data, initialization,
// steps, runtime changes, checkpoints and read-outs. Every entry point checks its pointers and
// handles before touching the model and catches every exception (src/c_api_internal.hpp).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "c_api_internal.hpp"

using namespace flexstress_c_api;

namespace {

/// fs_linearize and fs_linearized_frequencies, errors named after the function called.
int linearize_into(const char* function, fs_data* d, double* hz, int capacity, int* count,
                   double* static_residual) {
  if (count) *count = 0;
  if (static_residual) *static_residual = kNaN;
  return guarded(function, [&] {
    if (!d || (!hz && capacity > 0)) return null_argument(function);
    auto lin = fsx::linearize(*d->model, d->data);
    if (!lin) return error_status(d, lin.error());
    const int n = static_cast<int>(lin->frequencies_hz.size());
    if (count) *count = n;
    if (static_residual) *static_residual = lin->static_residual;
    for (int k = 0; k < std::min(n, std::max(capacity, 0)); ++k) hz[k] = lin->frequencies_hz(k);
    if (capacity < n)
      return fail(FS_ERROR_BUFFER_TOO_SMALL, std::string(function) + ": " + std::to_string(n) +
                                                 " frequencies, room for " +
                                                 std::to_string(capacity));
    return int(FS_OK);
  });
}

}  // namespace

extern "C" {

// ---- data -----------------------------------------------------------------------------------

fs_data* fs_data_create(const fs_model* m) {
  fs_data* out = nullptr;
  guarded("fs_data_create", [&] {
    if (!model_of(m)) return null_argument("fs_data_create");
    auto d = std::make_unique<fs_data>();
    d->model = m->model;
    d->data.reset(*d->model);
    out = d.release();
    return int(FS_OK);
  });
  return out;
}
void fs_data_destroy(fs_data* d) {
  delete d;
}

int fs_data_reset(fs_data* d) {
  return guarded("fs_data_reset", [&] {
    if (!d) return null_argument("fs_data_reset");
    d->data.reset(*d->model);
    d->error.clear();
    return int(FS_OK);
  });
}

const char* fs_data_error(const fs_data* d) {
  return d ? d->error.c_str() : "fs_data_error: null data";
}

int fs_initialize(fs_data* d) {
  return guarded("fs_initialize", [&] {
    if (!d) return null_argument("fs_initialize");
    const fsx::Status s = fsx::initialize(*d->model, d->data);
    if (!s.ok()) return error_status(d, s.error());
    d->error.clear();
    return int(FS_OK);
  });
}

int fs_solve_static_equilibrium(fs_data* d) {
  return guarded("fs_solve_static_equilibrium", [&] {
    if (!d) return null_argument("fs_solve_static_equilibrium");
    const fsx::Status s = fsx::solve_static_equilibrium(*d->model, d->data);
    if (!s.ok()) return error_status(d, s.error());
    d->error.clear();
    return int(FS_OK);
  });
}

int fs_step(fs_data* d) {
  if (!d) return null_argument("fs_step"), FS_STEP_ERROR;
  try {
    const fsx::StepStatus s = fsx::step(*d->model, d->data);
    if (s != fsx::StepStatus::ok && s != fsx::StepStatus::budget_reached) {
      // The step's reason (where it failed, or why a restart did), else the status's text.
      d->error = d->data.message[0] != '\0' ? d->data.message.data() : fsx::to_string(s);
      fail(FS_ERROR_NOT_CONVERGED, d->error);
    }
    return static_cast<int>(s);
  } catch (...) {
    fail_noexcept(FS_ERROR_INTERNAL, "fs_step", "unexpected exception");
    return FS_STEP_ERROR;
  }
}

int fs_set_step_size(fs_data* d, double step) {
  if (!d) return null_argument("fs_set_step_size");
  if (!(step > 0) || !std::isfinite(step))
    return fail(FS_ERROR_INVALID_ARGUMENT, "fs_set_step_size: the step must be positive");
  fsx::set_step_size(d->data, step);
  return FS_OK;
}

int fs_settings_get(const fs_data* d, fs_settings* out) {
  if (!d || !out) return null_argument("fs_settings_get");
  const auto& s = d->data.settings;
  out->step = s.step;
  out->spectral_radius = s.spectral_radius;
  out->max_iterations = s.max_iterations;
  out->accept_at_iteration_limit = s.accept_at_iteration_limit ? 1 : 0;
  out->acceleration_tolerance = s.acceleration_tolerance;
  out->relative_acceleration_tolerance = s.relative_acceleration_tolerance;
  out->local_error_tolerance = s.local_error_tolerance;
  out->max_step_halvings = s.max_step_halvings;
  out->velocity_drift_limit = s.velocity_drift_limit;
  out->project_velocities = s.project_velocities ? 1 : 0;
  out->newton_error_estimate_fraction = s.newton_error_estimate_fraction;
  out->keep_stalled_steps = s.keep_stalled_steps ? 1 : 0;
  out->linearized_multipliers = static_cast<int>(s.linearized_multipliers);
  out->refactorize_pieces = s.refactorize_pieces ? 1 : 0;
  out->piece_newton_tolerance_fraction = s.piece_newton_tolerance_fraction;
  return FS_OK;
}

int fs_settings_set(fs_data* d, const fs_settings* in) {
  return guarded("fs_settings_set", [&] {
    if (!d || !in) return null_argument("fs_settings_set");
    auto s = d->data.settings;
    s.step = in->step;
    s.spectral_radius = in->spectral_radius;
    s.max_iterations = in->max_iterations;
    s.accept_at_iteration_limit = in->accept_at_iteration_limit != 0;
    s.acceleration_tolerance = in->acceleration_tolerance;
    s.relative_acceleration_tolerance = in->relative_acceleration_tolerance;
    s.local_error_tolerance = in->local_error_tolerance;
    s.max_step_halvings = in->max_step_halvings;
    s.velocity_drift_limit = in->velocity_drift_limit;
    s.project_velocities = in->project_velocities != 0;
    s.newton_error_estimate_fraction = in->newton_error_estimate_fraction;
    s.keep_stalled_steps = in->keep_stalled_steps != 0;
    s.linearized_multipliers = static_cast<fsx::LinearizedMultipliers>(in->linearized_multipliers);
    s.refactorize_pieces = in->refactorize_pieces != 0;
    s.piece_newton_tolerance_fraction = in->piece_newton_tolerance_fraction;
    const fsx::Status st = fsx::set_settings(*d->model, d->data, s);
    if (!st.ok()) return fail(FS_ERROR_INVALID_ARGUMENT, "fs_settings_set: " + st.error().what());
    return int(FS_OK);
  });
}

double fs_time(const fs_data* d) {
  return d ? d->data.t : kNaN;
}

int fs_set_input(fs_data* d, int input, double value, double rate, double acceleration) {
  if (!d) return null_argument("fs_set_input");
  if (!in_range(input, d->model->inputs().size()))
    return bad_handle("fs_set_input", "input", input);
  if (fsx::set_input(*d->model, d->data, fsx::InputId{input}, value, rate, acceleration) !=
      fsx::StepStatus::ok)
    return fail(FS_ERROR_INVALID_ARGUMENT, "fs_set_input: a value is not finite");
  return FS_OK;
}

int fs_set_joint_active(fs_data* d, int joint, int active) {
  if (!d) return null_argument("fs_set_joint_active");
  if (!in_range(joint, d->model->joints().size()))
    return bad_handle("fs_set_joint_active", "joint", joint);
  fsx::set_joint_active(*d->model, d->data, fsx::JointId{joint}, active != 0);
  return FS_OK;
}

int fs_anchor_joint(fs_data* d, int joint) {
  return guarded("fs_anchor_joint", [&] {
    if (!d) return null_argument("fs_anchor_joint");
    if (!in_range(joint, d->model->joints().size()))
      return bad_handle("fs_anchor_joint", "joint", joint);
    const fsx::Status s = fsx::anchor_joint_at(*d->model, d->data, fsx::JointId{joint});
    return s.ok() ? int(FS_OK) : error_status(d, s.error());
  });
}

int fs_set_body_velocity(fs_data* d, int body, const double velocity[3],
                         const double omega_body[3]) {
  if (!d || !velocity || !omega_body) return null_argument("fs_set_body_velocity");
  if (!in_range(body, d->model->bodies().size()))
    return bad_handle("fs_set_body_velocity", "body", body);
  fsx::set_body_velocity(*d->model, d->data, fsx::BodyId{body}, vec3(velocity), vec3(omega_body));
  return FS_OK;
}

int fs_checkpoint_save(const fs_data* d, unsigned char* buffer, size_t capacity, size_t* size) {
  return guarded("fs_checkpoint_save", [&] {
    if (!d || !size) return null_argument("fs_checkpoint_save");
    auto bytes = fsx::save_checkpoint(*d->model, d->data);
    if (!bytes) return fail(status_of(bytes.error().code), bytes.error().what());
    *size = bytes->size();
    if (!buffer) return int(FS_OK);
    if (capacity < bytes->size())
      return fail(FS_ERROR_BUFFER_TOO_SMALL, "fs_checkpoint_save: the checkpoint takes " +
                                                 std::to_string(bytes->size()) +
                                                 " bytes, the buffer " + std::to_string(capacity));
    std::memcpy(buffer, bytes->data(), bytes->size());
    return int(FS_OK);
  });
}

int fs_checkpoint_restore(fs_data* d, const unsigned char* buffer, size_t size) {
  return guarded("fs_checkpoint_restore", [&] {
    if (!d || !buffer) return null_argument("fs_checkpoint_restore");
    const fsx::Status s = fsx::restore_checkpoint(*d->model, d->data, buffer, size);
    return s.ok() ? int(FS_OK) : error_status(d, s.error());
  });
}

int fs_set_law(fs_data* d, int joint, const fs_motion_law* law) {
  return guarded("fs_set_law", [&] {
    if (!d || !law) return null_argument("fs_set_law");
    if (!in_range(joint, d->model->joints().size()))
      return bad_handle("fs_set_law", "joint", joint);
    auto l = to_law(*law);
    if (!l) return error_status(d, l.error());
    const fsx::Status s = fsx::set_law(*d->model, d->data, fsx::JointId{joint}, std::move(*l));
    if (!s.ok()) return error_status(d, s.error());
    return int(FS_OK);
  });
}

// ---- read-outs ------------------------------------------------------------------------------

namespace {
// Checks a data, a body handle and an output pointer.
int check_body(const fs_data* d, int body, const void* out, const char* where) {
  if (!d || !out) return null_argument(where);
  if (!in_range(body, d->model->bodies().size())) return bad_handle(where, "body", body);
  return FS_OK;
}
}  // namespace

int fs_body_position(const fs_data* d, int body, double position[3]) {
  if (const int s = check_body(d, body, position, "fs_body_position")) return s;
  put3(fsx::body_position(*d->model, d->data, fsx::BodyId{body}), position);
  return FS_OK;
}
int fs_body_orientation(const fs_data* d, int body, double e[4]) {
  if (const int s = check_body(d, body, e, "fs_body_orientation")) return s;
  const auto q = fsx::body_orientation(*d->model, d->data, fsx::BodyId{body});
  for (int k = 0; k < 4; ++k) e[k] = q(k);
  return FS_OK;
}
int fs_body_velocity(const fs_data* d, int body, double velocity[3]) {
  if (const int s = check_body(d, body, velocity, "fs_body_velocity")) return s;
  put3(fsx::body_velocity(*d->model, d->data, fsx::BodyId{body}), velocity);
  return FS_OK;
}
int fs_body_angular_velocity(const fs_data* d, int body, double omega[3]) {
  if (const int s = check_body(d, body, omega, "fs_body_angular_velocity")) return s;
  put3(fsx::body_angular_velocity(*d->model, d->data, fsx::BodyId{body}), omega);
  return FS_OK;
}

int fs_marker_frame(const fs_data* d, int marker, double origin[3], double axes[9]) {
  return guarded("fs_marker_frame", [&] {
    if (!d || !origin) return null_argument("fs_marker_frame");
    if (!in_range(marker, d->model->markers().size()))
      return bad_handle("fs_marker_frame", "marker", marker);
    const auto f = fsx::marker_frame(*d->model, d->data, fsx::MarkerId{marker});
    put3(f.origin, origin);
    if (axes) {
      Eigen::Map<fsx::Mat3<double>> out(axes);
      out = f.axes;
    }
    return int(FS_OK);
  });
}

int fs_joint_reaction(const fs_data* d, int joint, double force[3], double moment[3]) {
  return guarded("fs_joint_reaction", [&] {
    if (!d || !force || !moment) return null_argument("fs_joint_reaction");
    if (!in_range(joint, d->model->joints().size()))
      return bad_handle("fs_joint_reaction", "joint", joint);
    const auto r = fsx::joint_reaction(*d->model, d->data, fsx::JointId{joint});
    put3(r.force, force);
    put3(r.moment, moment);
    return int(FS_OK);
  });
}

int fs_driver_effort(const fs_data* d, int joint, double* effort) {
  return guarded("fs_driver_effort", [&] {
    if (!d || !effort) return null_argument("fs_driver_effort");
    if (!in_range(joint, d->model->joints().size()))
      return bad_handle("fs_driver_effort", "joint", joint);
    if (!fsx::is_driver(d->model->joints()[static_cast<std::size_t>(joint)].kind))
      return fail(FS_ERROR_INVALID_ARGUMENT,
                  "fs_driver_effort: " + d->model->describe_joint(joint) + " is not a driver");
    *effort = fsx::driver_effort(*d->model, d->data, fsx::JointId{joint});
    return int(FS_OK);
  });
}

int fs_joint_coordinate(const fs_data* d, int joint, double* value, double* rate) {
  return guarded("fs_joint_coordinate", [&] {
    if (!d || !value || !rate) return null_argument("fs_joint_coordinate");
    if (!in_range(joint, d->model->joints().size()))
      return bad_handle("fs_joint_coordinate", "joint", joint);
    const auto c = fsx::joint_coordinate(*d->model, d->data, fsx::JointId{joint});
    if (!c.defined)
      return fail(FS_ERROR_INVALID_ARGUMENT,
                  "fs_joint_coordinate: " + d->model->describe_joint(joint) +
                      " has no single coordinate (revolute or "
                      "prismatic joints and drivers have one)");
    *value = c.value;
    *rate = c.rate;
    return int(FS_OK);
  });
}

int fs_energy_compute(fs_data* d, fs_energy* out) {
  return guarded("fs_energy_compute", [&] {
    if (!d || !out) return null_argument("fs_energy_compute");
    const auto e = fsx::energy(*d->model, d->data);
    out->kinetic = e.kinetic;
    out->gravity = e.gravity;
    out->elastic = e.elastic;
    out->springs = e.springs;
    out->total = e.total();
    return int(FS_OK);
  });
}

double fs_constraint_violation(const fs_data* d) {
  return d ? fsx::constraint_violation(*d->model, d->data) : kNaN;
}

int fs_statistics_get(const fs_data* d, fs_statistics* out) {
  if (!d || !out) return null_argument("fs_statistics_get");
  const auto& s = d->data.statistics;
  out->steps = s.steps;
  out->iterations = s.iterations;
  out->factorizations = s.factorizations;
  out->over_budget = s.over_budget;
  out->drift_projections = s.drift_projections;
  out->split_steps = s.split_steps;
  out->substeps = s.substeps;
  out->largest_error_estimate = s.largest_error_estimate;
  out->above_error_tolerance = s.above_error_tolerance;
  out->last_iterations = s.last_iterations;
  out->last_correction = s.last_correction;
  out->stalled_steps = s.stalled_steps;
  out->undone_corrections = s.undone_corrections;
  out->last_factorizations = s.last_factorizations;
  return FS_OK;
}

int fs_modal_coordinates(const fs_data* d, int body, double* p, int capacity, int* count) {
  if (const int s = check_body(d, body, p, "fs_modal_coordinates")) return s;
  const auto modes = fsx::modal_coordinates(*d->model, d->data, fsx::BodyId{body});
  const int n = static_cast<int>(modes.size());
  if (count) *count = n;
  for (int k = 0; k < std::min(n, capacity); ++k) p[k] = modes(k);
  if (capacity < n)
    return fail(FS_ERROR_BUFFER_TOO_SMALL, "fs_modal_coordinates: the body has " +
                                               std::to_string(n) + " modes, the buffer holds " +
                                               std::to_string(capacity));
  return FS_OK;
}

int fs_evaluate_outputs(fs_data* d) {
  if (!d) return null_argument("fs_evaluate_outputs"), FS_STEP_ERROR;
  const fsx::StepStatus s = fsx::evaluate_outputs(*d->model, d->data);
  if (s != fsx::StepStatus::ok) {  // a meter refused a sample: which, and what
    guarded("fs_evaluate_outputs", [&] {
      d->error = d->data.message.data();
      return fail(FS_ERROR_INVALID_ARGUMENT, "fs_evaluate_outputs: " + d->error);
    });
  }
  return static_cast<int>(s);
}

// Read-outs that return a value: a bad handle gives NaN (or -1) and sets fs_last_error.
static void report_bad_handle(const char* where, const char* what, int handle) {
  guarded(where, [&] { return bad_handle(where, what, handle); });
}

double fs_output_value(const fs_data* d, int output) {
  if (!d) return guarded("fs_output_value", [] { return null_argument("fs_output_value"); }), kNaN;
  if (output < 0 || output >= d->model->num_outputs())
    return report_bad_handle("fs_output_value", "output", output), kNaN;
  return fsx::output_value(d->data, fsx::OutputId{output});
}

double fs_meter_damage(const fs_data* d, int meter) {
  if (!d) return guarded("fs_meter_damage", [] { return null_argument("fs_meter_damage"); }), kNaN;
  if (!in_range(meter, d->model->meters().size()))
    return report_bad_handle("fs_meter_damage", "meter", meter), kNaN;
  return fsx::meter_damage(d->data, fsx::MeterId{meter});
}

long long fs_meter_refused_samples(const fs_data* d, int meter) {
  if (!d)
    return guarded("fs_meter_refused_samples",
                   [] { return null_argument("fs_meter_refused_samples"); }),
           -1;
  if (!in_range(meter, d->model->meters().size()))
    return report_bad_handle("fs_meter_refused_samples", "meter", meter), -1;
  return static_cast<long long>(fsx::meter_refused_samples(d->data, fsx::MeterId{meter}));
}

int fs_linearize(fs_data* d, double* hz, int capacity, int* count, double* static_residual) {
  return linearize_into("fs_linearize", d, hz, capacity, count, static_residual);
}

int fs_linearized_frequencies(fs_data* d, double* hz, int capacity, int* count) {
  return linearize_into("fs_linearized_frequencies", d, hz, capacity, count, nullptr);
}

}  // extern "C"
