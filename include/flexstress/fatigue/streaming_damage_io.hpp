// Checkpoint and restore of a live damage meter (StreamingDamage): the rainflow residue, the
// reversal filter's pending state, the counts and the compensated damage sum, so that a fatigue
// campaign split across jobs (with the model's checkpoint, model/checkpoint.hpp) counts
// exactly as one that never stopped.
//
// Format, version 1 (host byte order, which must be little-endian; checked), in the envelope of
// core/binary_io.hpp with magic "FLXDMG01" and as signature a hash of the meter's configuration:
// the Scalar size, class count, class window, gate, and the damage the meter's model gives a
// fixed set of probe cycles (so another S-N curve, FAT class, partial factor or mean-stress
// correction is another meter).
//   payload: i32 filter low, high, candidate, direction; u8 filter started; i32 residue size n;
//            i32 residue classes (n); u64 samples; u64 closed cycles; Scalar closed damage;
//            Scalar closed carry.
// The loader checks the envelope, then that the history is one the meter could have reached
// (StreamingRainflow::restore_history); on any error the meter is unchanged.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "flexstress/core/binary_io.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/fatigue/cycle.hpp"
#include "flexstress/fatigue/streaming_damage.hpp"

namespace flexstress::fatigue {

namespace damage_io_detail {

inline constexpr binary::Envelope kEnvelope{"FLXDMG01", 1, "damage meter checkpoint"};

}  // namespace damage_io_detail

/// The configuration signature of a damage meter (see the file comment).
template <class Scalar, int NClasses>
std::uint64_t damage_meter_signature(const StreamingDamage<Scalar, NClasses>& meter) {
  binary::Writer w;
  const auto& grid = meter.counter().grid();
  w.put(std::int64_t{sizeof(Scalar)});
  w.put(std::int64_t{NClasses});
  w.put(grid.lower());
  w.put(grid.upper());
  w.put(std::int64_t{meter.counter().gate_classes()});
  // Probe cycles (from, to) in MPa: ranges across a wide band, tensile and compressive means.
  const Scalar probes[][2] = {{0, 10},    {0, 40},     {0, 100},   {-50, 150},
                              {100, 400}, {-300, -20}, {200, 260}, {-1000, 1000}};
  for (const auto& p : probes) w.put(meter.model().damage(Cycle<Scalar>{p[0], p[1], Scalar(1)}));
  return binary::fnv1a(w.buffer.data(), w.buffer.size());
}

/// The meter's history as checkpoint bytes (allocates: not for the step path).
template <class Scalar, int NClasses>
Result<std::vector<unsigned char>> save_damage_meter(const StreamingDamage<Scalar, NClasses>& m) {
  if (!binary::little_endian_host())
    return make_error(ErrorCode::invalid_argument,
                      "damage meter checkpoint: this host is big-endian; the format is "
                      "little-endian only");
  const auto h = m.history();
  const auto& f = h.counter.filter;
  binary::Writer w;
  for (std::int32_t v : {f.low, f.high, f.candidate, f.direction}) w.put(v);
  w.put(static_cast<std::uint8_t>(f.started ? 1 : 0));
  w.put(static_cast<std::int32_t>(h.counter.size));
  for (int i = 0; i < h.counter.size; ++i)
    w.put(static_cast<std::int32_t>(h.counter.residue[static_cast<std::size_t>(i)]));
  w.put(h.counter.samples);
  w.put(h.counter.closed_cycles);
  w.put(h.closed_damage);
  w.put(h.closed_carry);
  return damage_io_detail::kEnvelope.seal(damage_meter_signature(m), w.buffer);
}

/// Restores a damage meter checkpoint into `meter`, which must be configured as the saved one.
/// `name` appears in the messages. On error the meter is unchanged.
template <class Scalar, int NClasses>
Status restore_damage_meter(const unsigned char* data, std::size_t size,
                            StreamingDamage<Scalar, NClasses>& meter,
                            const std::string& name = "damage meter checkpoint") {
  auto opened = damage_io_detail::kEnvelope.open(
      data, size, damage_meter_signature(meter), name,
      "the checkpoint is of another damage meter (class grid, gate, S-N curve or damage "
      "options differ from this meter's)");
  if (!opened) return opened.error();
  binary::Reader& r = *opened;
  auto bad = [&](const auto&... parts) {
    return make_error(ErrorCode::bad_file_format, "'", name, "': ", parts...);
  };
  typename StreamingDamage<Scalar, NClasses>::History h;
  auto& f = h.counter.filter;
  std::int32_t low = 0, high = 0, candidate = 0, direction = 0, n = 0;
  std::uint8_t started = 0;
  bool ok = r.get(low) && r.get(high) && r.get(candidate) && r.get(direction) && r.get(started) &&
            r.get(n);
  if (ok && (n < 0 || n >= StreamingRainflow<Scalar, NClasses>::residue_capacity))
    return bad("a residue of ", n, " reversals (", NClasses, " classes allow at most ",
               2 * NClasses - 1, ")");
  for (std::int32_t i = 0; ok && i < n; ++i) {
    std::int32_t c = 0;
    ok = r.get(c);
    h.counter.residue[static_cast<std::size_t>(i)] = c;
  }
  ok = ok && r.get(h.counter.samples) && r.get(h.counter.closed_cycles) && r.get(h.closed_damage) &&
       r.get(h.closed_carry);
  if (!ok || r.remaining() != 0)
    return bad("the data does not match the layout (", ok ? "bytes left over" : "it ends early",
               ")");
  if (started > 1) return bad("the filter's started flag is ", int(started), ", not 0 or 1");
  f.low = low;
  f.high = high;
  f.candidate = candidate;
  f.direction = direction;
  f.started = started == 1;
  h.counter.size = n;
  if (Status s = meter.restore_history(h); !s) return bad(s.error().message);
  return Status::success();
}

/// Writes a damage meter checkpoint file.
template <class Scalar, int NClasses>
Status save_damage_meter_file(const std::string& path,
                              const StreamingDamage<Scalar, NClasses>& meter) {
  auto bytes = save_damage_meter(meter);
  if (!bytes) return bytes.error();
  return binary::write_file(path, *bytes);
}

/// Reads a damage meter checkpoint file into `meter`.
template <class Scalar, int NClasses>
Status restore_damage_meter_file(const std::string& path,
                                 StreamingDamage<Scalar, NClasses>& meter) {
  auto bytes = binary::read_file(path);
  if (!bytes) return bytes.error();
  return restore_damage_meter(bytes->data(), bytes->size(), meter, path);
}

}  // namespace flexstress::fatigue
