// Binary save/load of modal body data: a round trip is bit-exact, and every kind of damaged or
// foreign file gets an error that names the defect; random corruption (a small in-test fuzzer,
// run under ASan/UBSan in CI) never crashes, reads out of bounds or yields non-finite data.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>
#include <string>

#include <doctest/doctest.h>

#include <flexstress/fe/beam_line.hpp>
#include <flexstress/reduction/modal_body_data.hpp>
#include <flexstress/reduction/modal_body_io.hpp>

#include "support/damaged_files.hpp"

namespace test_modal_body_io {

using namespace flexstress;
using namespace flexstress::reduction;

namespace {

// A cantilever-like steel beam, Craig-Bampton with both ends as interface: 6 static + 3
// fixed-interface modes, 7 kept, 2 % damping.
ModalBodyData reduced_beam() {
  fe::Mesh mesh;
  fe::BeamLineSpec spec;
  spec.end = Vector3d(1.5, 0, 0);
  spec.num_elements = 10;
  spec.material = mesh.add_material(fe::steel());
  spec.section = mesh.add_section(fe::rectangular_hollow_section(0.1, 0.05, 0.004));
  const auto line = fe::add_beam_line(mesh, spec);
  ReductionSpec rs;
  rs.interface = {{line.node_at(0.0)}, {line.node_at(1.5)}};
  rs.dynamic_modes.count = 3;
  rs.keep_modes = 7;
  rs.damping_ratio = 0.02;
  auto d = reduce(mesh, rs);
  REQUIRE(d.ok());
  return std::move(*d);
}

std::string output_path(const char* name) {
  return std::string(FLEXSTRESS_TEST_OUTPUT_DIR) + "/" + name;
}

// Rewrites the header checksum after a deliberate change of the payload, so the check under
// test is the one after the checksum.
void reseal(std::vector<unsigned char>& bytes) {
  const std::uint64_t h =
      binary::fnv1a(bytes.data() + modal_body_header_size, bytes.size() - modal_body_header_size);
  std::memcpy(bytes.data() + 24, &h, 8);
}

std::string error_of(const std::vector<unsigned char>& bytes) {
  auto r = deserialize(bytes.data(), bytes.size(), "test.fsm");
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().code == ErrorCode::bad_file_format);
  return r.error().what();
}

// Offset of eigenvalue i in the file: header, 3 flags, 3 counts, 3 scalars, S, Lambda.
std::size_t eigenvalue_offset(const ModalBodyData& d, Index i) {
  const auto n = static_cast<std::size_t>(d.num_modes);
  return modal_body_header_size + 3 + 24 + 24 + 8 * (3 * (n + 1) + 9 * (n + 1) * (n + 1)) +
         8 * static_cast<std::size_t>(i);
}

}  // namespace

TEST_CASE("modal body data survives a save and load bit for bit") {
  const ModalBodyData d = reduced_beam();
  const std::string path = output_path("beam.fsm");
  REQUIRE(save_modal_body(d, path).ok());
  auto back = load_modal_body(path);
  REQUIRE(back.ok());
  const ModalBodyData& e = *back;
  CHECK(e.method == d.method);
  CHECK(e.mass_options.lumping == d.mass_options.lumping);
  CHECK(e.mass_options.beam_rotary_inertia == d.mass_options.beam_rotary_inertia);
  CHECK(e.num_modes == 7);
  CHECK(e.inertia.mass == d.inertia.mass);
  CHECK(e.mass_residual == d.mass_residual);
  CHECK(e.stiffness_residual == d.stiffness_residual);
  for (std::size_t a = 0; a < d.inertia.first.size(); ++a)
    CHECK(e.inertia.first[a] == d.inertia.first[a]);
  for (std::size_t a = 0; a < d.inertia.second.size(); ++a)
    CHECK(e.inertia.second[a] == d.inertia.second[a]);
  CHECK(e.eigenvalues == d.eigenvalues);
  CHECK(e.damping_ratios == d.damping_ratios);
  CHECK(e.modal_stiffness == d.modal_stiffness);
  CHECK(e.node_positions == d.node_positions);
  CHECK(e.node_has_rotation == d.node_has_rotation);
  CHECK(e.phi_translation == d.phi_translation);
  CHECK(e.phi_rotation == d.phi_rotation);
  CHECK(e.interface_nodes == d.interface_nodes);
  // And the file is what the format says: header + payload of the announced size.
  auto bytes = serialize(d);
  REQUIRE(bytes.ok());
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  CHECK(static_cast<std::size_t>(in.tellg()) == bytes->size());
}

