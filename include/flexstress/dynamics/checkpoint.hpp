// Checkpoint and restore of a running scene: the State (time, coordinates, velocities,
// accelerations, multipliers, force elements' internal states) and the implicit integrator's
// history (its predictor and the factorization the modified Newton reuses), so a run stopped and
// restored continues bit-identically to one that never stopped. A long fatigue campaign can be
// split across jobs, or resumed after a crash. The explicit integrator (RK4) keeps no history
// between steps: its checkpoint is the step size and the State ("FLXCKRK4", same envelope, the
// payload without the history part).
//
// Format, version 3 (host byte order, which must be little-endian; checked):
//   "FLXCKPT1"  8-byte magic
//   u32 version, u32 byte-order mark 0x01020304
//   u64 scene signature (a hash of the scene's sizes: Scalar, coordinates, equations, bodies
//       and their modes, joints and their equations, force-element state sizes)
//   u64 payload size, u64 FNV-1a checksum of the payload
//   payload: Scalar h; Scalar t; per body position (3), Euler parameters (4), modal coordinates;
//            v, v_dot, a (nv each), lambda (nc); each force element's state (raw bytes);
//            u8 has_previous, u8 have_factorization; Scalar alpha; vd_prev (nv);
//            lambda_prev (nc), u8 converged_multipliers (version 2: the predictor
//            extrapolates the multipliers too);
//            the iteration matrix (nv x nv, column-major) if factorized, then each body's
//            rotation matrix at that factorization (9 per body, column-major; version 3: the
//            reused matrix is turned with the bodies); statistics (6 x i64).
// The loader checks magic, version, byte order, scene, size and checksum before it touches the
// state, and names what is wrong; a corrupted or foreign checkpoint is an error, never a crash.
// Application data that lives outside the scene is the application's to save alongside: a
// streaming damage meter has its own checkpoint (fatigue/streaming_damage_io.hpp).
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "flexstress/core/binary_io.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/dynamics/explicit_integrator.hpp"
#include "flexstress/dynamics/implicit_integrator.hpp"

