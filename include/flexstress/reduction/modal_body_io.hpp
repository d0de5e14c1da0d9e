// Binary save and load of modal body data, so a reduction computed once (seconds for a brick
// body) is loaded by a simulator in milliseconds, and a body reduced elsewhere can be shipped.
//
// Format, version 1 (all integers and floats little-endian, IEEE 754 double):
//   "FLXMODAL"  8-byte magic
//   u32 version, u32 byte-order mark 0x01020304
//   u64 payload size, u64 FNV-1a checksum of the payload
//   payload: u8 method, u8 lumping, u8 rotary inertia; i64 modes n, nodes m, interface nodes k;
//            f64 mass, mass residual, stiffness residual; S_a (3 (n+1)); Lambda_ab (9 (n+1)^2,
//            row-major over (a, b), each 3x3 column-major); eigenvalues (n); damping ratios (n);
//            modal stiffness (n x n, column-major); node positions (3 m); u8 has-rotation (m);
//            Phi_R (3m x n) and Phi_theta (3m x n), column-major; interface nodes (k, i64).
// The loader checks everything it reads (magic, version, byte order, sizes against the file's
// length before allocating, checksum, enum values, finite numbers, positive mass, node indices)
// and names what is wrong and where; a corrupted or foreign file is an error, never a crash.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "flexstress/core/binary_io.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/fe/mass_options.hpp"
#include "flexstress/reduction/modal_body.hpp"

namespace flexstress::reduction {

namespace io_detail {

inline constexpr char kMagic[8] = {'F', 'L', 'X', 'M', 'O', 'D', 'A', 'L'};
inline constexpr std::uint32_t kVersion = 1;
inline constexpr std::uint32_t kByteOrderMark = 0x01020304u;
inline constexpr std::size_t kHeaderSize = 8 + 4 + 4 + 8 + 8;

using binary::fnv1a;
using binary::little_endian_host;
using binary::Reader;
using binary::Writer;

/// Payload size for n modes, m nodes, k interface nodes; false on overflow.
inline bool payload_size(std::int64_t n, std::int64_t m, std::int64_t k, std::uint64_t& out) {
  if (n < 0 || m < 0 || k < 0 || n > (1 << 20) || m > (std::int64_t(1) << 32) ||
      k > (std::int64_t(1) << 32))
    return false;
  const auto un = static_cast<std::uint64_t>(n), um = static_cast<std::uint64_t>(m),
             uk = static_cast<std::uint64_t>(k);
  const std::uint64_t doubles =
      3 + 3 * (un + 1) + 9 * (un + 1) * (un + 1) + 2 * un + un * un + 3 * um + 2 * (3 * um * un);
  out = 3 + 3 * 8 + 8 * doubles + um + 8 * uk;
  return true;
}

inline bool all_finite(const double* p, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(p[i])) return false;
  return true;
}

}  // namespace io_detail

/// Bytes before the payload (magic, version, byte-order mark, payload size, checksum): where
/// the payload and its FNV-1a checksum (binary::fnv1a) start, for tools that write or inspect
/// the format.
inline constexpr std::size_t modal_body_header_size = io_detail::kHeaderSize;