TEST_CASE("damaged or foreign modal body files get errors that say what is wrong") {
  const ModalBodyData d = reduced_beam();
  const auto good = *serialize(d);

  SUBCASE("missing file") {
    auto r = load_modal_body(output_path("no-such-file.fsm"));
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().code == ErrorCode::io_error);
    CHECK(r.error().what().find("no-such-file.fsm") != std::string::npos);
  }
  SUBCASE("not a modal body file") {
    const std::string text = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
    auto r = deserialize(reinterpret_cast<const unsigned char*>(text.data()), text.size(), "x.msh");
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().what().find("x.msh") != std::string::npos);
    CHECK(r.error().what().find("FLXMODAL") != std::string::npos);
  }
  SUBCASE("truncated, a flipped bit, a newer format version") {
    testing::check_common_damage(good, error_of);
  }
  SUBCASE("big-endian byte order") {
    auto bytes = good;
    std::swap(bytes[12], bytes[15]);
    std::swap(bytes[13], bytes[14]);
    CHECK(error_of(bytes).find("byte-order") != std::string::npos);
  }
  SUBCASE("counts that do not match the data") {
    auto bytes = good;
    bytes[modal_body_header_size + 3] = 9;  // 9 modes announced, data for 7
    reseal(bytes);
    CHECK(error_of(bytes).find("9 modes") != std::string::npos);
  }
  SUBCASE("a NaN eigenvalue") {
    auto bytes = good;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    std::memcpy(bytes.data() + eigenvalue_offset(d, 2), &nan, 8);
    reseal(bytes);
    CHECK(error_of(bytes).find("eigenvalue of mode 2") != std::string::npos);
  }
  SUBCASE("a NaN orthonormalization residual") {
    auto bytes = good;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    // After three one-byte codes, three counts and the mass: the mass residual.
    std::memcpy(bytes.data() + modal_body_header_size + 3 + 3 * 8 + 8, &nan, 8);
    reseal(bytes);
    CHECK(error_of(bytes).find("orthonormalization residuals nan") != std::string::npos);
  }
  SUBCASE("an unknown reduction method") {
    auto bytes = good;
    bytes[modal_body_header_size] = 7;
    reseal(bytes);
    CHECK(error_of(bytes).find("reduction method code 7") != std::string::npos);
  }
}

TEST_CASE("random corruption never crashes the loader (in-test fuzzing)") {
  const auto good = *serialize(reduced_beam());
  std::mt19937_64 rng(20261122);
  int rejected = 0, accepted = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    auto bytes = good;
    const int kind = trial % 3;
    if (kind == 0) {  // random bytes overwritten, checksum resealed half of the time
      for (int k = 0; k < 4; ++k) bytes[rng() % bytes.size()] = static_cast<unsigned char>(rng());
    } else if (kind == 1) {  // random truncation
      bytes.resize(rng() % bytes.size());
    } else {  // a random count or flag in the payload's first 51 bytes, then resealed
      bytes[modal_body_header_size + rng() % 51] = static_cast<unsigned char>(rng());
    }
    if (kind != 1 && (kind == 2 || trial % 2 == 0)) reseal(bytes);
    auto r = deserialize(bytes.data(), bytes.size(), "fuzz");
    if (!r) {
      ++rejected;
      CHECK(r.error().code == ErrorCode::bad_file_format);
      continue;
    }
    ++accepted;  // a change that kept the data valid (a position, a mode shape entry, ...)
    CHECK(std::isfinite(r->inertia.mass));
    CHECK(r->eigenvalues.allFinite());
    CHECK(r->phi_translation.allFinite());
  }
  MESSAGE(rejected << " corrupted images rejected, " << accepted << " accepted as valid");
  CHECK(rejected > 1500);
}

}  // namespace test_modal_body_io
