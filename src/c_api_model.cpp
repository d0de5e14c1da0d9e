// The C interface (flexstress/flexstress.h) over the runtime model: motion laws, version and
// status strings, the builder and the model. Every entry point checks its pointers and
// handles before touching the model (the C++ read-outs index without checks) and catches every
// exception: nothing but status codes crosses into C.
#include <cstring>
#include <memory>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "c_api_internal.hpp"

using namespace flexstress_c_api;

namespace {

// A builder call given a null pointer: the call fails (FS_ERROR_NULL in fs_last_error's text),
// and, with a builder, so does finalize, as for any other part left out of the model.
int null_in_builder(fs_model_builder* b, const char* where) {
  if (!b) return null_argument(where), FS_INVALID_HANDLE;
  return record(b, fsx::make_error(fsx::ErrorCode::invalid_argument, "a required pointer is null"),
                where);
}

// Damage meters (fs_builder_add_damage_meter*).

fsx::Result<fsx::fatigue::SnCurve<double>> sn_curve(int curve, double category) {
  using fsx::fatigue::IiwBeyondKnee;
  switch (curve) {
    case FS_SN_IIW_NORMAL_HAIBACH:
      return fsx::fatigue::iiw_normal_curve(category, IiwBeyondKnee::haibach);
    case FS_SN_IIW_NORMAL_SLOPE_22:
      return fsx::fatigue::iiw_normal_curve(category, IiwBeyondKnee::slope_22);
    case FS_SN_IIW_SHEAR_HAIBACH:
      return fsx::fatigue::iiw_shear_curve(category, IiwBeyondKnee::haibach);
    case FS_SN_IIW_SHEAR_SLOPE_22:
      return fsx::fatigue::iiw_shear_curve(category, IiwBeyondKnee::slope_22);
    case FS_SN_EN1993_NORMAL: return fsx::fatigue::en1993_normal_curve(category);
    case FS_SN_EN1993_SHEAR: return fsx::fatigue::en1993_shear_curve(category);
    default:
      return fsx::make_error(fsx::ErrorCode::invalid_argument, "unknown S-N curve ", curve,
                             " (fs_sn_curve: 0 to 5)");
  }
}

int add_meter(fs_model_builder* b, const char* name, int output, int curve, double category,
              double lower, double upper, double scale) {
  const std::string part = std::string("meter '") + name + "'";
  auto sn = sn_curve(curve, category);
  if (!sn) return record(b, sn.error(), part);
  auto model = fsx::fatigue::DamageModel<double>::create(*sn);
  if (!model) return record(b, model.error(), part);
  // DamageMeter's streaming counter has its class count fixed at compile time.
  auto grid = fsx::fatigue::ClassGrid<double>::create(lower, upper, 128);
  if (!grid) return record(b, grid.error(), part);
  auto meter = fsx::DamageMeter<double>::create(*grid, 0, *model);
  if (!meter) return record(b, meter.error(), part);
  return b->builder.add_damage_meter(name, fsx::OutputId{output}, *meter, scale).index;
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
fs_motion_law fs_law_rest_to_rest(const double* rows, int num_rows) {
  return fs_motion_law{FS_LAW_REST_TO_REST, {0, 0, 0}, rows, num_rows, nullptr, nullptr, -1};
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
    if (!b || !name || !com || !inertia) return null_in_builder(b, "fs_builder_add_rigid_body");
    const Eigen::Map<const fsx::Mat3<double>> j(inertia);
    return b->builder.add_rigid_body(name, mass, vec3(com), j).index;
  });
}

int fs_builder_add_flexible_body(fs_model_builder* b, const char* name, const char* path,
                                 int modes) {
  return guarded_handle("fs_builder_add_flexible_body", [&] {
    if (!b || !name || !path) return null_in_builder(b, "fs_builder_add_flexible_body");
    auto data = fsx::reduction::load_modal_body(path);
    if (!data) return record(b, data.error(), std::string("body '") + name + "'");
    const int body = b->builder.add_flexible_body(name, *data, modes).index;
    b->flexible_bodies.push_back(
        {body, name, modes,
         std::make_shared<const fsx::reduction::ModalBodyData>(std::move(*data))});
    return body;
  });
}

int fs_builder_set_damping_ratio(fs_model_builder* b, int body, double zeta) {
  return guarded("fs_builder_set_damping_ratio", [&] {
    if (!b) return null_argument("fs_builder_set_damping_ratio");
    b->builder.set_damping_ratio(fsx::BodyId{body}, zeta);
    return int(FS_OK);
  });
}