/// Serializes d into the version-1 byte layout (header included).
inline Result<std::vector<unsigned char>> serialize(const ModalBodyData& d) {
  using io_detail::Writer;
  if (!io_detail::little_endian_host())
    return make_error(ErrorCode::invalid_argument,
                      "modal body files are little-endian; this host is not (not supported)");
  const Index n = d.num_modes, m = d.num_nodes(), k = static_cast<Index>(d.interface_nodes.size());
  if (d.eigenvalues.size() != n || d.damping_ratios.size() != n || d.modal_stiffness.rows() != n ||
      d.modal_stiffness.cols() != n || d.phi_translation.rows() != 3 * m ||
      d.phi_translation.cols() != n || d.phi_rotation.rows() != 3 * m ||
      d.phi_rotation.cols() != n || static_cast<Index>(d.node_has_rotation.size()) != m ||
      d.inertia.num_modes != n || static_cast<Index>(d.inertia.first.size()) != n + 1 ||
      static_cast<Index>(d.inertia.second.size()) != (n + 1) * (n + 1))
    return make_error(ErrorCode::size_mismatch,
                      "modal body data is inconsistent (array sizes do not match ", n,
                      " modes and ", m, " nodes); not saved");
  Writer w;
  w.put(static_cast<std::uint8_t>(d.method));
  w.put(static_cast<std::uint8_t>(d.mass_options.lumping));
  w.put(static_cast<std::uint8_t>(d.mass_options.beam_rotary_inertia ? 1 : 0));
  w.put(static_cast<std::int64_t>(n));
  w.put(static_cast<std::int64_t>(m));
  w.put(static_cast<std::int64_t>(k));
  w.put(d.inertia.mass);
  w.put(d.mass_residual);
  w.put(d.stiffness_residual);
  for (const Vector3d& s : d.inertia.first) w.put_doubles(s.data(), 3);
  for (const Matrix3d& l : d.inertia.second) w.put_doubles(l.data(), 9);
  w.put_doubles(d.eigenvalues.data(), static_cast<std::size_t>(n));
  w.put_doubles(d.damping_ratios.data(), static_cast<std::size_t>(n));
  w.put_doubles(d.modal_stiffness.data(), static_cast<std::size_t>(n * n));
  for (const Vector3d& x : d.node_positions) w.put_doubles(x.data(), 3);
  for (unsigned char r : d.node_has_rotation) w.put(static_cast<std::uint8_t>(r));
  w.put_doubles(d.phi_translation.data(), static_cast<std::size_t>(3 * m * n));
  w.put_doubles(d.phi_rotation.data(), static_cast<std::size_t>(3 * m * n));
  for (Index node : d.interface_nodes) w.put(static_cast<std::int64_t>(node));

  Writer out;
  out.buffer.insert(out.buffer.end(), io_detail::kMagic, io_detail::kMagic + 8);
  out.put(io_detail::kVersion);
  out.put(io_detail::kByteOrderMark);
  out.put(static_cast<std::uint64_t>(w.buffer.size()));
  out.put(io_detail::fnv1a(w.buffer.data(), w.buffer.size()));
  out.buffer.insert(out.buffer.end(), w.buffer.begin(), w.buffer.end());
  return std::move(out.buffer);
}

