// The C interface (flexstress/flexstress.h) over the runtime model. Every entry point checks
// its pointers and handles before touching the model (the C++ read-outs index without checks)
// and catches every exception: nothing but status codes crosses into C.
#include "flexstress/flexstress.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <limits>
#include <memory>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "flexstress/fatigue/sn_curve.hpp"
#include "flexstress/model/all.hpp"
#include "flexstress/reduction/modal_body_io.hpp"
#include "flexstress/version.hpp"

namespace fsx = flexstress;

struct fs_model_builder {
  fsx::ModelBuilder<double> builder;
  // Mistakes the C layer finds (a file that cannot be read), reported by finalize before the
  // builder's own.
  fsx::Error first_error;
  bool failed = false;
  std::string error;  // what fs_builder_error returns
};

struct fs_model {
  std::shared_ptr<const fsx::Model<double>> model;
};

struct fs_data {
  std::shared_ptr<const fsx::Model<double>> model;  // keeps the model alive
  fsx::Data<double> data;
  std::string error;
};

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

thread_local std::string t_last_error;

int fail(int status, std::string message) {
  try {
    t_last_error = std::move(message);
  } catch (...) {
    t_last_error.clear();  // out of memory: the code still says what happened
  }
  return status;
}

int status_of(fsx::ErrorCode code) {
  switch (code) {
    case fsx::ErrorCode::invalid_argument: return FS_ERROR_INVALID_ARGUMENT;
    case fsx::ErrorCode::invalid_mesh: return FS_ERROR_INVALID_MESH;
    case fsx::ErrorCode::degenerate_element: return FS_ERROR_DEGENERATE_ELEMENT;
    case fsx::ErrorCode::singular_matrix: return FS_ERROR_SINGULAR_MATRIX;
    case fsx::ErrorCode::not_converged: return FS_ERROR_NOT_CONVERGED;
    case fsx::ErrorCode::size_mismatch: return FS_ERROR_SIZE_MISMATCH;
    case fsx::ErrorCode::io_error: return FS_ERROR_IO;
    case fsx::ErrorCode::bad_file_format: return FS_ERROR_BAD_FILE_FORMAT;
  }
  return FS_ERROR_INTERNAL;
}

// fail() from inside a catch handler: building the message may itself throw.
int fail_noexcept(int status, const char* where, const char* what) noexcept {
  try {
    t_last_error = std::string(where) + ": " + what;
  } catch (...) {
    t_last_error.clear();
  }
  return status;
}

// Runs f, turning any exception into a status (and a message).
template <class F>
int guarded(const char* where, F&& f) noexcept {
  try {
    return f();
  } catch (const std::bad_alloc&) {
    return fail_noexcept(FS_ERROR_OUT_OF_MEMORY, where, "out of memory");
  } catch (const std::exception& e) {
    return fail_noexcept(FS_ERROR_INTERNAL, where, e.what());
  } catch (...) {
    return fail_noexcept(FS_ERROR_INTERNAL, where, "unknown exception");
  }
}

// The same for handle-returning functions: the status's message is kept, the handle is
// FS_INVALID_HANDLE.
template <class F>
int guarded_handle(const char* where, F&& f) noexcept {
  int handle = FS_INVALID_HANDLE;
  const int s = guarded(where, [&] {
    handle = f();
    return FS_OK;
  });
  return s == FS_OK ? handle : FS_INVALID_HANDLE;
}

int null_argument(const char* where) {
  return fail(FS_ERROR_NULL, std::string(where) + ": a required pointer is null");
}

int bad_handle(const char* where, const char* what, int handle) {
  return fail(FS_ERROR_INVALID_HANDLE,
              std::string(where) + ": no " + what + " with handle " + std::to_string(handle));
}

bool in_range(int handle, std::size_t size) {
  return handle >= 0 && static_cast<std::size_t>(handle) < size;
}

fsx::Vec3<double> vec3(const double* p) {
  return fsx::Vec3<double>(p[0], p[1], p[2]);
}
void put3(const fsx::Vec3<double>& v, double* out) {
  for (int k = 0; k < 3; ++k) out[k] = v(k);
}

// A mistake the C layer finds while building (a file, a table), kept for finalize; the first
// one counts, as in ModelBuilder. Returns FS_INVALID_HANDLE.
int record(fs_model_builder* b, const fsx::Error& e, const std::string& part) {
  if (!b->failed) {
    b->failed = true;
    b->first_error = e;
    b->first_error.message = part + ": " + e.message;
  }
  b->error = b->first_error.what();
  fail(status_of(e.code), b->error);
  return FS_INVALID_HANDLE;
}