int fs_builder_add_geometric_stiffening(fs_model_builder* b, int body, const char* path) {
  return guarded("fs_builder_add_geometric_stiffening", [&] {
    if (!b || !path) return null_argument("fs_builder_add_geometric_stiffening");
    const auto found = std::find_if(b->flexible_bodies.begin(), b->flexible_bodies.end(),
                                    [&](const auto& f) { return f.body == body; });
    if (found == b->flexible_bodies.end()) {
      // Not a flexible body: the C++ builder names it (a rigid body, or a bad handle).
      b->builder.add_geometric_stiffening(fsx::BodyId{body},
                                          fsx::reduction::ModalGeometricStiffness{});
      return int(FS_OK);
    }
    auto g = fsx::reduction::load_geometric_stiffness(path, *found->data);
    if (!g) {
      record(b, g.error(), "body '" + found->name + "'");
      return status_of(g.error().code);
    }
    b->builder.add_geometric_stiffening(fsx::BodyId{body}, *g);
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
    if (!b || !name) return null_in_builder(b, "fs_builder_add_marker");
    const fsx::Vec3<double> o = offset ? vec3(offset) : fsx::Vec3<double>::Zero();
    const fsx::Mat3<double> a = axes ? fsx::Mat3<double>(Eigen::Map<const fsx::Mat3<double>>(axes))
                                     : fsx::Mat3<double>::Identity();
    return b->builder.add_marker(name, fsx::BodyId{body}, static_cast<fsx::Index>(node), o, a)
        .index;
  });
}

namespace {
// FS_INVALID_HANDLE with a message, for a kind the call does not take.
// A joint kind the call cannot take: the call fails, and so does finalize (the joint is not in
// the model, and a caller that did not check the handle must not get a model without it).
int bad_kind(fs_model_builder* b, const char* where, const char* name, int kind, const char* why) {
  return record(b, fsx::make_error(fsx::ErrorCode::invalid_argument, where, ": kind ", kind, why),
                std::string("joint '") + name + "'");
}
bool joint_kind_ok(int kind) {
  return kind >= FS_JOINT_SPHERICAL && kind <= FS_JOINT_REVOLUTE_DRIVER;
}
}  // namespace

int fs_builder_add_joint(fs_model_builder* b, const char* name, int kind, int i, int j) {
  return guarded_handle("fs_builder_add_joint", [&] {
    if (!b || !name) return null_in_builder(b, "fs_builder_add_joint");
    if (!joint_kind_ok(kind)) return bad_kind(b, "fs_builder_add_joint", name, kind, " is unknown");
    if (kind == FS_JOINT_DISTANCE)
      return bad_kind(b, "fs_builder_add_joint", name, kind, " needs fs_builder_add_distance");
    return b->builder
        .add_joint(name, static_cast<fsx::JointKind>(kind), fsx::MarkerId{i}, fsx::MarkerId{j})
        .index;
  });
}

int fs_builder_add_distance(fs_model_builder* b, const char* name, int i, int j, double length) {
  return guarded_handle("fs_builder_add_distance", [&] {
    if (!b || !name) return null_in_builder(b, "fs_builder_add_distance");
    return b->builder.add_distance(name, fsx::MarkerId{i}, fsx::MarkerId{j}, length).index;
  });
}

int fs_builder_add_driver(fs_model_builder* b, const char* name, int kind, int i, int j,
                          const fs_motion_law* law) {
  return guarded_handle("fs_builder_add_driver", [&] {
    if (!b || !name || !law) return null_in_builder(b, "fs_builder_add_driver");
    if (!joint_kind_ok(kind))
      return bad_kind(b, "fs_builder_add_driver", name, kind, " is unknown");
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
    if (!b || !name) return null_in_builder(b, "fs_builder_add_spring_damper");
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
    if (!b || !name || !callback) return null_in_builder(b, "fs_builder_add_point_load");
    // The C callback has the C++ one's signature.
    return b->builder.add_point_load(name, fsx::MarkerId{marker}, callback, user).index;
  });
}

int fs_builder_add_stress_outputs(fs_model_builder* b, const char* name, int body,
                                  const double* rows, int num_outputs, int num_modes) {
  return guarded_handle("fs_builder_add_stress_outputs", [&] {
    if (!b || !name || !rows) return null_in_builder(b, "fs_builder_add_stress_outputs");
    if (num_outputs < 1 || num_modes < 0) {
      fail(FS_ERROR_INVALID_ARGUMENT, std::string("fs_builder_add_stress_outputs: outputs '") +
                                          name + "': " + std::to_string(num_outputs) + " x " +
                                          std::to_string(num_modes) + " rows");
      return FS_INVALID_HANDLE;
    }
    using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    const Eigen::MatrixXd f = Eigen::Map<const RowMajor>(rows, num_outputs, num_modes);
    return b->builder.add_stress_outputs(name, fsx::BodyId{body}, f).first.index;
  });
}