/// Parses a version-1 byte image; `source` names it in messages (a file name).
inline Result<ModalBodyData> deserialize(const unsigned char* data, std::size_t size,
                                         const std::string& source = "modal body data") {
  using io_detail::Reader;
  auto bad = [&](auto&&... what) {
    return make_error(ErrorCode::bad_file_format, source, ": ", what...);
  };
  if (!io_detail::little_endian_host())
    return make_error(ErrorCode::invalid_argument,
                      "modal body files are little-endian; this host is not (not supported)");
  if (size < 8 || std::memcmp(data, io_detail::kMagic, 8) != 0)
    return bad("not a flexstress modal body file (the first 8 bytes are not \"FLXMODAL\")");
  if (size < io_detail::kHeaderSize)
    return bad("truncated header (", size, " bytes, the header alone is ", io_detail::kHeaderSize,
               ")");
  Reader header(data + 8, io_detail::kHeaderSize - 8);
  std::uint32_t version = 0, bom = 0;
  std::uint64_t payload = 0, checksum = 0;
  header.get(version);
  header.get(bom);
  header.get(payload);
  header.get(checksum);
  if (bom != io_detail::kByteOrderMark)
    return bad("byte-order mark ", bom, " is not ", io_detail::kByteOrderMark,
               " (written on a big-endian machine, or corrupted)");
  if (version != io_detail::kVersion)
    return bad("format version ", version, " is not supported (this library reads version ",
               io_detail::kVersion, ")");
  if (payload != size - io_detail::kHeaderSize)
    return bad("the header announces ", payload, " bytes of data but the file holds ",
               size - io_detail::kHeaderSize, " (truncated or padded)");
  const unsigned char* body = data + io_detail::kHeaderSize;
  if (io_detail::fnv1a(body, static_cast<std::size_t>(payload)) != checksum)
    return bad("checksum mismatch: the data is corrupted");

  Reader r(body, static_cast<std::size_t>(payload));
  std::uint8_t method = 0, lumping = 0, rotary = 0;
  std::int64_t n = 0, m = 0, k = 0;
  r.get(method);
  r.get(lumping);
  r.get(rotary);
  if (!r.get(n) || !r.get(m) || !r.get(k)) return bad("truncated counts");
  std::uint64_t expected = 0;
  if (!io_detail::payload_size(n, m, k, expected))
    return bad("implausible counts (", n, " modes, ", m, " nodes, ", k, " interface nodes)");
  if (expected != payload)
    return bad(n, " modes, ", m, " nodes and ", k, " interface nodes need ", expected,
               " bytes of data; the file has ", payload);
  if (method > 1) return bad("unknown reduction method code ", int(method));
  if (lumping > 1) return bad("unknown mass lumping code ", int(lumping));
  if (rotary > 1) return bad("rotary-inertia flag ", int(rotary), " is not 0 or 1");

  // The sizes are now known to match the payload: allocate and read (cannot run out).
  ModalBodyData d;
  d.method = static_cast<ReductionMethod>(method);
  d.mass_options.lumping = static_cast<fe::MassLumping>(lumping);
  d.mass_options.beam_rotary_inertia = rotary == 1;
  d.num_modes = static_cast<Index>(n);
  r.get(d.inertia.mass);
  r.get(d.mass_residual);
  r.get(d.stiffness_residual);
  d.inertia.num_modes = d.num_modes;
  d.inertia.first.assign(static_cast<std::size_t>(n + 1), Vector3d::Zero());
  d.inertia.second.assign(static_cast<std::size_t>((n + 1) * (n + 1)), Matrix3d::Zero());
  for (Vector3d& s : d.inertia.first) r.get_doubles(s.data(), 3);
  for (Matrix3d& l : d.inertia.second) r.get_doubles(l.data(), 9);
  d.eigenvalues.resize(n);
  d.damping_ratios.resize(n);
  d.modal_stiffness.resize(n, n);
  r.get_doubles(d.eigenvalues.data(), static_cast<std::size_t>(n));
  r.get_doubles(d.damping_ratios.data(), static_cast<std::size_t>(n));
  r.get_doubles(d.modal_stiffness.data(), static_cast<std::size_t>(n * n));
  d.node_positions.assign(static_cast<std::size_t>(m), Vector3d::Zero());
  for (Vector3d& x : d.node_positions) r.get_doubles(x.data(), 3);
  d.node_has_rotation.assign(static_cast<std::size_t>(m), 0);
  for (unsigned char& f : d.node_has_rotation) {
    std::uint8_t v = 0;
    r.get(v);
    if (v > 1)
      return bad("has-rotation flag ", int(v), " of node ", &f - d.node_has_rotation.data(),
                 " is not 0 or 1");
    f = v;
  }
  d.phi_translation.resize(3 * m, n);
  d.phi_rotation.resize(3 * m, n);
  r.get_doubles(d.phi_translation.data(), static_cast<std::size_t>(3 * m * n));
  r.get_doubles(d.phi_rotation.data(), static_cast<std::size_t>(3 * m * n));
  for (std::int64_t i = 0; i < k; ++i) {
    std::int64_t node = 0;
    r.get(node);
    if (node < 0 || node >= m)
      return bad("interface node ", i, " refers to node ", node, " of ", m);
    d.interface_nodes.push_back(static_cast<Index>(node));
  }

  // Values: finite everywhere, a positive mass, non-negative eigenvalues and damping ratios.
  auto finite = [](const auto& a) {
    return io_detail::all_finite(a.data(), std::size_t(a.size()));
  };
  if (!(std::isfinite(d.inertia.mass) && d.inertia.mass > 0))
    return bad("mass ", d.inertia.mass, " is not a positive number");
  if (!(d.mass_residual >= 0 && std::isfinite(d.mass_residual) && d.stiffness_residual >= 0 &&
        std::isfinite(d.stiffness_residual)))
    return bad("orthonormalization residuals ", d.mass_residual, " and ", d.stiffness_residual,
               " are not non-negative numbers");
  for (std::size_t a = 0; a < d.inertia.first.size(); ++a)
    if (!finite(d.inertia.first[a])) return bad("non-finite first moment S_", a);
  for (std::size_t a = 0; a < d.inertia.second.size(); ++a)
    if (!finite(d.inertia.second[a])) return bad("non-finite inertia integral Lambda entry ", a);
  for (Index i = 0; i < n; ++i) {
    if (!(std::isfinite(d.eigenvalues(i)) && d.eigenvalues(i) >= 0))
      return bad("eigenvalue of mode ", i, " is ", d.eigenvalues(i));
    if (!(d.damping_ratios(i) >= 0 && d.damping_ratios(i) < 1))
      return bad("damping ratio of mode ", i, " is ", d.damping_ratios(i), " (must lie in [0, 1))");
  }
  if (!finite(d.modal_stiffness)) return bad("non-finite modal stiffness");
  for (std::size_t i = 0; i < d.node_positions.size(); ++i)
    if (!finite(d.node_positions[i])) return bad("non-finite position of node ", i);
  if (!finite(d.phi_translation) || !finite(d.phi_rotation))
    return bad("non-finite mode shape entries");
  return d;
}

/// Writes d to a file (version-1 layout).
inline Status save_modal_body(const ModalBodyData& d, const std::string& path) {
  auto bytes = serialize(d);
  if (!bytes) return bytes.error();
  return binary::write_file(path, *bytes);
}

/// Reads a file written by save_modal_body; every defect is an error naming the file.
inline Result<ModalBodyData> load_modal_body(const std::string& path) {
  auto bytes = binary::read_file(path);
  if (!bytes) return bytes.error();
  return deserialize(bytes->data(), bytes->size(), "'" + path + "'");
}

}  // namespace flexstress::reduction
