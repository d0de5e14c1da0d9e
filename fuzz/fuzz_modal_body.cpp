// libFuzzer target: the modal body loader. Two kinds of input, chosen by the first byte:
//  - even: the bytes as they come (the loader must refuse them without crashing);
//  - odd:  a valid file of a small body with the input's bytes written over its data at
//    fuzzer-chosen offsets, and its checksum recomputed, so that the corruption reaches the
//    checks behind the checksum (counts, codes, node indices, finite values).
// Whatever the input, deserialize returns; when it accepts, writing the body again gives the
// same bytes (nothing read is lost or invented).
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include <flexstress/reduction/modal_body_io.hpp>

namespace {

void require(bool condition) {
  if (!condition) __builtin_trap();
}

// Two modes, three nodes (one with rotations), one interface node: every array non-empty.
std::vector<unsigned char> valid_file() {
  using namespace flexstress;
  reduction::ModalBodyData d;
  const Index n = 2, m = 3;
  d.num_modes = n;
  d.inertia.num_modes = n;
  d.inertia.mass = 4.5;
  d.inertia.first.assign(n + 1, Vector3d(0.1, 0.2, 0.3));
  d.inertia.second.assign((n + 1) * (n + 1), Matrix3d::Identity());
  d.eigenvalues = Eigen::Vector2d(10.0, 40.0);
  d.damping_ratios = Eigen::Vector2d(0.01, 0.02);
  d.modal_stiffness = Eigen::Matrix2d(d.eigenvalues.asDiagonal());
  d.node_positions = {Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(2, 0, 0)};
  d.node_has_rotation = {1, 0, 0};
  d.phi_translation = MatrixXd::Constant(3 * m, n, 0.5);
  d.phi_rotation = MatrixXd::Constant(3 * m, n, 0.25);
  d.interface_nodes = {0};
  auto bytes = reduction::serialize(d);
  require(bytes.ok());
  return *bytes;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace flexstress::reduction;
  static const std::vector<unsigned char> valid = valid_file();
  std::vector<unsigned char> bytes;
  if (size > 0 && data[0] % 2 == 1) {
    // Patches of (offset into the data, length, bytes) written over the valid file's data.
    bytes = valid;
    const std::size_t header = io_detail::kHeaderSize, payload = valid.size() - header;
    for (std::size_t i = 1; i + 2 <= size;) {
      const std::size_t offset = data[i] % payload, length = data[i + 1] % 9;
      i += 2;
      for (std::size_t k = 0; k < length && i < size; ++k, ++i)
        bytes[header + (offset + k) % payload] = data[i];
    }
    const std::uint64_t checksum = flexstress::binary::fnv1a(bytes.data() + header, payload);
    std::memcpy(bytes.data() + header - 8, &checksum, 8);
  } else {
    bytes.assign(data, data + size);
  }
  auto body = deserialize(bytes.data(), bytes.size(), "fuzz.bin");
  if (!body) {
    require(body.error().message.rfind("fuzz.bin", 0) == 0);
    return 0;
  }
  auto again = serialize(*body);
  require(again.ok() && *again == bytes);
  return 0;
}