long fs_builder_nearest_node(const fs_model_builder* b, int body, const double point[3],
                             double* distance) {
  long node = -1;
  guarded("fs_builder_nearest_node", [&] {
    if (!b || !point) return null_argument("fs_builder_nearest_node");
    const auto found = std::find_if(b->flexible_bodies.begin(), b->flexible_bodies.end(),
                                    [&](const auto& f) { return f.body == body; });
    if (found == b->flexible_bodies.end())
      return fail(FS_ERROR_INVALID_HANDLE, "fs_builder_nearest_node: body " + std::to_string(body) +
                                               " is not a flexible body of this builder");
    const fsx::Vec3<double> x = vec3(point);
    node = static_cast<long>(found->data->nearest_node(x));
    if (node >= 0 && distance)
      *distance = (found->data->node_positions[static_cast<std::size_t>(node)] - x).norm();
    return int(FS_OK);
  });
  return node;
}

int fs_builder_add_beam_fibre_stress(fs_model_builder* b, const char* name, int body, long node_a,
                                     long node_b, const double orientation[3],
                                     double youngs_modulus, double xi, double y, double z) {
  return guarded_handle("fs_builder_add_beam_fibre_stress", [&] {
    if (!b || !name) return null_in_builder(b, "fs_builder_add_beam_fibre_stress");
    const std::string part = std::string("output '") + name + "'";
    const auto found = std::find_if(b->flexible_bodies.begin(), b->flexible_bodies.end(),
                                    [&](const auto& f) { return f.body == body; });
    if (found == b->flexible_bodies.end())
      return record(b,
                    fsx::make_error(fsx::ErrorCode::invalid_argument, "body ", body,
                                    " is not a flexible body of this builder"),
                    part);
    fsx::stress::BeamFibre fibre;
    fibre.node_a = node_a;
    fibre.node_b = node_b;
    if (orientation) fibre.orientation = vec3(orientation);
    fibre.youngs_modulus = youngs_modulus;
    fibre.xi = xi;
    fibre.y = y;
    fibre.z = z;
    auto row = fsx::stress::beam_fibre_stress_modes(*found->data, fibre, found->modes);
    if (!row) return record(b, row.error(), part);
    return b->builder.add_stress_outputs(name, fsx::BodyId{body}, Eigen::MatrixXd(*row))
        .first.index;
  });
}

int fs_builder_add_damage_meter(fs_model_builder* b, const char* name, int output, double fat,
                                double lower, double upper, double scale) {
  return guarded_handle("fs_builder_add_damage_meter", [&] {
    if (!b || !name) return null_in_builder(b, "fs_builder_add_damage_meter");
    return add_meter(b, name, output, FS_SN_IIW_NORMAL_HAIBACH, fat, lower, upper, scale);
  });
}

int fs_builder_add_damage_meter_curve(fs_model_builder* b, const char* name, int output, int curve,
                                      double category, double lower, double upper, double scale) {
  return guarded_handle("fs_builder_add_damage_meter_curve", [&] {
    if (!b || !name) return null_in_builder(b, "fs_builder_add_damage_meter_curve");
    return add_meter(b, name, output, curve, category, lower, upper, scale);
  });
}

int fs_builder_add_input(fs_model_builder* b, const char* name) {
  return guarded_handle("fs_builder_add_input", [&] {
    if (!b || !name) return null_in_builder(b, "fs_builder_add_input");
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
    if (step > 0) s.step = step;  // else the default (as the header says)
    if (spectral_radius >= 0) s.spectral_radius = spectral_radius;
    if (max_iterations > 0) s.max_iterations = max_iterations;
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
int fs_model_warning_count(const fs_model* m) {
  return size_or(m, [](const fsx::Model<double>& x) { return int(x.warnings().size()); });
}
const char* fs_model_warning(const fs_model* m, int index) {
  const auto* model = model_of(m);
  if (!model) return null_argument("fs_model_warning"), nullptr;
  if (!in_range(index, model->warnings().size()))
    return bad_handle("fs_model_warning", "warning", index), nullptr;
  return model->warnings()[static_cast<std::size_t>(index)].c_str();
}

}  // extern "C"
