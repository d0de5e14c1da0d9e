// Binary save/load of modal geometric stiffness: a round trip is bit-exact, a file made for
// another modal body is refused, every kind of damaged file gets an error that names the
// defect, and random corruption (run under ASan/UBSan in CI) never crashes the loader.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include <flexstress/fe/beam_line.hpp>
#include <flexstress/reduction/modal_body_data.hpp>
#include <flexstress/reduction/modal_geometric_stiffness.hpp>
#include <flexstress/reduction/modal_geometric_stiffness_io.hpp>

#include "support/damaged_files.hpp"

namespace test_modal_geometric_stiffness_io {

using namespace flexstress;
using namespace flexstress::reduction;

namespace {

// A 1.5 m steel cantilever, Craig-Bampton with its root as interface, 6 modes, and its
// geometric stiffness reacted at the root.
struct Blade {
  ModalBodyData data;
  ModalGeometricStiffness geometric;
};

Blade make_blade(double length) {
  fe::Mesh mesh;
  fe::BeamLineSpec spec;
  spec.end = Vector3d(length, 0, 0);
  spec.num_elements = 10;
  spec.material = mesh.add_material(fe::steel());
  spec.section = mesh.add_section(fe::rectangular_hollow_section(0.1, 0.05, 0.004));
  const auto line = fe::add_beam_line(mesh, spec);
  ReductionSpec rs;
  rs.interface = {{line.node_at(0.0)}};
  rs.dynamic_modes.count = 6;
  auto d = reduce(mesh, rs);
  REQUIRE(d.ok());
  auto g = modal_geometric_stiffness(mesh, *d, clamp_interface_nodes(*d));
  REQUIRE(g.ok());
  return {std::move(*d), std::move(*g)};
}

const Blade& blade() {
  static const Blade b = make_blade(1.5);
  return b;
}

std::string output_path(const char* name) {
  return std::string(FLEXSTRESS_TEST_OUTPUT_DIR) + "/" + name;
}

constexpr std::size_t kHeader = binary::Envelope::header_size;

// Rewrites the header checksum after a deliberate change of the payload, so that the check
// under test is one after the checksum.
void reseal(std::vector<unsigned char>& bytes) {
  const std::uint64_t h = binary::fnv1a(bytes.data() + kHeader, bytes.size() - kHeader);
  std::memcpy(bytes.data() + 32, &h, 8);
}

std::string error_of(const std::vector<unsigned char>& bytes) {
  auto r = deserialize_geometric_stiffness(bytes.data(), bytes.size(), blade().data, "g.fsgeom");
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().code == ErrorCode::bad_file_format);
  CHECK(r.error().what().find("g.fsgeom") != std::string::npos);
  return r.error().what();
}

}  // namespace

TEST_CASE("geometric stiffness survives a save and load bit for bit") {
  const Blade& b = blade();
  // The axial tension of a spin (the spin_xx field pulls along the beam) stiffens its bending.
  CHECK(b.geometric.cases[static_cast<std::size_t>(InertialLoadCase::spin_xx)].norm() > 0);
  const std::string path = output_path("blade.fsgeom");
  REQUIRE(save_geometric_stiffness(b.geometric, b.data, path).ok());
  auto loaded = load_geometric_stiffness(path, b.data);
  REQUIRE_MESSAGE(loaded.ok(), loaded.error().what());
  CHECK(loaded->num_modes == b.geometric.num_modes);
  for (std::size_t j = 0; j < b.geometric.cases.size(); ++j) {
    CAPTURE(j);
    REQUIRE(loaded->cases[j].rows() == b.geometric.num_modes);
    CHECK(std::memcmp(loaded->cases[j].data(), b.geometric.cases[j].data(),
                      sizeof(double) * static_cast<std::size_t>(b.geometric.cases[j].size())) == 0);
  }
}

TEST_CASE("geometric stiffness is saved and loaded only with the body it belongs to") {
  const Blade& b = blade();
  SUBCASE("loaded for another body") {
    const Blade other = make_blade(1.2);
    const auto bytes = *serialize_geometric_stiffness(b.geometric, b.data);
    auto r = deserialize_geometric_stiffness(bytes.data(), bytes.size(), other.data, "g.fsgeom");
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().code == ErrorCode::bad_file_format);
    CHECK(r.error().what().find("another modal body") != std::string::npos);
  }
  SUBCASE("the same body with another damping ratio is another body") {
    ModalBodyData damped = b.data;
    damped.damping_ratios.setConstant(0.05);
    const auto bytes = *serialize_geometric_stiffness(b.geometric, b.data);
    CHECK_FALSE(
        deserialize_geometric_stiffness(bytes.data(), bytes.size(), damped, "g.fsgeom").ok());
  }
  SUBCASE("saved with fewer modes than the body has") {
    auto fewer = b.geometric.truncated(3);
    REQUIRE(fewer.ok());
    auto r = serialize_geometric_stiffness(*fewer, b.data);
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().code == ErrorCode::size_mismatch);
    CHECK(r.error().what().find("3 modes for a body of 6") != std::string::npos);
  }
}

TEST_CASE("damaged or foreign geometric stiffness files get errors that say what is wrong") {
  const auto good = *serialize_geometric_stiffness(blade().geometric, blade().data);
  SUBCASE("missing file") {
    auto r = load_geometric_stiffness(output_path("no-such-file.fsgeom"), blade().data);
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().code == ErrorCode::io_error);
    CHECK(r.error().what().find("no-such-file.fsgeom") != std::string::npos);
  }
  SUBCASE("a modal body file in its place") {
    const auto modal = *serialize(blade().data);
    CHECK(error_of(modal).find("FLXGEOMS") != std::string::npos);
  }
  SUBCASE("truncated, a flipped bit, a newer format version") {
    testing::check_common_damage(good, error_of);
  }
  SUBCASE("a mode count that does not match the data") {
    auto bytes = good;
    bytes[kHeader] = 7;  // 7 modes announced, data for 6
    reseal(bytes);
    CHECK(error_of(bytes).find("7 modes need") != std::string::npos);
  }
  SUBCASE("a NaN entry names its load case") {
    auto bytes = good;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    // After the count and nine 6 x 6 matrices: the first entry of spin_xy's.
    std::memcpy(bytes.data() + kHeader + 8 + 9 * 36 * 8, &nan, 8);
    reseal(bytes);
    CHECK(error_of(bytes).find("load case spin_xy") != std::string::npos);
  }
}

TEST_CASE("random corruption never crashes the geometric stiffness loader (in-test fuzzing)") {
  const auto good = *serialize_geometric_stiffness(blade().geometric, blade().data);
  std::mt19937_64 rng(20261128);
  int rejected = 0, accepted = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    auto bytes = good;
    if (trial % 2 == 0) {  // random bytes overwritten, checksum resealed half of the time
      for (int k = 0; k < 4; ++k) bytes[rng() % bytes.size()] = static_cast<unsigned char>(rng());
      if (trial % 4 == 0) reseal(bytes);
    } else {  // random truncation
      bytes.resize(rng() % bytes.size());
    }
    auto r = deserialize_geometric_stiffness(bytes.data(), bytes.size(), blade().data, "fuzz");
    if (!r) {
      ++rejected;
      CHECK(r.error().code == ErrorCode::bad_file_format);
      continue;
    }
    ++accepted;  // a changed matrix entry, still a finite number
    for (const MatrixXd& g : r->cases) CHECK(g.allFinite());
  }
  MESSAGE(rejected << " corrupted images rejected, " << accepted << " accepted as valid");
  CHECK(rejected > 0);
}

}  // namespace test_modal_geometric_stiffness_io
