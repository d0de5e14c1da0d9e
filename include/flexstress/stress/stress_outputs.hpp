// What a sub-model reports per step, as linear functionals of the boundary displacements u_b:
// stress tensors at read-out points, stress components along a direction (normal to a weld toe),
// IIW hot-spot stresses (weighted sums of those components at the rule's read-out points) and
// strain gauges (the strain averaged over a grid length along a direction:
// (u(x + L/2 d) - u(x - L/2 d)) . d / L, exactly the mean of eps_dd along the grid).
//
// Built once (precompute) into rows R (outputs x 6 k): output = R u_b. Non-linear measures (a
// principal stress) are computed per step from tensor outputs.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/stress/hot_spot.hpp"
#include "flexstress/stress/sub_model.hpp"

namespace flexstress::stress {

using Vector6d = Vec6<double>;

/// Voigt weights w with w . sigma = n^T sigma n (Voigt order xx, yy, zz, xy, yz, zx).
inline Vector6d normal_component_weights(const Vector3d& n) {
  Vector6d w;
  w << n.x() * n.x(), n.y() * n.y(), n.z() * n.z(), 2 * n.x() * n.y(), 2 * n.y() * n.z(),
      2 * n.z() * n.x();
  return w;
}

class StressOutputs {
 public:
  /// Six rows: the Voigt stress tensor at `point`. Returns the first row's index.
  Index add_tensor(const Vector3d& point, std::string label = {}) {
    const Index row = num_outputs();
    const Index p = add_stress_point(point);
    for (int c = 0; c < 6; ++c) {
      Term t;
      t.stress_point = p;
      t.weights = Vector6d::Unit(c);
      add_row({t}, label.empty() ? label : label + "[" + std::to_string(c) + "]");
    }
    return row;
  }

  /// One row: n^T sigma n at `point` (n normalized here).
  Index add_normal_stress(const Vector3d& point, const Vector3d& n, std::string label = {}) {
    Term t;
    t.stress_point = add_stress_point(point);
    t.weights = normal_component_weights(n.normalized());
    return add_row({t}, std::move(label));
  }

  /// One row: the hot-spot stress of the stress component along `h.away` (perpendicular to the
  /// toe line), extrapolated by the rule. Fails for a bad rule or direction.
  Result<Index> add_hot_spot(const HotSpotLocation& h, std::string label = {}) {
    auto rule = hot_spot_rule(h.rule, h.thickness, h.user_distances);
    if (!rule) return rule.error();
    auto pts = readout_points(h, *rule);
    if (!pts) return pts.error();
    std::vector<Term> terms;
    const Vector6d w = normal_component_weights(h.away.normalized());
    for (std::size_t i = 0; i < pts->size(); ++i) {
      Term t;
      t.stress_point = add_stress_point((*pts)[i]);
      t.weights = rule->weights[i] * w;
      terms.push_back(t);
    }
    return add_row(terms, std::move(label));
  }

  /// One row: a strain gauge centred at `center`, measuring along `direction` over `length`.
  Result<Index> add_strain_gauge(const Vector3d& center, const Vector3d& direction, double length,
                                 std::string label = {}) {
    if (!(length > 0.0) || !(direction.norm() > 0.0))
      return make_error(ErrorCode::invalid_argument, "strain gauge '", label, "': grid length ",
                        length, " m and direction must be non-zero");
    const Vector3d d = direction.normalized();
    Term a, b;
    a.displacement_point = add_displacement_point(center - 0.5 * length * d);
    a.weights.head<3>() = -d / length;
    b.displacement_point = add_displacement_point(center + 0.5 * length * d);
    b.weights.head<3>() = d / length;
    return add_row({a, b}, std::move(label));
  }

  Index num_outputs() const { return static_cast<Index>(rows_.size()); }
  const std::string& label(Index i) const { return labels_[static_cast<std::size_t>(i)]; }
  const std::vector<Vector3d>& stress_points() const { return stress_points_; }

  /// R (outputs x 6 k) for `sub`. Fails, naming the point, for read-out points outside the
  /// sub-model's bricks.
  FLEXSTRESS_PRECOMPUTE
  Result<MatrixXd> rows(const SubModel& sub) const;
  /// The outputs of arbitrary all-DOF displacement fields of `sub` (outputs x fields.cols()),
  /// e.g. its inertia_fields().
  FLEXSTRESS_PRECOMPUTE
  Result<MatrixXd> rows(const SubModel& sub, const MatrixXd& fields) const;

 private:
  struct Term {
    Index stress_point = -1, displacement_point = -1;
    Vector6d weights = Vector6d::Zero();
  };
  Index add_stress_point(const Vector3d& x) {
    stress_points_.push_back(x);
    return static_cast<Index>(stress_points_.size()) - 1;
  }
  Index add_displacement_point(const Vector3d& x) {
    displacement_points_.push_back(x);
    return static_cast<Index>(displacement_points_.size()) - 1;
  }
  Index add_row(std::vector<Term> terms, std::string label) {
    rows_.push_back(std::move(terms));
    labels_.push_back(std::move(label));
    return num_outputs() - 1;
  }
  std::vector<Vector3d> stress_points_, displacement_points_;
  std::vector<std::vector<Term>> rows_;
  std::vector<std::string> labels_;
};

#if FLEXSTRESS_PRECOMPUTE_BODIES
template <class>
Result<MatrixXd> StressOutputs::rows(const SubModel& sub) const {
  return rows(sub, sub.unit_displacements());
}

template <class>
Result<MatrixXd> StressOutputs::rows(const SubModel& sub, const MatrixXd& fields) const {
  auto hs = sub.stress_influence(stress_points_, fields);
  if (!hs) return make_error(hs.error().code, "stress read-out: ", hs.error().message);
  auto hu = sub.displacement_influence(displacement_points_, fields);
  if (!hu) return make_error(hu.error().code, "strain gauge end: ", hu.error().message);
  MatrixXd r = MatrixXd::Zero(num_outputs(), fields.cols());
  for (Index i = 0; i < num_outputs(); ++i)
    for (const Term& t : rows_[static_cast<std::size_t>(i)]) {
      if (t.stress_point >= 0)
        r.row(i) += t.weights.transpose() * hs->middleRows<6>(6 * t.stress_point);
      else
        r.row(i) += t.weights.head<3>().transpose() * hu->middleRows<3>(3 * t.displacement_point);
    }
  return r;
}
#endif

}  // namespace flexstress::stress

// This header's precompute entry points (core/precompute.hpp).
#define FLEXSTRESS_PRECOMPUTE_STRESS_STRESS_OUTPUTS(X)                                  \
  X(10, Result<MatrixXd>, stress::StressOutputs::rows, (const stress::SubModel&) const) \
  X(10, Result<MatrixXd>, stress::StressOutputs::rows,                                  \
    (const stress::SubModel&, const MatrixXd&) const)
namespace flexstress {
FLEXSTRESS_PRECOMPUTE_EXTERN(FLEXSTRESS_PRECOMPUTE_STRESS_STRESS_OUTPUTS)
}  // namespace flexstress
