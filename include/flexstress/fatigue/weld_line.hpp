// Damage along a weld-toe line: many hot spots, one stress history each, and the critical one.
//
// A weld toe is assessed at a row of hot spots (IIW hot-spot stresses along the toe, from the
// stress layer). Each hot spot gets its own rainflow count and Miner sum; the critical location
// is the hot spot with the largest damage (the first one on ties).
//
// Batch: weld_line_damage on a (samples x hot spots) matrix, one column per hot spot.
// Streaming: StreamingWeldLine, one StreamingDamage per hot spot, allocated once at setup; a
// step pushes one stress per hot spot and never allocates.
#pragma once

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "flexstress/core/assert.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/fatigue/class_grid.hpp"
#include "flexstress/fatigue/cycle.hpp"
#include "flexstress/fatigue/damage.hpp"
#include "flexstress/fatigue/rainflow.hpp"
#include "flexstress/fatigue/streaming_damage.hpp"

namespace flexstress::fatigue {

/// The critical hot spot of a line.
template <class Scalar>
struct CriticalLocation {
  Eigen::Index index = 0;     ///< Hot spot with the largest damage (first on ties).
  Scalar damage = Scalar(0);  ///< Its damage.
};

/// Damage at every hot spot of a line and the critical one.
template <class Scalar>
struct WeldLineDamage {
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> damage;  ///< Damage per hot spot.
  CriticalLocation<Scalar> critical;
};

namespace detail {
/// Index and value of the largest entry of a damage vector (first one on ties). Written out
/// rather than maxCoeff so that the tie rule is part of the contract.
template <class Scalar, class Derived>
CriticalLocation<Scalar> find_critical(const Eigen::MatrixBase<Derived>& damage) {
  CriticalLocation<Scalar> c;
  for (Eigen::Index i = 0; i < damage.size(); ++i) {
    // Strictly greater: an equal damage further along the line does not move the location.
    if (i == 0 || damage(i) > c.damage) {
      c.index = i;
      c.damage = damage(i);
    }
  }
  return c;
}
}  // namespace detail

/// Batch damage along a line: histories(i, j) is the stress at sample i of hot spot j (each
/// column one history). Rainflow with options (gate, closure: repeating gives damage per work
/// cycle) and Miner with model at every hot spot. Errors: no hot spots, and the errors of
/// count_cycles, with the hot spot named ("hot spot 3: sample 17 is NaN").
template <class Scalar>
Result<WeldLineDamage<Scalar>> weld_line_damage(
    const Eigen::Ref<const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>>& histories,
    const DamageModel<Scalar>& model, const CountOptions<Scalar>& options = {}) {
  if (histories.cols() == 0)
    return make_error(ErrorCode::invalid_argument, "weld line has no hot spots");
  // Each hot spot is an independent history: count and sum its damage, keeping the first error.
  WeldLineDamage<Scalar> out;
  out.damage.resize(histories.cols());
  for (Eigen::Index j = 0; j < histories.cols(); ++j) {
    // Columns of a column-major matrix are contiguous.
    Result<std::vector<Cycle<Scalar>>> cycles =
        count_cycles(histories.col(j).data(), static_cast<std::size_t>(histories.rows()), options);
    if (!cycles) {
      Error e = cycles.error();
      e.message = "hot spot " + std::to_string(j) + ": " + e.message;
      return e;
    }
    out.damage(j) = miner_damage(*cycles, model);
  }
  out.critical = detail::find_critical<Scalar>(out.damage);
  return out;
}

/// Live damage meters along a line of hot spots, all on the same class grid, gate and damage
/// model (one detail category along the toe).
template <class Scalar, int NClasses>
class StreamingWeldLine {
 public:
  using Meter = StreamingDamage<Scalar, NClasses>;

  /// Errors: hot_spots < 1, and those of StreamingDamage::create.
  static Result<StreamingWeldLine> create(Eigen::Index hot_spots, const ClassGrid<Scalar>& grid,
                                          int gate_classes, const DamageModel<Scalar>& model) {
    if (hot_spots < 1)
      return make_error(ErrorCode::invalid_argument, "weld line needs at least one hot spot, got ",
                        static_cast<long long>(hot_spots));
    Result<Meter> meter = Meter::create(grid, gate_classes, model);
    if (!meter) return meter.error();
    return StreamingWeldLine(static_cast<std::size_t>(hot_spots), *meter);
  }

  /// One step: stresses[j] for hot spot j, j < hot_spots(). All or nothing: if any stress is
  /// NaN/inf (invalid_input) or outside the class window (capacity_exceeded), returns that
  /// status and nothing changes. Never allocates.
  template <class Derived>
  StepStatus push(const Eigen::DenseBase<Derived>& stresses) {
    FLEXSTRESS_ASSERT(stresses.size() == hot_spots(),
                      "StreamingWeldLine::push: one stress per hot spot expected");
    // Check every stress first, so that a refused step leaves every hot spot unchanged (all
    // meters share one grid).
    const ClassGrid<Scalar>& grid = meters_.front().counter().grid();
    for (Eigen::Index j = 0; j < stresses.size(); ++j) {
      if (!std::isfinite(stresses(j))) return StepStatus::invalid_input;
      if (!grid.contains(stresses(j))) return StepStatus::capacity_exceeded;
    }
    // All accepted: push them (each push can only succeed now).
    for (Eigen::Index j = 0; j < stresses.size(); ++j) {
      const StepStatus s = meters_[static_cast<std::size_t>(j)].push(stresses(j));
      FLEXSTRESS_ASSERT(s == StepStatus::ok, "StreamingWeldLine::push: checked sample refused");
      static_cast<void>(s);
    }
    return StepStatus::ok;
  }

  Eigen::Index hot_spots() const noexcept { return static_cast<Eigen::Index>(meters_.size()); }

  /// Meter of hot spot j.
  Meter& meter(Eigen::Index j) {
    FLEXSTRESS_ASSERT(j >= 0 && j < hot_spots(), "StreamingWeldLine::meter: index out of range");
    return meters_[static_cast<std::size_t>(j)];
  }

  /// Critical hot spot by closed damage (cheap: no residue work).
  CriticalLocation<Scalar> critical_closed() const {
    CriticalLocation<Scalar> c;
    for (std::size_t j = 0; j < meters_.size(); ++j) {
      const Scalar d = meters_[j].closed_damage();
      if (j == 0 || d > c.damage) {
        c.index = static_cast<Eigen::Index>(j);
        c.damage = d;
      }
    }
    return c;
  }

  /// Critical hot spot with each residue closed as `closure` (O(hot spots x residue), no
  /// allocation).
  CriticalLocation<Scalar> critical(CycleClosure closure) {
    CriticalLocation<Scalar> c;
    for (std::size_t j = 0; j < meters_.size(); ++j) {
      const Scalar d = meters_[j].damage(closure);
      if (j == 0 || d > c.damage) {
        c.index = static_cast<Eigen::Index>(j);
        c.damage = d;
      }
    }
    return c;
  }

  /// Forgets the histories of every hot spot.
  void reset() noexcept {
    for (Meter& m : meters_) m.reset();
  }

 private:
  // Copies of one configured meter: the only allocation, at setup.
  StreamingWeldLine(std::size_t hot_spots, const Meter& prototype)
      : meters_(hot_spots, prototype) {}

  std::vector<Meter> meters_;  // one live damage meter per hot spot, in line order
};

}  // namespace flexstress::fatigue