int error_status(fs_data* d, const fsx::Error& e) {
  d->error = e.what();
  return fail(status_of(e.code), d->error);
}

// A C law as a C++ law; the error text names the problem (a bad table).
fsx::Result<fsx::MotionLaw<double>> to_law(const fs_motion_law& l) {
  using Law = fsx::MotionLaw<double>;
  switch (l.kind) {
    case FS_LAW_POLYNOMIAL:
      return Law::constant_acceleration(l.coefficients[0], l.coefficients[1], l.coefficients[2]);
    case FS_LAW_TABLE: {
      if (l.table == nullptr || l.table_rows < 0)
        return fsx::make_error(fsx::ErrorCode::invalid_argument,
                               "table law: null rows or a negative row count");
      std::vector<double> t(static_cast<std::size_t>(l.table_rows)), s(t.size());
      for (std::size_t r = 0; r < t.size(); ++r) {
        t[r] = l.table[2 * r];
        s[r] = l.table[2 * r + 1];
      }
      auto table = fsx::TableLaw<double>::create(t, s);
      if (!table) return table.error();
      return Law::from_table(std::move(*table));
    }
    case FS_LAW_CALLBACK: return Law::from_callback(l.callback, l.user);
    case FS_LAW_INPUT: return Law::from_input(fsx::InputId{l.input});
    default: break;
  }
  return fsx::make_error(fsx::ErrorCode::invalid_argument, "unknown law kind ", l.kind);
}

}  // namespace

