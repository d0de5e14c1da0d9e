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
// Application data that lives outside the scene (a streaming damage meter, an energy audit) is
// the application's to save alongside.
#pragma once

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "flexstress/core/binary_io.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/dynamics/implicit_integrator.hpp"

namespace flexstress {

namespace checkpoint_detail {

inline constexpr char kMagic[8] = {'F', 'L', 'X', 'C', 'K', 'P', 'T', '1'};
inline constexpr std::uint32_t kVersion = 1;
inline constexpr std::uint32_t kByteOrderMark = 0x01020304u;
inline constexpr std::size_t kHeaderSize = 8 + 4 + 4 + 8 + 8 + 8;

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

  binary::Writer out;
  out.buffer.insert(out.buffer.end(), checkpoint_detail::kMagic, checkpoint_detail::kMagic + 8);
  out.put(checkpoint_detail::kVersion);
  out.put(checkpoint_detail::kByteOrderMark);
  out.put(scene_signature<SceneT>());
  out.put(static_cast<std::uint64_t>(w.buffer.size()));
  out.put(binary::fnv1a(w.buffer.data(), w.buffer.size()));
  out.buffer.insert(out.buffer.end(), w.buffer.begin(), w.buffer.end());
  return std::move(out.buffer);
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
  if (size < 8 || std::memcmp(data, checkpoint_detail::kMagic, 8) != 0)
    return bad("not a flexstress checkpoint (the first 8 bytes are not \"FLXCKPT1\")");
  if (size < checkpoint_detail::kHeaderSize)
    return bad("truncated header (", size, " bytes, the header alone is ",
               checkpoint_detail::kHeaderSize, ")");
  binary::Reader header(data + 8, checkpoint_detail::kHeaderSize - 8);
  std::uint32_t version = 0, bom = 0;
  std::uint64_t signature = 0, payload = 0, checksum = 0;
  header.get(version);
  header.get(bom);
  header.get(signature);
  header.get(payload);
  header.get(checksum);
  if (bom != checkpoint_detail::kByteOrderMark)
    return bad("byte-order mark ", bom, " is not ", checkpoint_detail::kByteOrderMark,
               " (written on a host of the other byte order)");
  if (version != checkpoint_detail::kVersion)
    return bad("format version ", version, " is not supported (this library reads version ",
               checkpoint_detail::kVersion, ")");
  if (signature != scene_signature<SceneT>())
    return bad("the checkpoint is of another scene (its sizes differ from this scene's: ",
               SceneT::num_bodies, " bodies, ", SceneT::nv, " coordinates, ", SceneT::nc,
               " constraint equations, ", sizeof(Scalar), "-byte scalars)");
  if (payload != size - checkpoint_detail::kHeaderSize)
    return bad("the header announces ", payload, " bytes of data but the file holds ",
               size - checkpoint_detail::kHeaderSize, " (truncated or padded)");
  const unsigned char* body = data + checkpoint_detail::kHeaderSize;
  if (binary::fnv1a(body, static_cast<std::size_t>(payload)) != checksum)
    return bad("checksum mismatch: the data is corrupted");

  // Read into copies; commit only when everything was read.
  binary::Reader r(body, static_cast<std::size_t>(payload));
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
  std::ofstream out(path, std::ios::binary);
  if (!out) return make_error(ErrorCode::io_error, "cannot open '", path, "' for writing");
  out.write(reinterpret_cast<const char*>(bytes->data()),
            static_cast<std::streamsize>(bytes->size()));
  if (!out) return make_error(ErrorCode::io_error, "writing '", path, "' failed");
  return Status::success();
}

/// Reads a checkpoint file into s and the integrator.
template <class SceneT>
Status restore_checkpoint_file(const std::string& path, typename SceneT::State& s,
                               ImplicitIntegrator<SceneT>& integrator) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return make_error(ErrorCode::io_error, "cannot open '", path, "' for reading");
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                         std::istreambuf_iterator<char>());
  return restore_checkpoint(bytes.data(), bytes.size(), s, integrator, path);
}

}  // namespace flexstress
