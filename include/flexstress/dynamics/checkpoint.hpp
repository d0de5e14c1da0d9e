// Checkpoint and restore of a running scene: the State (time, coordinates, velocities,
// accelerations, multipliers, force elements' internal states) and the implicit integrator's
// history (its predictor and the factorization the modified Newton reuses), so a run stopped and
// restored continues bit-identically to one that never stopped. A long fatigue campaign can be
// split across jobs, or resumed after a crash.
//
// Format, version 1 (host byte order, which must be little-endian; checked):
//   "FLXCKPT1"  8-byte magic
//   u32 version, u32 byte-order mark 0x01020304
//   u64 scene signature (a hash of the scene's sizes: Scalar, coordinates, equations, bodies
//       and their modes, joints and their equations, force-element state sizes)
//   u64 payload size, u64 FNV-1a checksum of the payload
//   payload: Scalar h; Scalar t; per body position (3), Euler parameters (4), modal coordinates;
//            v, v_dot, a (nv each), lambda (nc); each force element's state (raw bytes);
//            u8 has_previous, u8 have_factorization; Scalar alpha; vd_prev (nv);
//            the iteration matrix (nv x nv, column-major) if factorized; statistics (6 x i64).
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
#include "flexstress/dynamics/implicit_integrator.hpp"

namespace flexstress {

namespace checkpoint_detail {

inline constexpr binary::Envelope kEnvelope{"FLXCKPT1", 1, "checkpoint"};

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

/// The state and the integrator's history as checkpoint bytes (setup-time: allocates).
template <class SceneT>
Result<std::vector<unsigned char>> save_checkpoint(const typename SceneT::State& s,
                                                   const ImplicitIntegrator<SceneT>& integrator) {
  using checkpoint_detail::put_scalars;
  if (!binary::little_endian_host())
    return make_error(ErrorCode::invalid_argument,
                      "checkpoint: this host is big-endian; the format is little-endian only");
  binary::Writer w;
  w.put(integrator.settings().step);
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
        auto raw = [&](const auto& x) {
          static_assert(std::is_trivially_copyable_v<std::decay_t<decltype(x)>>,
                        "force element states are saved as raw bytes");
          const auto* b = reinterpret_cast<const unsigned char*>(&x);
          w.buffer.insert(w.buffer.end(), b, b + sizeof(x));
        };
        (raw(f), ...);
      },
      s.force_states);
  typename ImplicitIntegrator<SceneT>::History h;
  integrator.save_history(h);
  w.put(static_cast<std::uint8_t>(h.has_previous));
  w.put(static_cast<std::uint8_t>(h.have_factorization));
  w.put(h.alpha);
  put_scalars(w, h.vd_prev.data(), SceneT::nv);
  if (h.have_factorization)
    put_scalars(w, h.iteration.data(), Index(SceneT::nv) * Index(SceneT::nv));
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
  auto opened = checkpoint_detail::kEnvelope.open(
      data, size, scene_signature<SceneT>(), name,
      "the checkpoint is of another scene (its sizes differ from this scene's: " +
          std::to_string(SceneT::num_bodies) + " bodies, " + std::to_string(SceneT::nv) +
          " coordinates, " + std::to_string(SceneT::nc) + " constraint equations, " +
          std::to_string(sizeof(Scalar)) + "-byte scalars)");
  if (!opened) return opened.error();

  // Read into copies; commit only when everything was read.
  binary::Reader& r = *opened;
  typename SceneT::State next = s;
  typename ImplicitIntegrator<SceneT>::History h;
  integrator.save_history(h);  // sized like the integrator's
  Scalar step = Scalar(0);
  bool ok = r.get(step) && r.get(next.t);
  std::apply(
      [&](auto&... q) {
        ((ok = ok && get_scalars(r, q.position.data(), 3) && get_scalars(r, q.theta.data(), 4) &&
               get_scalars(r, q.p.data(), q.p.size())),
         ...);
      },
      next.q);
  for (auto* v : {&next.v, &next.v_dot, &next.a}) ok = ok && get_scalars(r, v->data(), SceneT::nv);
  ok = ok && get_scalars(r, next.lambda.data(), SceneT::nc);
  std::apply(
      [&](auto&... f) {
        auto raw = [&](auto& x) {
          auto* b = reinterpret_cast<unsigned char*>(&x);
          for (std::size_t i = 0; ok && i < sizeof(x); ++i) ok = r.get(b[i]);
        };
        (raw(f), ...);
      },
      next.force_states);
  std::uint8_t has_previous = 0, have_factorization = 0;
  ok = ok && r.get(has_previous) && r.get(have_factorization) && r.get(h.alpha) &&
       get_scalars(r, h.vd_prev.data(), SceneT::nv);
  h.has_previous = has_previous != 0;
  h.have_factorization = have_factorization != 0;
  if (ok && h.have_factorization) {
    h.iteration.resize(SceneT::nv, SceneT::nv);
    ok = get_scalars(r, h.iteration.data(), Index(SceneT::nv) * Index(SceneT::nv));
  }
  std::int64_t stats[6] = {};
  for (std::int64_t& v : stats) ok = ok && r.get(v);
  if (!ok || r.remaining() != 0)
    return bad("the data does not match the layout of this scene (",
               ok ? "bytes left over" : "it ends early", ")");
  if (step != integrator.settings().step)
    return bad("taken with the step h = ", static_cast<double>(step),
               " s, the integrator steps h = ", static_cast<double>(integrator.settings().step),
               " s");
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

/// Writes a checkpoint file.
template <class SceneT>
Status save_checkpoint_file(const std::string& path, const typename SceneT::State& s,
                            const ImplicitIntegrator<SceneT>& integrator) {
  auto bytes = save_checkpoint(s, integrator);
  if (!bytes) return bytes.error();
  return binary::write_file(path, *bytes);
}

/// Reads a checkpoint file into s and the integrator.
template <class SceneT>
Status restore_checkpoint_file(const std::string& path, typename SceneT::State& s,
                               ImplicitIntegrator<SceneT>& integrator) {
  auto bytes = binary::read_file(path);
  if (!bytes) return bytes.error();
  return restore_checkpoint(bytes->data(), bytes->size(), s, integrator, path);
}

}  // namespace flexstress