extern "C" {

fs_motion_law fs_law_polynomial(double s0, double v, double a) {
  return fs_motion_law{FS_LAW_POLYNOMIAL, {s0, v, a}, nullptr, 0, nullptr, nullptr, -1};
}
fs_motion_law fs_law_table(const double* rows, int num_rows) {
  return fs_motion_law{FS_LAW_TABLE, {0, 0, 0}, rows, num_rows, nullptr, nullptr, -1};
}
fs_motion_law fs_law_callback(fs_motion_callback callback, void* user) {
  return fs_motion_law{FS_LAW_CALLBACK, {0, 0, 0}, nullptr, 0, callback, user, -1};
}
fs_motion_law fs_law_input(int input) {
  return fs_motion_law{FS_LAW_INPUT, {0, 0, 0}, nullptr, 0, nullptr, nullptr, input};
}

const char* fs_version(void) {
  return fsx::version_string;
}
int fs_version_number(void) {
  return FLEXSTRESS_VERSION;
}
const char* fs_last_error(void) {
  return t_last_error.c_str();
}

const char* fs_status_string(int status) {
  static const char* const names[] = {"ok",
                                      "null argument",
                                      "invalid handle",
                                      "invalid argument",
                                      "invalid mesh",
                                      "degenerate element",
                                      "singular matrix",
                                      "not converged",
                                      "size mismatch",
                                      "i/o error",
                                      "bad file format",
                                      "buffer too small",
                                      "out of memory",
                                      "internal error"};
  return status >= 0 && status <= FS_ERROR_INTERNAL ? names[status] : "unknown status";
}
const char* fs_step_status_string(int s) {
  if (s < 0 || s > static_cast<int>(fsx::StepStatus::budget_reached)) return "error";
  return fsx::to_string(static_cast<fsx::StepStatus>(s));
}

// ---- builder --------------------------------------------------------------------------------

fs_model_builder* fs_builder_create(void) {
  try {
    return new fs_model_builder();
  } catch (...) {
    fail(FS_ERROR_OUT_OF_MEMORY, "fs_builder_create: out of memory");
    return nullptr;
  }
}
void fs_builder_destroy(fs_model_builder* b) {
  delete b;
}

int fs_builder_add_rigid_body(fs_model_builder* b, const char* name, double mass,
                              const double com[3], const double inertia[9]) {
  return guarded_handle("fs_builder_add_rigid_body", [&] {
    if (!b || !name || !com || !inertia)
      return null_argument("fs_builder_add_rigid_body"), FS_INVALID_HANDLE;
    const Eigen::Map<const fsx::Mat3<double>> j(inertia);
    return b->builder.add_rigid_body(name, mass, vec3(com), j).index;
  });
}

int fs_builder_add_flexible_body(fs_model_builder* b, const char* name, const char* path,
                                 int modes) {
  return guarded_handle("fs_builder_add_flexible_body", [&] {
    if (!b || !name || !path)
      return null_argument("fs_builder_add_flexible_body"), FS_INVALID_HANDLE;
    auto data = fsx::reduction::load_modal_body(path);
    if (!data) return record(b, data.error(), std::string("body '") + name + "'");
    return b->builder.add_flexible_body(name, *data, modes).index;
  });
}

int fs_builder_set_damping_ratio(fs_model_builder* b, int body, double zeta) {
  return guarded("fs_builder_set_damping_ratio", [&] {
    if (!b) return null_argument("fs_builder_set_damping_ratio");
    b->builder.set_damping_ratio(fsx::BodyId{body}, zeta);
    return int(FS_OK);
  });
}

int fs_builder_set_initial_pose(fs_model_builder* b, int body, const double position[3],
                                const double orientation[4]) {
  return guarded("fs_builder_set_initial_pose", [&] {
    if (!b || !position) return null_argument("fs_builder_set_initial_pose");
    fsx::EulerParameters<double> e = fsx::identity_euler_parameters<double>();
    if (orientation) e << orientation[0], orientation[1], orientation[2], orientation[3];
    b->builder.set_initial_pose(fsx::BodyId{body}, vec3(position), e);
    return int(FS_OK);
  });
}

int fs_builder_add_marker(fs_model_builder* b, const char* name, int body, long node,
                          const double offset[3], const double axes[9]) {
  return guarded_handle("fs_builder_add_marker", [&] {
    if (!b || !name) return null_argument("fs_builder_add_marker"), FS_INVALID_HANDLE;
    const fsx::Vec3<double> o = offset ? vec3(offset) : fsx::Vec3<double>::Zero();
    const fsx::Mat3<double> a = axes ? fsx::Mat3<double>(Eigen::Map<const fsx::Mat3<double>>(axes))
                                     : fsx::Mat3<double>::Identity();
    return b->builder.add_marker(name, fsx::BodyId{body}, static_cast<fsx::Index>(node), o, a)
        .index;
  });
}

namespace {
// FS_INVALID_HANDLE with a message, for a kind the call does not take.
int bad_kind(const char* where, const char* name, int kind, const char* why) {
  fail(FS_ERROR_INVALID_ARGUMENT,
       std::string(where) + ": joint '" + name + "': kind " + std::to_string(kind) + why);
  return FS_INVALID_HANDLE;
}
bool joint_kind_ok(int kind) {
  return kind >= FS_JOINT_SPHERICAL && kind <= FS_JOINT_REVOLUTE_DRIVER;
}
}  // namespace

int fs_builder_add_joint(fs_model_builder* b, const char* name, int kind, int i, int j) {
  return guarded_handle("fs_builder_add_joint", [&] {
    if (!b || !name) return null_argument("fs_builder_add_joint"), FS_INVALID_HANDLE;
    if (!joint_kind_ok(kind)) return bad_kind("fs_builder_add_joint", name, kind, " is unknown");
    if (kind == FS_JOINT_DISTANCE)
      return bad_kind("fs_builder_add_joint", name, kind, " needs fs_builder_add_distance");
    return b->builder
        .add_joint(name, static_cast<fsx::JointKind>(kind), fsx::MarkerId{i}, fsx::MarkerId{j})
        .index;
  });
}

int fs_builder_add_distance(fs_model_builder* b, const char* name, int i, int j, double length) {
  return guarded_handle("fs_builder_add_distance", [&] {
    if (!b || !name) return null_argument("fs_builder_add_distance"), FS_INVALID_HANDLE;
    return b->builder.add_distance(name, fsx::MarkerId{i}, fsx::MarkerId{j}, length).index;
  });
}

int fs_builder_add_driver(fs_model_builder* b, const char* name, int kind, int i, int j,
                          const fs_motion_law* law) {
  return guarded_handle("fs_builder_add_driver", [&] {
    if (!b || !name || !law) return null_argument("fs_builder_add_driver"), FS_INVALID_HANDLE;
    if (!joint_kind_ok(kind)) return bad_kind("fs_builder_add_driver", name, kind, " is unknown");
    auto l = to_law(*law);
    if (!l) return record(b, l.error(), std::string("joint '") + name + "'");
    return b->builder
        .add_driver(name, static_cast<fsx::JointKind>(kind), fsx::MarkerId{i}, fsx::MarkerId{j},
                    std::move(*l))
        .index;
  });
}

int fs_builder_add_spring_damper(fs_model_builder* b, const char* name, int i, int j,
                                 double stiffness, double damping, double rest_length,
                                 double preload) {
  return guarded_handle("fs_builder_add_spring_damper", [&] {
    if (!b || !name) return null_argument("fs_builder_add_spring_damper"), FS_INVALID_HANDLE;
    fsx::SpringDamperParams<double> p;
    p.stiffness = stiffness;
    p.damping = damping;
    p.rest_length = rest_length;
    p.preload = preload;
    return b->builder.add_spring_damper(name, fsx::MarkerId{i}, fsx::MarkerId{j}, p).index;
  });
}

int fs_builder_add_point_load(fs_model_builder* b, const char* name, int marker,
                              fs_point_load_callback callback, void* user) {
  return guarded_handle("fs_builder_add_point_load", [&] {
    if (!b || !name || !callback)
      return null_argument("fs_builder_add_point_load"), FS_INVALID_HANDLE;
    // The C callback has the C++ one's signature.
    return b->builder.add_point_load(name, fsx::MarkerId{marker}, callback, user).index;
  });
}

int fs_builder_add_stress_outputs(fs_model_builder* b, const char* name, int body,
                                  const double* rows, int num_outputs, int num_modes) {
  return guarded_handle("fs_builder_add_stress_outputs", [&] {
    if (!b || !name || !rows)
      return null_argument("fs_builder_add_stress_outputs"), FS_INVALID_HANDLE;
    if (num_outputs < 1 || num_modes < 0) {
      fail(FS_ERROR_INVALID_ARGUMENT, std::string("fs_builder_add_stress_outputs: outputs '") +
                                          name + "': " + std::to_string(num_outputs) + " x " +
                                          std::to_string(num_modes) + " rows");
      return FS_INVALID_HANDLE;
    }
    using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    const Eigen::MatrixXd f = Eigen::Map<const RowMajor>(rows, num_outputs, num_modes);
    return b->builder.add_stress_outputs(name, fsx::BodyId{body}, f).index;
  });
}

int fs_builder_add_damage_meter(fs_model_builder* b, const char* name, int output, double fat,
                                double lower, double upper, double scale) {
  return guarded_handle("fs_builder_add_damage_meter", [&] {
    if (!b || !name) return null_argument("fs_builder_add_damage_meter"), FS_INVALID_HANDLE;
    const std::string part = std::string("meter '") + name + "'";
    auto curve = fsx::fatigue::iiw_normal_curve(fat, fsx::fatigue::IiwBeyondKnee::haibach);
    if (!curve) return record(b, curve.error(), part);
    auto model = fsx::fatigue::DamageModel<double>::create(*curve);
    if (!model) return record(b, model.error(), part);
    auto grid = fsx::fatigue::ClassGrid<double>::create(lower, upper, 128);
    if (!grid) return record(b, grid.error(), part);
    auto meter = fsx::DamageMeter<double>::create(*grid, 0, *model);
    if (!meter) return record(b, meter.error(), part);
    return b->builder.add_damage_meter(name, fsx::OutputId{output}, *meter, scale).index;
  });
}

int fs_builder_add_input(fs_model_builder* b, const char* name) {
  return guarded_handle("fs_builder_add_input", [&] {
    if (!b || !name) return null_argument("fs_builder_add_input"), FS_INVALID_HANDLE;
    return b->builder.add_input(name).index;
  });
}

int fs_builder_set_gravity(fs_model_builder* b, const double g[3]) {
  return guarded("fs_builder_set_gravity", [&] {
    if (!b || !g) return null_argument("fs_builder_set_gravity");
    b->builder.set_gravity(vec3(g));
    return int(FS_OK);
  });
}

int fs_builder_set_integrator(fs_model_builder* b, double step, double spectral_radius,
                              int max_iterations, double tolerance) {
  return guarded("fs_builder_set_integrator", [&] {
    if (!b) return null_argument("fs_builder_set_integrator");
    auto& s = b->builder.settings();
    s.step = step;
    s.spectral_radius = spectral_radius;
    s.max_iterations = max_iterations;
    if (tolerance > 0) {  // an absolute tolerance in place of the default relative one
      s.acceleration_tolerance = tolerance;
      s.relative_acceleration_tolerance = 0;
    }
    return int(FS_OK);  // finalize checks the values
  });
}

int fs_builder_finalize(fs_model_builder* b, fs_model** model) {
  if (model) *model = nullptr;
  return guarded("fs_builder_finalize", [&] {
    if (!b || !model) return null_argument("fs_builder_finalize");
    if (b->failed) {
      b->error = b->first_error.what();
      return fail(status_of(b->first_error.code), b->error);
    }
    auto m = b->builder.finalize();
    if (!m) {
      b->error = m.error().what();
      return fail(status_of(m.error().code), b->error);
    }
    auto out = std::make_unique<fs_model>();
    out->model = std::make_shared<const fsx::Model<double>>(std::move(*m));
    b->error.clear();
    *model = out.release();
    return int(FS_OK);
  });
}

const char* fs_builder_error(const fs_model_builder* b) {
  return b ? b->error.c_str() : "fs_builder_error: null builder";
}

size_t fs_builder_copy_error(const fs_model_builder* b, char* buffer, size_t size) {
  const char* text = fs_builder_error(b);
  const size_t n = std::strlen(text);
  if (buffer && size > 0) {
    const size_t k = std::min(n, size - 1);
    std::memcpy(buffer, text, k);
    buffer[k] = '\0';
  }
  return n;
}

// ---- model ----------------------------------------------------------------------------------

void fs_model_destroy(fs_model* m) {
  delete m;
}

namespace {
const fsx::Model<double>* model_of(const fs_model* m) {
  return m ? m->model.get() : nullptr;
}
int size_or(const fs_model* m, int (*f)(const fsx::Model<double>&)) {
  const auto* model = model_of(m);
  if (!model) return null_argument("fs_model"), -1;
  return f(*model);
}
}  // namespace

int fs_model_num_velocities(const fs_model* m) {
  return size_or(m, [](const fsx::Model<double>& x) { return x.num_velocities(); });
}
int fs_model_num_constraints(const fs_model* m) {
  return size_or(m, [](const fsx::Model<double>& x) { return x.num_constraints(); });
}
int fs_model_num_bodies(const fs_model* m) {
  return size_or(m, [](const fsx::Model<double>& x) { return int(x.bodies().size()); });
}
int fs_model_num_markers(const fs_model* m) {
  return size_or(m, [](const fsx::Model<double>& x) { return int(x.markers().size()); });
}
int fs_model_num_joints(const fs_model* m) {
  return size_or(m, [](const fsx::Model<double>& x) { return int(x.joints().size()); });
}
int fs_model_num_inputs(const fs_model* m) {
  return size_or(m, [](const fsx::Model<double>& x) { return int(x.inputs().size()); });
}
int fs_model_body_modes(const fs_model* m, int body) {
  const auto* model = model_of(m);
  if (!model) return null_argument("fs_model_body_modes"), -1;
  if (!in_range(body, model->bodies().size()))
    return bad_handle("fs_model_body_modes", "body", body), -1;
  return model->body(fsx::BodyId{body}).modes;
}

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
  return static_cast<int>(fsx::evaluate_outputs(*d->model, d->data));
}

