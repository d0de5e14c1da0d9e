// Checkpoints of a running model: the whole Data (state, joint switches, anchored markers,
// laws, inputs, force-element states, outputs and damage meters, integrator history and
// statistics) as bytes, with a description of the model it belongs to. A restored run continues
// bit for bit; a restore into a model that differs fails and says what differs (the first body,
// joint, force, input or output set whose kind, size or parameters are not the checkpoint's).
//
// Format (little-endian, core/binary_io.hpp envelope "FLXMODL1", version 14, signature 0): the
// model description (entries of a label, a summary and a hash of the part's parameters), then
// the Data. A callback law cannot be saved: the checkpoint records that there was one, and the
// restoring Data must hold a callback law in that place (its own function is kept).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include <Eigen/Core>

#include "flexstress/core/binary_io.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/dynamics/step_settings.hpp"
#include "flexstress/fatigue/streaming_damage_io.hpp"
#include "flexstress/model/data.hpp"
#include "flexstress/model/implicit_step.hpp"
#include "flexstress/model/model.hpp"

namespace flexstress {

/// One part of a model as a checkpoint describes it.
struct ModelPart {
  std::string label;    ///< "body 2"
  std::string summary;  ///< "'boom', 10 modes"
  std::uint64_t parameters = 0;
};

namespace checkpoint_model_detail {

inline constexpr binary::Envelope kEnvelope{"FLXMODL1", 14, "model checkpoint"};

template <class T>
void put_raw(binary::Writer& w, const T& x) {
  static_assert(std::is_trivially_copyable_v<T>, "saved as raw bytes");
  const auto* b = reinterpret_cast<const unsigned char*>(&x);
  // Byte by byte: GCC 12 flags a range insert from a raw pointer (-Wnonnull, a false positive
  // on the empty vector's null data) once it is inlined here.
  for (std::size_t i = 0; i < sizeof(T); ++i) w.buffer.push_back(b[i]);
}
template <class T>
bool get_raw(binary::Reader& r, T& x) {
  auto* b = reinterpret_cast<unsigned char*>(&x);
  for (std::size_t i = 0; i < sizeof(T); ++i)
    if (!r.get(b[i])) return false;
  return true;
}
/// All coefficients of a matrix, in storage order.
template <class M>
auto flat(M& m) {
  using S = typename std::remove_const_t<M>::Scalar;
  using Vec = Eigen::Matrix<S, Eigen::Dynamic, 1>;
  using Target = std::conditional_t<std::is_const_v<M>, const Vec, Vec>;
  return Eigen::Map<Target>(m.data(), m.size());
}
template <class V>
void put_vector(binary::Writer& w, const V& v) {
  for (Index i = 0; i < v.size(); ++i) w.put(v(i));
}
template <class V>
bool get_vector(binary::Reader& r, V& v) {
  for (Index i = 0; i < v.size(); ++i)
    if (!r.get(v(i))) return false;
  return true;
}
inline void put_string(binary::Writer& w, const std::string& s) {
  w.put(static_cast<std::uint32_t>(s.size()));
  for (char c : s) w.buffer.push_back(static_cast<unsigned char>(c));
}
inline bool get_string(binary::Reader& r, std::string& s) {
  std::uint32_t n = 0;
  if (!r.get(n) || n > r.remaining()) return false;
  s.resize(n);
  for (auto& c : s)
    if (!r.get(c)) return false;
  return true;
}
inline std::uint64_t hash(const binary::Writer& w) {
  return binary::fnv1a(w.buffer.data(), w.buffer.size());
}

}  // namespace checkpoint_model_detail

/// The parts of a model as a checkpoint records them: kinds, sizes, names and a hash of each
/// part's parameters (body data, marker placement, joint and force parameters, output rows).
template <class Scalar>
std::vector<ModelPart> describe_model(const Model<Scalar>& m) {
  using namespace checkpoint_model_detail;
  std::vector<ModelPart> parts;
  const auto marker_text = [&](int k) {
    return k < 0 ? std::string("-") : "'" + m.markers()[static_cast<std::size_t>(k)].name + "'";
  };
  parts.push_back({"scalar", std::to_string(sizeof(Scalar)) + "-byte", 0});
  {
    binary::Writer w;
    put_vector(w, m.gravity());
    w.put(static_cast<std::uint8_t>(m.has_gravity()));
    w.put(static_cast<std::uint8_t>(m.has_quadratic_velocity()));
    w.put(static_cast<std::uint8_t>(m.ground_motion().moving));
    put_vector(w, m.ground_axis());
    parts.push_back({"effects", m.has_gravity() ? "gravity" : "no gravity", hash(w)});
  }
  for (std::size_t b = 0; b < m.bodies().size(); ++b) {
    const auto& body = m.bodies()[b];
    binary::Writer w;
    w.put(body.kernels->fingerprint(body.holder.get()));
    put_raw(w, body.effects);
    parts.push_back({"body " + std::to_string(b),
                     "'" + body.name + "', " + std::to_string(body.modes) + " modes, " +
                         std::to_string(body.num_markers) + " markers",
                     hash(w)});
  }
  {
    // Where the markers are: on the ground their frames (bodies hash their own markers).
    binary::Writer w;
    for (const auto& mk : m.markers()) {
      w.put(static_cast<std::int32_t>(mk.body));
      w.put(static_cast<std::int32_t>(mk.local));
    }
    for (const auto& g : m.ground_markers())
      for (const auto* v : {&g.origin.value, &g.x.value, &g.y.value, &g.z.value}) put_vector(w, *v);
    parts.push_back({"markers", std::to_string(m.markers().size()) + " markers", hash(w)});
  }
  for (std::size_t k = 0; k < m.joints().size(); ++k) {
    const auto& j = m.joints()[k];
    binary::Writer w;
    w.put(static_cast<std::int32_t>(j.marker_i));
    w.put(static_cast<std::int32_t>(j.marker_j));
    w.put(j.length);
    w.put(static_cast<std::int32_t>(j.law));
    parts.push_back({"joint " + std::to_string(k),
                     "'" + j.name + "' (" + to_string(j.kind) + ") from " +
                         marker_text(j.marker_i) + " to " + marker_text(j.marker_j),
                     hash(w)});
  }
  for (std::size_t k = 0; k < m.forces().size(); ++k) {
    const auto& f = m.forces()[k];
    binary::Writer w;
    w.put(static_cast<std::int32_t>(f.marker_i));
    w.put(static_cast<std::int32_t>(f.marker_j));
    put_raw(w, f.params);
    put_raw(w, f.hydraulic);
    const char* kind = f.kind == ForceKind::spring_damper        ? "spring-damper"
                       : f.kind == ForceKind::hydraulic_cylinder ? "hydraulic cylinder"
                                                                 : "point load";
    parts.push_back({"force " + std::to_string(k), "'" + f.name + "' (" + kind + ")", hash(w)});
  }
  for (std::size_t k = 0; k < m.inputs().size(); ++k)
    parts.push_back({"input " + std::to_string(k), "'" + m.inputs()[k] + "'", 0});
  for (std::size_t k = 0; k < m.output_sets().size(); ++k) {
    const auto& set = m.output_sets()[k];
    binary::Writer w;
    w.put(static_cast<std::int32_t>(set.body));
    put_vector(w, flat(set.rows));
    put_vector(w, flat(set.inertia));
    parts.push_back({"output set " + std::to_string(k),
                     "'" + set.name + "', " + std::to_string(set.rows.rows()) + " outputs",
                     hash(w)});
  }
  for (std::size_t k = 0; k < m.meters().size(); ++k) {
    const auto& meter = m.meters()[k];
    binary::Writer w;
    w.put(static_cast<std::int32_t>(meter.output));
    w.put(meter.scale);
    w.put(fatigue::damage_meter_signature(meter.prototype));
    parts.push_back({"meter " + std::to_string(k), "'" + meter.name + "'", hash(w)});
  }
  return parts;
}

/// d as checkpoint bytes (setup-time: allocates).
template <class Scalar>
Result<std::vector<unsigned char>> save_checkpoint(const Model<Scalar>& m, const Data<Scalar>& d) {
  using namespace checkpoint_model_detail;
  if (!binary::little_endian_host())
    return make_error(ErrorCode::invalid_argument,
                      "checkpoint: this host is big-endian; the format is little-endian only");
  binary::Writer w;
  const auto parts = describe_model(m);
  w.put(static_cast<std::uint32_t>(parts.size()));
  for (const auto& p : parts) {
    put_string(w, p.label);
    put_string(w, p.summary);
    w.put(p.parameters);
  }
  // State.
  w.put(d.t);
  for (const auto* v : {&d.q, &d.v, &d.v_dot, &d.a, &d.lambda}) put_vector(w, *v);
  // Runtime changes.
  for (unsigned char a : d.joint_active) w.put(a);
  for (const auto& a : d.anchors) {
    w.put(static_cast<std::uint8_t>(a.active));
    for (const auto& c : a.c) put_vector(w, c);
  }
  for (const auto& law : d.laws) {
    w.put(static_cast<std::uint8_t>(law.kind));
    put_raw(w, law.polynomial);
    w.put(static_cast<std::int32_t>(law.input.index));
    w.put(static_cast<std::uint8_t>(law.table.interpolation()));
    const auto& t = law.table.times();
    const auto& s = law.table.values();
    w.put(static_cast<std::uint64_t>(t.size()));
    for (std::size_t i = 0; i < t.size(); ++i) {
      w.put(t[i]);
      w.put(s[i]);
    }
  }
  for (const auto& in : d.inputs) put_raw(w, in);
  for (const auto& in : d.inputs_start) put_raw(w, in);
  w.put(d.input_t0);
  w.put(d.input_t1);
  for (unsigned char s : d.input_set) w.put(s);
  w.put(d.revision);
  for (const auto& f : d.force_states) put_raw(w, f);
  // Outputs and meters.
  put_vector(w, d.outputs);
  for (const auto& meter : d.meters) {
    auto bytes = fatigue::save_damage_meter(meter);
    if (!bytes) return bytes.error();
    w.put(static_cast<std::uint64_t>(bytes->size()));
    w.buffer.insert(w.buffer.end(), bytes->begin(), bytes->end());
  }
  for (std::int64_t refused : d.meter_refused) w.put(refused);
  // Integrator: settings, history, statistics.
  put_raw(w, d.settings);
  put_raw(w, d.statistics);
  const auto& in = d.integrator;
  for (bool flag : {in.initialized, in.has_previous, in.have_factorization, in.predict_linear})
    w.put(static_cast<std::uint8_t>(flag));
  w.put(static_cast<std::int32_t>(in.converged_multipliers));
  w.put(static_cast<std::int32_t>(in.piece_level));
  w.put(static_cast<std::int32_t>(in.reuse_backoff));
  w.put(static_cast<std::int32_t>(in.fresh_starts_left));
  w.put(static_cast<std::int32_t>(in.boost_age));
  w.put(in.h);
  w.put(in.revision);
  w.put(in.penalty);
  w.put(in.penalty_boost);
  w.put(in.acceleration_scale);
  put_vector(w, in.vd_prev);
  put_vector(w, in.lambda_last);
  put_vector(w, in.lambda_increment);
  if (in.have_factorization) {
    put_vector(w, flat(in.iteration));
    for (const auto& a : in.factorized_rotations) put_vector(w, flat(a));
  }
  return kEnvelope.seal(0, w.buffer);
}

/// Restores a checkpoint into d (made for `m`). `name` appears in the messages. On error d is
/// left as it was.
template <class Scalar>
Status restore_checkpoint(const Model<Scalar>& m, Data<Scalar>& d, const unsigned char* data,
                          std::size_t size, const std::string& name = "checkpoint") {
  using namespace checkpoint_model_detail;
  auto bad = [&](const auto&... parts) {
    return make_error(ErrorCode::bad_file_format, "'", name, "': ", parts...);
  };
  auto opened = kEnvelope.open(data, size, 0, name,
                               "the header's signature field is damaged (a model checkpoint's is "
                               "0; the model is described in the data)");
  if (!opened) return opened.error();
  binary::Reader& r = *opened;
  // The model: the first part that differs.
  const auto here = describe_model(m);
  std::uint32_t count = 0;
  if (!r.get(count)) return bad("it ends early");
  for (std::uint32_t k = 0; k < count; ++k) {
    ModelPart p;
    if (!get_string(r, p.label) || !get_string(r, p.summary) || !r.get(p.parameters))
      return bad("it ends early");
    if (k >= here.size())
      return bad("the checkpoint is of another model: it has ", p.label, " (", p.summary,
                 "), this model has no such part");
    const ModelPart& h = here[k];
    if (p.label != h.label)
      return bad("the checkpoint is of another model: it has ", p.label, " (", p.summary,
                 ") where this model has ", h.label, " (", h.summary, ")");
    if (p.summary != h.summary)
      return bad("the checkpoint is of another model: ", p.label, " is ", p.summary, " there and ",
                 h.summary, " here");
    if (p.parameters != h.parameters)
      return bad("the checkpoint is of another model: ", p.label, " (", h.summary,
                 ") has other parameters (data, placement or settings)");
  }
  if (count < here.size())
    return bad("the checkpoint is of another model: this model also has ", here[count].label, " (",
               here[count].summary, ")");
  // Read into a copy; commit only when everything was read.
  Data<Scalar> next = d;
  bool ok = r.get(next.t);
  for (auto* v : {&next.q, &next.v, &next.v_dot, &next.a, &next.lambda})
    ok = ok && get_vector(r, *v);
  for (auto& a : next.joint_active) ok = ok && r.get(a);
  for (auto& a : next.anchors) {
    std::uint8_t active = 0;
    ok = ok && r.get(active);
    a.active = active != 0;
    for (auto& c : a.c) ok = ok && get_vector(r, c);
  }
  for (std::size_t k = 0; ok && k < next.laws.size(); ++k) {
    auto& law = next.laws[k];
    std::uint8_t kind = 0, interpolation = 0;
    std::int32_t input = -1;
    std::uint64_t rows = 0;
    PolynomialLaw<Scalar> polynomial;
    ok = r.get(kind) && get_raw(r, polynomial) && r.get(input) && r.get(interpolation) &&
         r.get(rows) && rows <= r.remaining() / (2 * sizeof(double));
    std::vector<double> t(ok ? rows : 0), s(ok ? rows : 0);
    for (std::size_t i = 0; ok && i < t.size(); ++i) ok = r.get(t[i]) && r.get(s[i]);
    if (!ok) break;
    const auto saved = static_cast<MotionLawKind>(kind);
    if (saved == MotionLawKind::callback) {
      if (law.kind != MotionLawKind::callback)
        return bad("law ", k,
                   " was a callback when saved; this Data's is not (give it the "
                   "callback before restoring)");
      continue;  // keeps this Data's function and user data
    }
    MotionLaw<Scalar> restored;
    restored.kind = saved;
    restored.polynomial = polynomial;
    restored.input = InputId{input};
    if (saved == MotionLawKind::table) {
      if (interpolation > static_cast<std::uint8_t>(TableInterpolation::rest_to_rest))
        return bad("law ", k, ": unknown table interpolation ", int(interpolation));
      auto table = TableLaw<Scalar>::create(t, s, static_cast<TableInterpolation>(interpolation));
      if (!table) return bad("law ", k, ": ", table.error().message);
      restored.table = std::move(*table);
    }
    law = std::move(restored);
  }
  for (auto& in : next.inputs) ok = ok && get_raw(r, in);
  for (auto& in : next.inputs_start) ok = ok && get_raw(r, in);
  ok = ok && r.get(next.input_t0) && r.get(next.input_t1);
  for (auto& s : next.input_set) ok = ok && r.get(s);
  ok = ok && r.get(next.revision);
  for (auto& f : next.force_states) ok = ok && get_raw(r, f);
  ok = ok && get_vector(r, next.outputs);
  for (auto& meter : next.meters) {
    std::uint64_t n = 0;
    ok = ok && r.get(n) && n <= r.remaining();
    if (!ok) break;
    std::vector<unsigned char> bytes(static_cast<std::size_t>(n));
    for (auto& b : bytes) ok = ok && r.get(b);
    if (!ok) break;
    if (Status s = fatigue::restore_damage_meter(bytes.data(), bytes.size(), meter,
                                                 name + " (damage meter)");
        !s.ok())
      return s;
  }
  for (auto& refused : next.meter_refused) ok = ok && r.get(refused) && refused >= 0;
  ok = ok && get_raw(r, next.settings) && get_raw(r, next.statistics);
  // Settings read as bytes: a damaged file must not hand the step a negative hold or a NaN step.
  if (ok)
    if (Status checked = check_settings(next.settings); !checked)
      return bad("its integrator settings are damaged (", checked.error().what(), ")");
  auto& in = next.integrator;
  std::uint8_t flags[4] = {};
  for (auto& f : flags) ok = ok && r.get(f);
  std::int32_t converged = 0, piece_level = 0, backoff = 0, fresh_starts = 0, boost_age = 0;
  Scalar piece = 0;
  ok = ok && r.get(converged) && r.get(piece_level) && r.get(backoff) && r.get(fresh_starts) &&
       r.get(boost_age) && r.get(piece) && r.get(in.revision) && r.get(in.penalty) &&
       r.get(in.penalty_boost) && r.get(in.acceleration_scale) && get_vector(r, in.vd_prev) &&
       get_vector(r, in.lambda_last) && get_vector(r, in.lambda_increment);
  if (ok) {
    set_step_size(next, next.settings.step);  // the step's constants (clears the factorization)
    // The pieces the step was taking (step()), when a valid part of the step.
    if (piece_level > 0 && piece_level <= next.settings.max_step_halvings &&
        piece == std::ldexp(next.settings.step, -piece_level)) {
      detail::set_step_parameters(next, piece);
      in.piece_level = piece_level;
    }
    in.initialized = flags[0] != 0;
    in.has_previous = flags[1] != 0;
    in.have_factorization = flags[2] != 0;
    in.predict_linear = flags[3] != 0;
    in.converged_multipliers = converged < 0 ? 0 : converged > 2 ? 2 : converged;
    if (!(in.penalty_boost >= Scalar(1) && std::isfinite(in.penalty_boost)))
      in.penalty_boost = Scalar(1);
    const int limit = std::max(1, next.settings.refactor_backoff_limit);
    in.reuse_backoff = std::clamp(static_cast<int>(backoff), 0, limit);
    in.fresh_starts_left = std::clamp(static_cast<int>(fresh_starts), 0, limit);
    in.boost_age = std::clamp(static_cast<int>(boost_age), 0, next.settings.penalty_hold_steps);
  }
  if (ok && in.have_factorization) {
    auto iteration = flat(in.iteration);
    ok = get_vector(r, iteration);
    for (auto& a : in.factorized_rotations) {
      auto coefficients = flat(a);
      ok = ok && get_vector(r, coefficients);
    }
    if (ok) in.cholesky.compute(in.iteration);
  }
  if (!ok || r.remaining() != 0)
    return bad("the data does not match the layout of this model (",
               ok ? "bytes left over" : "it ends early", ")");
  d = std::move(next);
  return Status::success();
}

/// Writes a checkpoint file.
template <class Scalar>
Status save_checkpoint_file(const std::string& path, const Model<Scalar>& m,
                            const Data<Scalar>& d) {
  auto bytes = save_checkpoint(m, d);
  if (!bytes) return bytes.error();
  return binary::write_file(path, *bytes);
}

/// Restores a checkpoint file into d.
template <class Scalar>
Status restore_checkpoint_file(const std::string& path, const Model<Scalar>& m, Data<Scalar>& d) {
  auto bytes = binary::read_file(path);
  if (!bytes) return bytes.error();
  return restore_checkpoint(m, d, bytes->data(), bytes->size(), path);
}

}  // namespace flexstress
