// Live damage meter of one detail: the streaming class-bin rainflow counter feeding a
// Palmgren-Miner sum, one stress sample at a time, without allocation.
//
// What it reports:
//   closed_damage()                      damage of the cycles closed so far (monotone; what a
//                                        simulator can show an operator while running);
//   damage(CycleClosure::half_cycles)    damage if the history ended now (ASTM E1049-85
//                                        section 5.4.4: the residue as half cycles);
//   damage(CycleClosure::repeating)      damage per work cycle if what was pushed is one work
//                                        cycle (ASTM E1049-85 section 5.4.5: the residue closed
//                                        with itself).
// Streaming equals batch: on the same samples, count_cycles_classed() + miner_damage() give
// the same damage for either closure, to rounding (tested). The capacity rule is that of
// StreamingRainflow (class bins, residue <= 2 NClasses - 1; samples outside the class window
// are refused with StepStatus::capacity_exceeded).
#pragma once

#include <cmath>
#include <cstddef>

#include "flexstress/core/assert.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/fatigue/class_grid.hpp"
#include "flexstress/fatigue/cycle.hpp"
#include "flexstress/fatigue/damage.hpp"
#include "flexstress/fatigue/streaming_rainflow.hpp"

namespace flexstress::fatigue {

/// Streaming rainflow + Miner damage of one stress history on NClasses class bins.
template <class Scalar, int NClasses>
class StreamingDamage {
 public:
  using Counter = StreamingRainflow<Scalar, NClasses>;

  /// Errors: those of StreamingRainflow::create (grid size, gate).
  static Result<StreamingDamage> create(const ClassGrid<Scalar>& grid, int gate_classes,
                                        const DamageModel<Scalar>& model) {
    Result<Counter> counter = Counter::create(grid, gate_classes);
    if (!counter) return counter.error();
    return StreamingDamage(*counter, model);
  }

  /// Feeds one sample. ok, or invalid_input (NaN/inf) / capacity_exceeded (outside the class
  /// window) with nothing changed. Never allocates.
  StepStatus push(Scalar x) {
    return counter_.push(x, [this](const Cycle<Scalar>& c) { closed_.add(model_.damage(c)); });
  }

  /// Feeds n samples, all or nothing: if any sample would be refused, returns its status and
  /// nothing changes; otherwise pushes them all and returns ok. Never allocates.
  StepStatus push_block(const Scalar* x, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) {
      if (!std::isfinite(x[i])) return StepStatus::invalid_input;
      if (!counter_.grid().contains(x[i])) return StepStatus::capacity_exceeded;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const StepStatus s = push(x[i]);
      FLEXSTRESS_ASSERT(s == StepStatus::ok, "StreamingDamage::push_block: checked sample refused");
      static_cast<void>(s);
    }
    return StepStatus::ok;
  }

  /// Damage of the cycles closed so far.
  Scalar closed_damage() const noexcept { return closed_.value(); }

  /// Closed damage plus the damage of the residue closed as `closure` (does not change the
  /// counter; costs O(residue), never allocates).
  Scalar damage(CycleClosure closure) const {
    KahanSum<Scalar> total = closed_;
    auto add = [this, &total](const Cycle<Scalar>& c) { total.add(model_.damage(c)); };
    if (closure == CycleClosure::repeating) {
      counter_.visit_repeating_closure(add);
    } else {
      counter_.visit_half_cycle_closure(add);
    }
    return total.value();
  }

  const Counter& counter() const noexcept { return counter_; }
  const DamageModel<Scalar>& model() const noexcept { return model_; }

  /// Forgets the history and the damage (keeps grid, gate and model).
  void reset() noexcept {
    counter_.reset();
    closed_ = KahanSum<Scalar>();
  }

  /// The counter's history and the closed damage (compensated sum): what a checkpoint saves.
  struct History {
    typename Counter::History counter;
    Scalar closed_damage = Scalar(0);
    Scalar closed_carry = Scalar(0);
  };
  History history() const noexcept {
    return History{counter_.history(), closed_.value(), closed_.carry()};
  }

  /// Continues from a saved history (checked as StreamingRainflow::restore_history does; the
  /// damage must be finite and non-negative). On error nothing changes.
  Status restore_history(const History& h) {
    using std::isfinite;
    if (!(isfinite(h.closed_damage) && h.closed_damage >= Scalar(0) && isfinite(h.closed_carry)))
      return make_error(ErrorCode::invalid_argument, "damage meter history: closed damage ",
                        h.closed_damage, " (carry ", h.closed_carry,
                        ") is not a finite non-negative number");
    if (Status s = counter_.restore_history(h.counter); !s) return s;
    closed_ = KahanSum<Scalar>::restored(h.closed_damage, h.closed_carry);
    return Status::success();
  }

 private:
  StreamingDamage(const Counter& counter, const DamageModel<Scalar>& model)
      : counter_(counter), model_(model) {}

  Counter counter_;
  DamageModel<Scalar> model_;
  KahanSum<Scalar> closed_;
};

}  // namespace flexstress::fatigue
