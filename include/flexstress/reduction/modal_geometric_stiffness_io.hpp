// Binary save and load of modal geometric stiffness (the data of geometric stiffening,
// reduction/modal_geometric_stiffness.hpp), so a program that has only a modal body file (a C
// program, a simulator without the FE mesh) can stiffen the body too. The matrices belong to
// the modes of one body: a file records that body's signature, and loading it for another body
// is an error, never a silently wrong stiffness.
//
// Format, version 1 (binary::Envelope, magic "FLXGEOMS"; little-endian, IEEE 754 double):
//   header: magic, u32 version, u32 byte-order mark, u64 signature of the modal body
//           (modal_body_signature), u64 payload size, u64 FNV-1a checksum of the payload
//   payload: i64 modes n; the 12 matrices G_j (n x n, column-major) in InertialLoadCase order.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "flexstress/core/binary_io.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/reduction/modal_body.hpp"
#include "flexstress/reduction/modal_body_io.hpp"
#include "flexstress/reduction/modal_geometric_stiffness_data.hpp"

namespace flexstress::reduction {

namespace geometric_io_detail {

inline constexpr binary::Envelope kEnvelope{"FLXGEOMS", 1, "geometric stiffness file"};

inline constexpr const char* kCaseNames[num_inertial_load_cases] = {
    "accel_x", "accel_y", "accel_z", "alpha_x", "alpha_y", "alpha_z",
    "spin_xx", "spin_yy", "spin_zz", "spin_xy", "spin_yz", "spin_zx"};

/// Payload bytes for n modes; false when n is implausible.
inline bool payload_size(std::int64_t n, std::uint64_t& out) {
  if (n < 0 || n > (1 << 16)) return false;
  const auto un = static_cast<std::uint64_t>(n);
  out = 8 + 8 * num_inertial_load_cases * un * un;
  return true;
}

}  // namespace geometric_io_detail

/// A fingerprint of modal body data: the FNV-1a hash of its saved image. Two bodies share it
/// only if their files would be the same byte for byte.
inline Result<std::uint64_t> modal_body_signature(const ModalBodyData& body) {
  auto bytes = serialize(body);
  if (!bytes) return bytes.error();
  return binary::fnv1a(bytes->data(), bytes->size());
}

/// Serializes g, computed for `body` (all of its modes), into the version-1 layout.
inline Result<std::vector<unsigned char>> serialize_geometric_stiffness(
    const ModalGeometricStiffness& g, const ModalBodyData& body) {
  if (g.num_modes != body.num_modes)
    return make_error(ErrorCode::size_mismatch, "geometric stiffness of ", g.num_modes,
                      " modes for a body of ", body.num_modes,
                      " (compute it for all of the body's modes); not saved");
  for (int j = 0; j < num_inertial_load_cases; ++j) {
    const MatrixXd& gj = g.cases[static_cast<std::size_t>(j)];
    if (gj.rows() != g.num_modes || gj.cols() != g.num_modes)
      return make_error(ErrorCode::size_mismatch, "geometric stiffness of load case ",
                        geometric_io_detail::kCaseNames[j], " is ", gj.rows(), " x ", gj.cols(),
                        ", not ", g.num_modes, " x ", g.num_modes, "; not saved");
  }
  auto signature = modal_body_signature(body);
  if (!signature) return signature.error();
  binary::Writer w;
  w.put(static_cast<std::int64_t>(g.num_modes));
  for (const MatrixXd& gj : g.cases) w.put_doubles(gj.data(), static_cast<std::size_t>(gj.size()));
  return geometric_io_detail::kEnvelope.seal(*signature, w.buffer);
}

/// Parses a version-1 image made for `body`; `source` names it in messages (a file name).
inline Result<ModalGeometricStiffness> deserialize_geometric_stiffness(
    const unsigned char* data, std::size_t size, const ModalBodyData& body,
    const std::string& source = "geometric stiffness data") {
  auto signature = modal_body_signature(body);
  if (!signature) return signature.error();
  auto reader = geometric_io_detail::kEnvelope.open(
      data, size, *signature, source,
      "made for another modal body (its signature is not this body's: compute the geometric "
      "stiffness from the mesh this body was reduced from, and save it with this body)");
  if (!reader) return reader.error();
  auto bad = [&](const auto&... what) {
    return make_error(ErrorCode::bad_file_format, "'", source, "': ", what...);
  };
  binary::Reader& r = *reader;
  const std::uint64_t payload = size - binary::Envelope::header_size;
  std::int64_t n = 0;
  if (!r.get(n)) return bad("truncated mode count");
  std::uint64_t expected = 0;
  if (!geometric_io_detail::payload_size(n, expected)) return bad("implausible mode count ", n);
  if (expected != payload)
    return bad(n, " modes need ", expected, " bytes of data; the file has ", payload);
  if (n != body.num_modes) return bad("it has ", n, " modes, the body ", body.num_modes);
  ModalGeometricStiffness g;
  g.num_modes = static_cast<Index>(n);
  for (int j = 0; j < num_inertial_load_cases; ++j) {
    MatrixXd& gj = g.cases[static_cast<std::size_t>(j)];
    gj.resize(g.num_modes, g.num_modes);
    r.get_doubles(gj.data(), static_cast<std::size_t>(gj.size()));
    if (!gj.allFinite())
      return bad("non-finite entry in the matrix of load case ",
                 geometric_io_detail::kCaseNames[j]);
  }
  return g;
}

/// Writes g, computed for `body`, to a file.
inline Status save_geometric_stiffness(const ModalGeometricStiffness& g, const ModalBodyData& body,
                                       const std::string& path) {
  auto bytes = serialize_geometric_stiffness(g, body);
  if (!bytes) return bytes.error();
  return binary::write_file(path, *bytes);
}

/// Reads a file written by save_geometric_stiffness for `body`; every defect, and a file made
/// for another body, is an error naming the file.
inline Result<ModalGeometricStiffness> load_geometric_stiffness(const std::string& path,
                                                                const ModalBodyData& body) {
  auto bytes = binary::read_file(path);
  if (!bytes) return bytes.error();
  return deserialize_geometric_stiffness(bytes->data(), bytes->size(), body, path);
}

}  // namespace flexstress::reduction
