// Typed handles to the parts of a Model: what the builder returns and every read-out, runtime
// change and message takes. A handle is an index into its model (no pointers, so it stays valid
// when a model is copied or a Data is made for it), typed so that a joint cannot be passed where
// a body is meant.
#pragma once

#include <cstddef>

namespace flexstress {

template <class Tag>
struct Handle {
  int index = -1;
  constexpr bool valid() const { return index >= 0; }
  friend constexpr bool operator==(Handle a, Handle b) { return a.index == b.index; }
  friend constexpr bool operator!=(Handle a, Handle b) { return a.index != b.index; }
};

struct BodyTag;
struct MarkerTag;
struct JointTag;
struct ForceTag;
struct InputTag;
struct OutputTag;
struct MeterTag;

/// A body; the ground is the body with index -1 (ModelBuilder::ground()).
using BodyId = Handle<BodyTag>;
/// A frame attached to a body, where joints and force elements act.
using MarkerId = Handle<MarkerTag>;
/// A joint or driver (its constraint equations).
using JointId = Handle<JointTag>;
/// A force element (spring-damper, ...).
using ForceId = Handle<ForceTag>;
/// A value set from outside before each step (set_input), read by a motion law.
using InputId = Handle<InputTag>;
/// One stress output (a hot spot, a gauge, a stress component) of a flexible body.
using OutputId = Handle<OutputTag>;
/// A damage meter counting one output.
using MeterId = Handle<MeterTag>;

/// The outputs of one set (ModelBuilder::add_stress_outputs), row k of its matrix being
/// output k. Converts to its first output, which is what functions that take a set's
/// OutputId (add_output_inertia) expect.
struct OutputRange {
  OutputId first;
  int count = 0;
  /// Row k's output; outside 0 .. count - 1 an invalid handle, which the builder refuses. Takes
  /// the library's wide index (stress::StressOutputs::add_hot_spot's row) without narrowing.
  constexpr OutputId operator[](std::ptrdiff_t k) const {
    return k >= 0 && k < count ? OutputId{first.index + static_cast<int>(k)} : OutputId{};
  }
  constexpr int size() const { return count; }
  constexpr operator OutputId() const { return first; }  // NOLINT: a set is its first output
};

}  // namespace flexstress
