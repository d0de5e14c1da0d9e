// Damage meter checkpoints: a meter stopped, saved, restored into a fresh meter and fed the rest
// of the history counts exactly (bit for bit) as the meter that never stopped; damaged, foreign
// and impossible checkpoints are refused and leave the meter as it was. The reference is the
// uninterrupted run itself.
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include <flexstress/fatigue/damage.hpp>
#include <flexstress/fatigue/sn_curve.hpp>
#include <flexstress/fatigue/streaming_damage.hpp>
#include <flexstress/fatigue/streaming_damage_io.hpp>

#include "fatigue/fatigue_test_helpers.hpp"

namespace test_damage_meter_checkpoint {

using namespace flexstress;
using namespace flexstress::fatigue;

constexpr int N = 64;
using Meter = StreamingDamage<double, N>;

Meter make_meter(double fat = 71.0, double upper = 200.0, int gate = 1) {
  auto curve = en1993_normal_curve(fat);
  REQUIRE(curve.ok());
  auto model = DamageModel<double>::create(*curve);
  REQUIRE(model.ok());
  auto grid = ClassGrid<double>::create(-200.0, upper, N);
  REQUIRE(grid.ok());
  auto meter = Meter::create(*grid, gate, *model);
  REQUIRE(meter.ok());
  return *meter;
}

// Everything a meter reports, compared bit for bit.
void check_same(Meter& a, Meter& b) {
  CHECK(a.closed_damage() == b.closed_damage());
  CHECK(a.damage(CycleClosure::half_cycles) == b.damage(CycleClosure::half_cycles));
  CHECK(a.damage(CycleClosure::repeating) == b.damage(CycleClosure::repeating));
  CHECK(a.counter().samples() == b.counter().samples());
  CHECK(a.counter().closed_cycles() == b.counter().closed_cycles());
  REQUIRE(a.counter().residue_size() == b.counter().residue_size());
  for (int i = 0; i < a.counter().residue_size(); ++i)
    CHECK(a.counter().residue(i) == b.counter().residue(i));
  CHECK(a.counter().has_pending() == b.counter().has_pending());
}

TEST_CASE("a restored damage meter counts on exactly as one that never stopped") {
  std::mt19937 rng(20261122);
  const auto x = test::random_walk_history<double>(rng, 50000, -200, 200, 30);
  Meter straight = make_meter();
  for (double v : x) REQUIRE(straight.push(v) == StepStatus::ok);
  REQUIRE(straight.counter().closed_cycles() > 1000);

  // Stops at several places, including before any sample and right after the first ones
  // (the filter's undecided phase).
  for (std::size_t stop : {std::size_t(0), std::size_t(1), std::size_t(2), std::size_t(777),
                           std::size_t(31415), x.size()}) {
    CAPTURE(stop);
    Meter first = make_meter();
    for (std::size_t i = 0; i < stop; ++i) REQUIRE(first.push(x[i]) == StepStatus::ok);
    const std::string path =
        std::string(FLEXSTRESS_TEST_OUTPUT_DIR) + "/meter_" + std::to_string(stop) + ".dmg";
    REQUIRE(save_damage_meter_file(path, first).ok());
    Meter resumed = make_meter();  // a fresh meter: the history comes from the file
    const Status restored = restore_damage_meter_file(path, resumed);
    REQUIRE_MESSAGE(restored.ok(), restored.error().what());
    check_same(first, resumed);
    for (std::size_t i = stop; i < x.size(); ++i) REQUIRE(resumed.push(x[i]) == StepStatus::ok);
    check_same(straight, resumed);
  }
}

// Recomputes the checksum after a deliberate edit of the data (offset 32 in the envelope).
void reseal(std::vector<unsigned char>& bytes) {
  const std::size_t header = binary::Envelope::header_size;
  const std::uint64_t h = binary::fnv1a(bytes.data() + header, bytes.size() - header);
  std::memcpy(bytes.data() + 32, &h, 8);
}

TEST_CASE("damaged, foreign or impossible damage meter checkpoints are refused") {
  std::mt19937 rng(7);
  const auto x = test::random_walk_history<double>(rng, 5000, -200, 200, 30);
  Meter saved = make_meter();
  for (double v : x) REQUIRE(saved.push(v) == StepStatus::ok);
  REQUIRE(saved.counter().residue_size() >= 4);
  const std::vector<unsigned char> good = *save_damage_meter(saved);

  // Payload offsets (streaming_damage_io.hpp): filter (4 x i32, u8), residue size (i32), residue.
  const std::size_t payload = binary::Envelope::header_size, residue = payload + 4 * 4 + 1 + 4;
  auto put_i32 = [](std::vector<unsigned char>& b, std::size_t at, std::int32_t v) {
    std::memcpy(b.data() + at, &v, 4);
  };
  auto get_i32 = [](const std::vector<unsigned char>& b, std::size_t at) {
    std::int32_t v = 0;
    std::memcpy(&v, b.data() + at, 4);
    return v;
  };
  auto error_of = [](const std::vector<unsigned char>& bytes, Meter meter) {
    const Meter before = meter;
    const Status s = restore_damage_meter(bytes.data(), bytes.size(), meter, "run.dmg");
    REQUIRE_FALSE(s.ok());
    CHECK(s.error().code == ErrorCode::bad_file_format);
    CHECK(meter.counter().samples() == before.counter().samples());  // untouched
    CHECK(meter.closed_damage() == before.closed_damage());
    return s.error().what();
  };
  auto contains = [](const std::string& text, const char* part) {
    CAPTURE(text);
    CHECK(text.find(part) != std::string::npos);
  };

  std::vector<unsigned char> flipped = good;
  flipped[flipped.size() - 3] ^= 0x20;
  contains(error_of(flipped, make_meter()), "'run.dmg': checksum mismatch");
  std::vector<unsigned char> cut(good.begin(), good.end() - 4);
  contains(error_of(cut, make_meter()), "truncated or padded");
  const std::string text = "time,stroke\n";
  contains(error_of({text.begin(), text.end()}, make_meter()),
           "not a flexstress damage meter checkpoint (the first 8 bytes are not \"FLXDMG01\")");
  // Another FAT class, another class window, another gate: another meter.
  for (const Meter& other : {make_meter(80.0), make_meter(71.0, 250.0), make_meter(71.0, 200.0, 0)})
    contains(error_of(good, other), "the checkpoint is of another damage meter");

  // Edited and resealed: the checksum passes, the history check does not.
  std::vector<unsigned char> edited = good;
  put_i32(edited, residue + 4, N + 5);
  reseal(edited);
  contains(error_of(edited, make_meter()), "residue reversal 1 is class 69, outside the 64");
  edited = good;
  put_i32(edited, residue + 4, get_i32(good, residue + 0));  // reversal 1 = reversal 0
  reseal(edited);
  contains(error_of(edited, make_meter()), "residue reversals 0 and 1 are equal");
  edited = good;
  put_i32(edited, payload + 4 * 4 + 1, 2 * N + 3);  // residue size beyond the bound
  reseal(edited);
  contains(error_of(edited, make_meter()), "a residue of 131 reversals");
  edited = good;
  const double negative = -1.0;
  std::memcpy(edited.data() + edited.size() - 16, &negative, 8);  // the closed damage
  reseal(edited);
  contains(error_of(edited, make_meter()), "closed damage -1");
}

TEST_CASE("a residue the four-point rule would have closed is refused") {
  // Classes 10, 30, 20, 25: the inner range 30-20 (10) is larger than the next one, 20-25 (5),
  // so it stays open. Classes 10, 30, 25, 40: the inner range 30-25 (5) is no larger than
  // either neighbour (20 and 15): a closed cycle the counter would have removed.
  Meter meter = make_meter();
  Meter::History h;
  h.counter.filter = {10, 30, 41, -1, true};
  h.counter.size = 4;
  h.counter.samples = 100;
  h.counter.residue = {};
  const int open_residue[] = {10, 30, 20, 25};
  const int closed_residue[] = {10, 30, 25, 40};
  for (int i = 0; i < 4; ++i) h.counter.residue[static_cast<std::size_t>(i)] = open_residue[i];
  h.counter.filter.candidate = 18;  // falling from the peak 25, more than the gate (1) below it
  CHECK(meter.restore_history(h).ok());
  for (int i = 0; i < 4; ++i) h.counter.residue[static_cast<std::size_t>(i)] = closed_residue[i];
  h.counter.filter.candidate = 33;
  const Status s = meter.restore_history(h);
  REQUIRE_FALSE(s.ok());
  CHECK(s.error().message ==
        "rainflow history: residue range 1 to 2 is a closed cycle (four-point rule)");
  // A pending reversal that does not continue the residue (rising again after the peak 25).
  for (int i = 0; i < 4; ++i) h.counter.residue[static_cast<std::size_t>(i)] = open_residue[i];
  h.counter.filter.direction = 1;
  h.counter.filter.candidate = 40;
  const Status t = meter.restore_history(h);
  REQUIRE_FALSE(t.ok());
  CHECK(t.error().message ==
        "rainflow history: pending reversal class 40 does not continue the "
        "residue");
}

}  // namespace test_damage_meter_checkpoint