double fs_output_value(const fs_data* d, int output) {
  if (!d || output < 0 || output >= d->model->num_outputs()) return kNaN;
  return fsx::output_value(d->data, fsx::OutputId{output});
}

double fs_meter_damage(fs_data* d, int meter) {
  if (!d || !in_range(meter, d->model->meters().size())) return kNaN;
  return fsx::meter_damage(d->data, fsx::MeterId{meter});
}

int fs_linearized_frequencies(fs_data* d, double* hz, int capacity, int* count) {
  if (count) *count = 0;
  return guarded("fs_linearized_frequencies", [&] {
    if (!d || (!hz && capacity > 0)) return null_argument("fs_linearized_frequencies");
    auto lin = fsx::linearize(*d->model, d->data);
    if (!lin) return error_status(d, lin.error());
    const int n = static_cast<int>(lin->frequencies_hz.size());
    if (count) *count = n;
    for (int k = 0; k < std::min(n, std::max(capacity, 0)); ++k) hz[k] = lin->frequencies_hz(k);
    if (capacity < n)
      return fail(FS_ERROR_BUFFER_TOO_SMALL, "fs_linearized_frequencies: " + std::to_string(n) +
                                                 " frequencies, room for " +
                                                 std::to_string(capacity));
    return int(FS_OK);
  });
}

}  // extern "C"