namespace flexstress {

namespace checkpoint_detail {

inline constexpr binary::Envelope kEnvelope{"FLXCKPT1", 3, "checkpoint"};
inline constexpr binary::Envelope kExplicitEnvelope{"FLXCKRK4", 1,
                                                    "explicit-integrator checkpoint"};

template <class T>
void put_scalars(binary::Writer& w, const T* p, Index n) {
  for (Index i = 0; i < n; ++i) w.put(p[i]);
}
template <class T>
bool get_scalars(binary::Reader& r, T* p, Index n) {
  for (Index i = 0; i < n; ++i)
    if (!r.get(p[i])) return false;
  return true;
}

}  // namespace checkpoint_detail

/// The scene's structural signature: checkpoints of one scene type restore only into it.
template <class SceneT>
std::uint64_t scene_signature() {
  using Scalar = typename SceneT::scalar_type;
  binary::Writer w;
  w.put(std::int64_t{sizeof(Scalar)});
  w.put(std::int64_t{SceneT::nv});
  w.put(std::int64_t{SceneT::nc});
  w.put(std::int64_t{SceneT::num_bodies});
  for (int n : SceneT::body_nv) w.put(std::int64_t{n});
  w.put(std::int64_t{SceneT::num_joints});
  for (int n : SceneT::joint_nc) w.put(std::int64_t{n});
  w.put(std::int64_t{SceneT::num_forces});
  std::apply([&](const auto&... f) { (w.put(std::int64_t(sizeof(f))), ...); },
             typename SceneT::State().force_states);
  return binary::fnv1a(w.buffer.data(), w.buffer.size());
}

namespace checkpoint_detail {

/// Appends the State: t, per body position, Euler parameters, modal coordinates; v, v_dot, a;
/// lambda; the force elements' states as raw bytes.
template <class SceneT>
void put_state(binary::Writer& w, const typename SceneT::State& s) {
  w.put(s.t);
  std::apply(
      [&](const auto&... q) {
        ((put_scalars(w, q.position.data(), 3), put_scalars(w, q.theta.data(), 4),
          put_scalars(w, q.p.data(), q.p.size())),
         ...);
      },
      s.q);
  for (const auto* v : {&s.v, &s.v_dot, &s.a}) put_scalars(w, v->data(), SceneT::nv);
  put_scalars(w, s.lambda.data(), SceneT::nc);
  std::apply(
      [&](const auto&... f) {
        [[maybe_unused]] auto raw = [&](const auto& x) {  // unused without force elements
          static_assert(std::is_trivially_copyable_v<std::decay_t<decltype(x)>>,
                        "force element states are saved as raw bytes");
          const auto* b = reinterpret_cast<const unsigned char*>(&x);
          w.buffer.insert(w.buffer.end(), b, b + sizeof(x));
        };
        (raw(f), ...);
      },
      s.force_states);
}

/// Reads what put_state wrote into s; false if the data ends early.
template <class SceneT>
bool get_state(binary::Reader& r, typename SceneT::State& s) {
  bool ok = r.get(s.t);
  std::apply(
      [&](auto&... q) {
        ((ok = ok && get_scalars(r, q.position.data(), 3) && get_scalars(r, q.theta.data(), 4) &&
               get_scalars(r, q.p.data(), q.p.size())),
         ...);
      },
      s.q);
  for (auto* v : {&s.v, &s.v_dot, &s.a}) ok = ok && get_scalars(r, v->data(), SceneT::nv);
  ok = ok && get_scalars(r, s.lambda.data(), SceneT::nc);
  std::apply(
      [&](auto&... f) {
        [[maybe_unused]] auto raw = [&](auto& x) {  // unused without force elements
          auto* b = reinterpret_cast<unsigned char*>(&x);
          for (std::size_t i = 0; ok && i < sizeof(x); ++i) ok = r.get(b[i]);
        };
        (raw(f), ...);
      },
      s.force_states);
  return ok;
}

/// What a signature mismatch means, with this scene's sizes.
template <class SceneT>
std::string other_scene() {
  return "the checkpoint is of another scene (its sizes differ from this scene's: " +
         std::to_string(SceneT::num_bodies) + " bodies, " + std::to_string(SceneT::nv) +
         " coordinates, " + std::to_string(SceneT::nc) + " constraint equations, " +
         std::to_string(sizeof(typename SceneT::scalar_type)) + "-byte scalars)";
}

/// A checkpoint of the other integrator gets its own message (not "not a checkpoint").
inline bool has_magic(const unsigned char* data, std::size_t size, const binary::Envelope& e) {
  return size >= 8 && std::memcmp(data, e.magic, 8) == 0;
}

/// What both integrators' checkpoints begin with: the step size and the State.
template <class SceneT>
Result<binary::Writer> state_payload(typename SceneT::scalar_type step,
                                     const typename SceneT::State& s) {
  if (!binary::little_endian_host())
    return make_error(ErrorCode::invalid_argument,
                      "checkpoint: this host is big-endian; the format is little-endian only");
  binary::Writer w;
  w.put(step);
  put_state<SceneT>(w, s);
  return w;
}

/// After reading: everything read, nothing left over, and the step size the integrator has.
template <class Scalar>
Status check_read(bool ok, const binary::Reader& r, Scalar step, Scalar integrator_step,
                  const std::string& name) {
  auto bad = [&](const auto&... parts) {
    return make_error(ErrorCode::bad_file_format, "'", name, "': ", parts...);
  };
  if (!ok || r.remaining() != 0)
    return bad("the data does not match the layout of this scene (",
               ok ? "bytes left over" : "it ends early", ")");
  if (step != integrator_step)
    return bad("taken with the step h = ", static_cast<double>(step),
               " s, the integrator steps h = ", static_cast<double>(integrator_step), " s");
  return Status::success();
}

}  // namespace checkpoint_detail

/// The state and the integrator's history as checkpoint bytes (setup-time: allocates).
template <class SceneT>
Result<std::vector<unsigned char>> save_checkpoint(const typename SceneT::State& s,
                                                   const ImplicitIntegrator<SceneT>& integrator) {
  using checkpoint_detail::put_scalars;
  auto payload = checkpoint_detail::state_payload<SceneT>(integrator.settings().step, s);
  if (!payload) return payload.error();
  binary::Writer& w = *payload;
  typename ImplicitIntegrator<SceneT>::History h;
  integrator.save_history(h);
  w.put(static_cast<std::uint8_t>(h.has_previous));
  w.put(static_cast<std::uint8_t>(h.have_factorization));
  w.put(h.alpha);
  put_scalars(w, h.vd_prev.data(), SceneT::nv);
  put_scalars(w, h.lambda_prev.data(), SceneT::nc);
  w.put(static_cast<std::uint8_t>(h.converged_multipliers));
  if (h.have_factorization) {
    put_scalars(w, h.iteration.data(), Index(SceneT::nv) * Index(SceneT::nv));
    for (const auto& a : h.rotations) put_scalars(w, a.data(), 9);
  }
  const auto& st = h.statistics;
  for (std::int64_t v : {std::int64_t(st.steps), std::int64_t(st.iterations),
                         std::int64_t(st.factorizations), std::int64_t(st.last_iterations),
                         std::int64_t(st.last_factorizations), std::int64_t(st.over_budget)})
    w.put(v);

  return checkpoint_detail::kEnvelope.seal(scene_signature<SceneT>(), w.buffer);
}

/// Restores a checkpoint into s and the integrator (built on the same scene, with the step size
/// the checkpoint was taken with). `name` appears in the messages. On error s and the
/// integrator are left as they were.
template <class SceneT>
Status restore_checkpoint(const unsigned char* data, std::size_t size, typename SceneT::State& s,
                          ImplicitIntegrator<SceneT>& integrator,
                          const std::string& name = "checkpoint") {
  using Scalar = typename SceneT::scalar_type;
  using checkpoint_detail::get_scalars;
  auto bad = [&](const auto&... parts) {
    return make_error(ErrorCode::bad_file_format, "'", name, "': ", parts...);
  };
  if (checkpoint_detail::has_magic(data, size, checkpoint_detail::kExplicitEnvelope))
    return bad("an explicit-integrator checkpoint: restore it into an ExplicitIntegrator");
  auto opened = checkpoint_detail::kEnvelope.open(data, size, scene_signature<SceneT>(), name,
                                                  checkpoint_detail::other_scene<SceneT>());
  if (!opened) return opened.error();

  // Read into copies; commit only when everything was read.
  binary::Reader& r = *opened;
  typename SceneT::State next = s;
  typename ImplicitIntegrator<SceneT>::History h;
  integrator.save_history(h);  // sized like the integrator's
  Scalar step = Scalar(0);
  bool ok = r.get(step) && checkpoint_detail::get_state<SceneT>(r, next);
  std::uint8_t has_previous = 0, have_factorization = 0, converged_multipliers = 0;
  ok = ok && r.get(has_previous) && r.get(have_factorization) && r.get(h.alpha) &&
       get_scalars(r, h.vd_prev.data(), SceneT::nv) &&
       get_scalars(r, h.lambda_prev.data(), SceneT::nc) && r.get(converged_multipliers);
  h.converged_multipliers = converged_multipliers > 2 ? 2 : converged_multipliers;
  h.has_previous = has_previous != 0;
  h.have_factorization = have_factorization != 0;
  if (ok && h.have_factorization) {
    h.iteration.resize(SceneT::nv, SceneT::nv);
    ok = get_scalars(r, h.iteration.data(), Index(SceneT::nv) * Index(SceneT::nv));
    for (auto& a : h.rotations) ok = ok && get_scalars(r, a.data(), 9);
  }
  std::int64_t stats[6] = {};
  for (std::int64_t& v : stats) ok = ok && r.get(v);
  if (Status done = checkpoint_detail::check_read(ok, r, step, integrator.settings().step, name);
      !done)
    return done;
  h.statistics.steps = stats[0];
  h.statistics.iterations = stats[1];
  h.statistics.factorizations = stats[2];
  h.statistics.last_iterations = static_cast<int>(stats[3]);
  h.statistics.last_factorizations = static_cast<int>(stats[4]);
  h.statistics.over_budget = stats[5];
  s = std::move(next);
  integrator.restore_history(h);
  return Status::success();
}

/// The step size and State of a run of the explicit integrator as checkpoint bytes
/// (setup-time: allocates). RK4 starts each step from the State alone, so nothing else is needed
/// to continue bit-identically.
template <class SceneT>
Result<std::vector<unsigned char>> save_checkpoint(const typename SceneT::State& s,
                                                   const ExplicitIntegrator<SceneT>& integrator) {
  auto payload = checkpoint_detail::state_payload<SceneT>(integrator.settings().step, s);
  if (!payload) return payload.error();
  binary::Writer& w = *payload;
  return checkpoint_detail::kExplicitEnvelope.seal(scene_signature<SceneT>(), w.buffer);
}

/// Restores an explicit-integrator checkpoint into s (the integrator must step with the size
/// the checkpoint was taken with). On error s is left as it was.
template <class SceneT>
Status restore_checkpoint(const unsigned char* data, std::size_t size, typename SceneT::State& s,
                          const ExplicitIntegrator<SceneT>& integrator,
                          const std::string& name = "checkpoint") {
  using Scalar = typename SceneT::scalar_type;
  auto bad = [&](const auto&... parts) {
    return make_error(ErrorCode::bad_file_format, "'", name, "': ", parts...);
  };
  if (checkpoint_detail::has_magic(data, size, checkpoint_detail::kEnvelope))
    return bad("an implicit-integrator checkpoint: restore it into an ImplicitIntegrator");
  auto opened = checkpoint_detail::kExplicitEnvelope.open(
      data, size, scene_signature<SceneT>(), name, checkpoint_detail::other_scene<SceneT>());
  if (!opened) return opened.error();
  binary::Reader& r = *opened;
  typename SceneT::State next = s;
  Scalar step = Scalar(0);
  const bool ok = r.get(step) && checkpoint_detail::get_state<SceneT>(r, next);
  if (Status done = checkpoint_detail::check_read(ok, r, step, integrator.settings().step, name);
      !done)
    return done;
  s = std::move(next);
  return Status::success();
}

/// Writes a checkpoint file (either integrator).
template <template <class> class Integrator, class SceneT>
Status save_checkpoint_file(const std::string& path, const typename SceneT::State& s,
                            const Integrator<SceneT>& integrator) {
  auto bytes = save_checkpoint(s, integrator);
  if (!bytes) return bytes.error();
  return binary::write_file(path, *bytes);
}

/// Reads a checkpoint file into s and the integrator (either integrator).
template <template <class> class Integrator, class SceneT>
Status restore_checkpoint_file(const std::string& path, typename SceneT::State& s,
                               Integrator<SceneT>& integrator) {
  auto bytes = binary::read_file(path);
  if (!bytes) return bytes.error();
  return restore_checkpoint(bytes->data(), bytes->size(), s, integrator, path);
}

}  // namespace flexstress
