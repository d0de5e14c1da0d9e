// Modal stress modes: the sub-model's whole nodal stress field per host mode, so that the stress
// anywhere in the detail is a linear combination sigma(x, t) = sum_i S_i(x) p_i(t) (the modal
// stress recovery of Adams Durability and Exudyn, applied to the sub-model: S_i is the stress
// field the sub-model shows when its boundary moves with host mode i).
//
// Precompute: S = N_s U Phi_b, with N_s the nodal (extrapolated and averaged) stress operator
// of the brick mesh, U the sub-model's unit boundary displacement fields and Phi_b the host's
// boundary modes (12 x N for two attachments). Per step: any node's tensor is a 6 x N block
// times p, the whole field a (6 n) x N product, the largest von Mises stress a scan. Compared
// with fused output rows (stress/fused_stress.hpp), which give only the outputs chosen in
// advance at a few nanoseconds each, modal stress modes answer questions asked later (where is
// the peak? what is the whole field at the worst instant?) at O(6 n N) per full evaluation;
// docs/performance.md has both.
#pragma once

#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Core>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/fe/stress_recovery.hpp"
#include "flexstress/stress/sub_model.hpp"

namespace flexstress::stress {

template <int NModes, class Scalar = double>
class ModalStressModes {
 public:
  using ModalVector = Eigen::Matrix<Scalar, NModes, 1>;
  using Modes = Eigen::Matrix<Scalar, Eigen::Dynamic, NModes>;

  /// S for every node of the sub-model's bricks (spider nodes excluded), from the first NModes
  /// columns of the boundary modes (6 k x >= NModes).
  FLEXSTRESS_PRECOMPUTE
  static Result<ModalStressModes> build(const SubModel& sub, const MatrixXd& boundary_modes);

  Index num_nodes() const { return static_cast<Index>(nodes_.size()); }
  /// Sub-model node of entry i.
  Index node(Index i) const { return nodes_[static_cast<std::size_t>(i)]; }
  /// (6 n) x N: rows 6 i .. 6 i + 5 are node(i)'s Voigt stress per unit modal coordinate.
  const Modes& modes() const { return modes_; }

  /// The whole nodal field, out = S p (6 n entries). Never allocates.
  template <class Out>
  void evaluate(const ModalVector& p, Out&& out) const {
    out.noalias() = modes_ * p;
  }
  /// The Voigt stress at entry i.
  Vec6<Scalar> tensor(Index i, const ModalVector& p) const {
    return modes_.template middleRows<6>(6 * i) * p;
  }
  /// The largest von Mises stress over the nodes and where (entry index); a scan without
  /// storing the field.
  Scalar max_von_mises(const ModalVector& p, Index* where = nullptr) const {
    Scalar best = Scalar(-1);
    Index at = -1;
    for (Index i = 0; i < num_nodes(); ++i) {
      const Vec6<Scalar> s = tensor(i, p);
      const Scalar a = s(0) - s(1), b = s(1) - s(2), c = s(2) - s(0);
      const Scalar vm2 = Scalar(0.5) * (a * a + b * b + c * c) +
                         Scalar(3) * (s(3) * s(3) + s(4) * s(4) + s(5) * s(5));
      if (vm2 > best) {
        best = vm2;
        at = i;
      }
    }
    if (where != nullptr) *where = at;
    return at < 0 ? Scalar(0) : std::sqrt(best);
  }

 private:
  std::vector<Index> nodes_;
  Modes modes_;
};

template <int NModes, class Scalar>
template <class>
Result<ModalStressModes<NModes, Scalar>> ModalStressModes<NModes, Scalar>::build(
    const SubModel& sub, const MatrixXd& boundary_modes) {
  if (boundary_modes.rows() != sub.num_boundary_dofs())
    return make_error(ErrorCode::size_mismatch, "modal stress modes: the sub-model has ",
                      sub.num_boundary_dofs(), " boundary DOFs, the boundary modes ",
                      boundary_modes.rows());
  if (boundary_modes.cols() < NModes)
    return make_error(ErrorCode::size_mismatch, "modal stress modes: the host body has ",
                      boundary_modes.cols(), " modes, the template asks for ", NModes);
  const fe::Mesh& mesh = sub.mesh();
  std::vector<char> in_brick(static_cast<std::size_t>(mesh.num_nodes()), 0);
  for (const fe::Hex8Element& h : mesh.hexes())
    for (Index n : h.nodes) in_brick[static_cast<std::size_t>(n)] = 1;
  ModalStressModes m;
  for (Index n = 0; n < mesh.num_nodes(); ++n)
    if (in_brick[static_cast<std::size_t>(n)]) m.nodes_.push_back(n);
  auto op = fe::nodal_stress_operator(mesh, sub.model().dofs, m.nodes_);
  if (!op) return op.error();
  const MatrixXd field_per_mode = sub.unit_displacements() * boundary_modes.leftCols(NModes);
  m.modes_ = (*op * field_per_mode).template cast<Scalar>();
  return m;
}

}  // namespace flexstress::stress
