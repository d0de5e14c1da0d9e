// What the model builder does to a body before the model owns it, for a body of any mode count
// behind a type-erased holder (BodyHolder<Scalar, N>): add a marker, set its geometric
// stiffness, copy it with a damping ratio, ask whether it damps. One table of functions per
// mode count; the builder picks the table of the kernels the body runs.
#pragma once

#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/model/body_kernels.hpp"
#include "flexstress/reduction/modal_geometric_stiffness_data.hpp"

namespace flexstress::detail {

template <class Scalar>
struct BodyHolderOps {
  /// Adds a marker at `node` (-1: the body frame); its index on the body, or -1 (no such node).
  int (*add_marker)(void*, Index node, const Vec3<Scalar>& offset,
                    const Mat3<Scalar>& axes) = nullptr;
  Status (*set_geometric)(void*, const reduction::ModalGeometricStiffness&) = nullptr;
  /// Copies the holder with damping ratio zeta (if set) and reads its mode data.
  std::shared_ptr<const void> (*clone)(const void*, const std::optional<Scalar>& zeta,
                                       std::vector<Scalar>& displacement_scale,
                                       Scalar& max_frequency, int& modes) = nullptr;
  /// Whether the body damps its modes with damping ratio zeta (if set).
  bool (*damps)(const void*, const std::optional<Scalar>& zeta) = nullptr;
};

template <class Scalar, int N>
std::shared_ptr<const void> clone_body_holder(const void* h, const std::optional<Scalar>& zeta,
                                              std::vector<Scalar>& scale, Scalar& max_frequency,
                                              int& modes) {
  auto copy =
      std::make_shared<BodyHolder<Scalar, N>>(*static_cast<const BodyHolder<Scalar, N>*>(h));
  if (zeta) copy->body.set_damping_ratio(*zeta);
  modes = copy->body.modes();
  const auto& s = copy->body.modal_displacement_scale();
  scale.assign(s.data(), s.data() + s.size());
  max_frequency = copy->body.max_frequency();
  return copy;
}

template <class Scalar, int N>
bool body_holder_damps(const void* h, const std::optional<Scalar>& zeta) {
  if (zeta) return *zeta != Scalar(0);
  return !static_cast<const BodyHolder<Scalar, N>*>(h)->body.modal_damping().isZero(0);
}

template <class Scalar, int N>
BodyHolderOps<Scalar> body_holder_ops() {
  BodyHolderOps<Scalar> ops;
  ops.add_marker = &BodyKernelImpl<Scalar, N>::add_marker;
  ops.set_geometric = &BodyKernelImpl<Scalar, N>::set_geometric_stiffness;
  ops.clone = &clone_body_holder<Scalar, N>;
  ops.damps = &body_holder_damps<Scalar, N>;
  return ops;
}

/// The table for kernels of `fixed_modes` (BodyKernels::fixed_modes: 0 rigid, Eigen::Dynamic
/// bounded, else one of the compiled counts Ns).
template <class Scalar, int... Ns>
BodyHolderOps<Scalar> body_holder_ops_for(int fixed_modes, std::integer_sequence<int, Ns...>) {
  if (fixed_modes == 0) return body_holder_ops<Scalar, 0>();
  BodyHolderOps<Scalar> ops;
  bool done = false;
  ((!done && fixed_modes == Ns ? (ops = body_holder_ops<Scalar, Ns>(), done = true) : false), ...);
  return done ? ops : body_holder_ops<Scalar, Eigen::Dynamic>();
}

}  // namespace flexstress::detail
