// A sub-model: a refined brick model of a welded detail tied to its host body by rigid,
// massless webs (Rantalainen et al. 2013: 250 rigid beams from each end section to a master node
// on the beam axis; u_s = u_m + theta_m x (x_s - x_m)). The sub-model is solved quasi-statically
// from the masters' displacements (one-way coupling), and since it is linear, once per unit
// boundary DOF: the columns of U_b (all-DOF displacements, 6 k of them for k attachments) make
// every later read-out a small dense product, stress = S U_b u_b = H u_b.
//
// Coordinates: the sub-model mesh is given in the host body's frame (the boom's frame for the
// crane), so u_b = Phi_b p needs no rotation.
//
// Force-driven ends (not in the paper): an attachment may instead carry the host's section force
// and moment at its master (AttachmentDrive::force, with section_force_modes.hpp), the master
// then free; its 6 boundary values are that force and moment, and its columns of U_b the
// responses to unit loads. With one displacement-driven end and the others force-driven, the
// sub-model is statically determinate: its stresses no longer depend on how its stiffness
// compares with the host's (docs/accuracy-vs-time.md measures the difference on the crane).
#pragma once

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/fe/assembly.hpp"
#include "flexstress/fe/boundary_conditions.hpp"
#include "flexstress/fe/brick_locator.hpp"
#include "flexstress/fe/mesh.hpp"
#include "flexstress/fe/static_solver.hpp"
#include "flexstress/fe/stress_recovery.hpp"
#include "flexstress/stress/host_point.hpp"

namespace flexstress::stress {

/// One attachment: the master point (where the host's deformation is read) and the sub-model
/// face nodes that follow it rigidly.
struct SubModelAttachment {
  Vector3d master = Vector3d::Zero();
  std::vector<Index> face_nodes;
  AttachmentDrive drive = AttachmentDrive::displacement;
};

class SubModel {
 public:
  /// Adds the masters and rigid links to `mesh`, prescribes all six DOFs of every
  /// displacement-driven master, factorizes once and solves for each unit boundary value (a unit
  /// displacement, or a unit load on a force-driven master). Fails, naming the attachment and
  /// node, for empty or overlapping face sets, nodes that do not exist and attachments that are
  /// all force-driven; a sub-model the attachments leave free to move otherwise gets the static
  /// solver's explanation.
  FLEXSTRESS_PRECOMPUTE
  static Result<SubModel> build(fe::Mesh mesh, const std::vector<SubModelAttachment>& attachments);

  Index num_attachments() const { return static_cast<Index>(masters_.size()); }
  /// Length of the boundary vector: 6 values (displacements and rotations, or force and moment)
  /// per attachment.
  Index num_boundary_dofs() const { return 6 * num_attachments(); }
  AttachmentDrive drive(Index a) const { return drives_[static_cast<std::size_t>(a)]; }
  const fe::Mesh& mesh() const { return *mesh_; }
  const fe::AssembledModel& model() const { return *model_; }
  /// Master node of attachment a in mesh().
  Index master_node(Index a) const { return masters_[static_cast<std::size_t>(a)]; }
  /// All-DOF displacements per unit boundary value (dofs x 6 k).
  const MatrixXd& unit_displacements() const { return unit_; }
  const fe::BrickLocator& locator() const { return *locator_; }

  /// H (6 P x 6 k): Voigt stresses at the points per unit boundary DOF. Fails, naming the point,
  /// for a point outside the brick mesh.
  FLEXSTRESS_PRECOMPUTE
  Result<MatrixXd> stress_influence(const std::vector<Vector3d>& points) const;
  /// The same for any all-DOF displacement fields (columns), e.g. inertia_fields().
  FLEXSTRESS_PRECOMPUTE
  Result<MatrixXd> stress_influence(const std::vector<Vector3d>& points,
                                    const MatrixXd& fields) const;

  /// (3 P x 6 k): displacements at the points per unit boundary DOF (trilinear interpolation
  /// in the containing brick).
  FLEXSTRESS_PRECOMPUTE
  Result<MatrixXd> displacement_influence(const std::vector<Vector3d>& points) const;
  /// The same for any all-DOF displacement fields (columns).
  FLEXSTRESS_PRECOMPUTE
  Result<MatrixXd> displacement_influence(const std::vector<Vector3d>& points,
                                          const MatrixXd& fields) const;

  /// Quasi-static response to the sub-model's own inertia with the boundary held: all-DOF
  /// displacements for the body force -rho a(x), a(x) the acceleration of the material point at
  /// x (host frame), i.e. the load -M a with a sampled at the nodes (exact for the linear fields
  /// of rigid-body motion, which brick interpolation reproduces). The rigid webs are massless.
  template <class AccelerationField>
  VectorXd inertia_response(const AccelerationField& acceleration_at) const {
    const fe::DofMap& dofs = model_->dofs;
    VectorXd a = VectorXd::Zero(dofs.size());
    for (Index n = 0; n < mesh_->num_nodes(); ++n) {
      if (dofs.num_node_dofs(n) == 0) continue;
      const Vector3d an = acceleration_at(mesh_->node(n));
      for (int c = 0; c < 3; ++c) a(dofs.dof(n, c)) = an(c);
    }
    return load_response(-(model_->mass_all * a));
  }

  /// Quasi-static response to a load (all-DOF vector of forces and moments, e.g. on nodes tied
  /// to the mesh by links) with the boundary held: all-DOF displacements. With the masters held,
  /// the model need not be in equilibrium; the masters take the reactions.
  FLEXSTRESS_PRECOMPUTE
  VectorXd load_response(const VectorXd& load) const;

  /// The responses to the 12 unit inertia coordinates of a rigid host-frame motion (dofs x 12):
  /// a(x) = a_O + alpha x x + omega x (omega x x) is linear in
  /// g = [a_O (3); alpha (3); wx^2, wy^2, wz^2, wx wy, wy wz, wz wx] (see sub_model_inertia.hpp).
  FLEXSTRESS_PRECOMPUTE
  MatrixXd inertia_fields() const;

  /// Acceleration at x for unit inertia coordinate k (0-2 translation, 3-5 angular
  /// acceleration, 6-11 the products of angular velocity components; omega x (omega x x) =
  /// (omega omega^T - |omega|^2 I) x).
  static Vector3d unit_inertia_field(int k, const Vector3d& x) {
    switch (k) {
      case 0:
      case 1:
      case 2: return Vector3d::Unit(k);
      case 3:
      case 4:
      case 5: return Vector3d::Unit(k - 3).cross(x);
      case 6: return Vector3d(0, -x.y(), -x.z());  // wx^2
      case 7: return Vector3d(-x.x(), 0, -x.z());  // wy^2
      case 8: return Vector3d(-x.x(), -x.y(), 0);  // wz^2
      case 9: return Vector3d(x.y(), x.x(), 0);    // wx wy
      case 10: return Vector3d(0, x.z(), x.y());   // wy wz
      default: return Vector3d(x.z(), 0, x.x());   // wz wx
    }
  }

  /// The reference path: all-DOF displacements for boundary values u_b by a fresh solve with
  /// the factorization (what the influence matrix replaces). The blocks of force-driven
  /// attachments are loads on their masters.
  FLEXSTRESS_PRECOMPUTE
  VectorXd solve(const VectorXd& u_b) const;

  /// Reference path for stresses at points: re-solve, then recover (allocates; not per step).
  FLEXSTRESS_PRECOMPUTE
  Result<VectorXd> stresses_by_resolve(const std::vector<Vector3d>& points,
                                       const VectorXd& u_b) const;

 private:
  SubModel() = default;
  std::unique_ptr<fe::Mesh> mesh_;  // heap: the model, solver and locator point into these
  std::unique_ptr<fe::AssembledModel> model_;
  std::unique_ptr<fe::StaticSolver> solver_;
  std::unique_ptr<fe::BrickLocator> locator_;
  // Number of prescribed values: six per displacement-driven attachment.
  Index num_prescribed() const {
    return 6 * static_cast<Index>(
                   std::count(drives_.begin(), drives_.end(), AttachmentDrive::displacement));
  }

  std::vector<Index> masters_;
  std::vector<AttachmentDrive> drives_;
  MatrixXd unit_;
};

#if FLEXSTRESS_PRECOMPUTE_BODIES
template <class>
Result<SubModel> SubModel::build(fe::Mesh mesh,
                                 const std::vector<SubModelAttachment>& attachments) {
  if (attachments.empty())
    return make_error(ErrorCode::invalid_argument, "sub-model: no attachments given");
  if (mesh.hexes().empty())
    return make_error(ErrorCode::invalid_argument, "sub-model: the mesh has no bricks");
  std::vector<int> owner(static_cast<std::size_t>(mesh.num_nodes()), -1);
  for (std::size_t a = 0; a < attachments.size(); ++a) {
    const auto& att = attachments[a];
    if (att.face_nodes.empty())
      return make_error(ErrorCode::invalid_argument, "sub-model attachment ", a,
                        ": the face node set is empty");
    if (!att.master.allFinite())
      return make_error(ErrorCode::invalid_argument, "sub-model attachment ", a,
                        ": the master point is not finite");
    for (Index n : att.face_nodes) {
      if (n < 0 || n >= mesh.num_nodes())
        return make_error(ErrorCode::invalid_argument, "sub-model attachment ", a, ": face node ",
                          n, " does not exist (the mesh has ", mesh.num_nodes(), " nodes)");
      int& o = owner[static_cast<std::size_t>(n)];
      if (o >= 0)
        return make_error(
            ErrorCode::invalid_argument, "sub-model attachment ", a, ": face node ", n,
            o == static_cast<int>(a) ? " is listed twice" : " also belongs to attachment ",
            o == static_cast<int>(a) ? std::string() : std::to_string(o),
            " (face sets must not overlap)");
      o = static_cast<int>(a);
    }
  }
  if (std::none_of(attachments.begin(), attachments.end(), [](const SubModelAttachment& a) {
        return a.drive == AttachmentDrive::displacement;
      }))
    return make_error(ErrorCode::invalid_argument, "sub-model: all ", attachments.size(),
                      " attachments are force-driven; at least one must be displacement-driven "
                      "to hold the sub-model (the others' loads are reacted there)");
  SubModel s;
  fe::BoundaryConditions bc;
  for (const auto& att : attachments) {
    const Index m = mesh.add_node(att.master);
    mesh.add_rigid_link(m, att.face_nodes);
    s.masters_.push_back(m);
    s.drives_.push_back(att.drive);
    // Components 0..5 in order: the prescribed values are the displacement-driven blocks of
    // the boundary vector, in attachment order.
    if (att.drive == AttachmentDrive::displacement) bc.clamp(m);
  }
  s.mesh_ = std::make_unique<fe::Mesh>(std::move(mesh));
  auto model = fe::assemble(*s.mesh_, bc);
  if (!model) return model.error();
  s.model_ = std::make_unique<fe::AssembledModel>(std::move(*model));
  auto solver = fe::StaticSolver::factorize(*s.mesh_, *s.model_);
  if (!solver)
    return make_error(solver.error().code, "sub-model with ", attachments.size(),
                      " attachments: ", solver.error().message);
  s.solver_ = std::make_unique<fe::StaticSolver>(std::move(*solver));
  const Index nb = 6 * static_cast<Index>(attachments.size());
  const Index nd = s.model_->dofs.size();
  s.unit_ = MatrixXd::Zero(nd, nb);
  for (Index j = 0; j < nb; ++j) {
    VectorXd v = VectorXd::Zero(nb);
    v(j) = 1.0;
    s.unit_.col(j) = s.solve(v);
  }
  auto locator = fe::BrickLocator::build(*s.mesh_);
  if (!locator) return locator.error();
  s.locator_ = std::make_unique<fe::BrickLocator>(std::move(*locator));
  return s;
}

template <class>
Result<MatrixXd> SubModel::stress_influence(const std::vector<Vector3d>& points) const {
  return stress_influence(points, unit_);
}

template <class>
Result<MatrixXd> SubModel::stress_influence(const std::vector<Vector3d>& points,
                                            const MatrixXd& fields) const {
  auto s = fe::point_stress_operator(*mesh_, model_->dofs, *locator_, points);
  if (!s) return s.error();
  return MatrixXd(*s * fields);
}

template <class>
Result<MatrixXd> SubModel::displacement_influence(const std::vector<Vector3d>& points) const {
  return displacement_influence(points, unit_);
}

template <class>
Result<MatrixXd> SubModel::displacement_influence(const std::vector<Vector3d>& points,
                                                  const MatrixXd& fields) const {
  MatrixXd out = MatrixXd::Zero(3 * static_cast<Index>(points.size()), fields.cols());
  for (std::size_t i = 0; i < points.size(); ++i) {
    auto bp = locator_->locate(points[i]);
    if (!bp) return bp.error();
    const auto& h = mesh_->hexes()[static_cast<std::size_t>(bp->element)];
    const Eigen::Matrix<double, 8, 1> n = fe::hex8::shape(bp->xi);
    for (int k = 0; k < 8; ++k)
      for (int c = 0; c < 3; ++c)
        out.row(3 * static_cast<Index>(i) + c) +=
            n(k) * fields.row(model_->dofs.dof(h.nodes[static_cast<std::size_t>(k)], c));
  }
  return out;
}

template <class>
VectorXd SubModel::load_response(const VectorXd& load) const {
  return solver_->solve(load, VectorXd::Zero(num_prescribed()));
}

template <class>
MatrixXd SubModel::inertia_fields() const {
  MatrixXd out(model_->dofs.size(), 12);
  for (int k = 0; k < 12; ++k)
    out.col(k) = inertia_response([k](const Vector3d& x) { return unit_inertia_field(k, x); });
  return out;
}

template <class>
VectorXd SubModel::solve(const VectorXd& u_b) const {
  VectorXd load = VectorXd::Zero(model_->dofs.size());
  VectorXd prescribed(num_prescribed());
  Index next = 0;
  for (Index a = 0; a < num_attachments(); ++a) {
    if (drive(a) == AttachmentDrive::displacement) {
      prescribed.segment<6>(next) = u_b.segment<6>(6 * a);
      next += 6;
    } else {
      for (int c = 0; c < 6; ++c) load(model_->dofs.dof(master_node(a), c)) = u_b(6 * a + c);
    }
  }
  return solver_->solve(load, prescribed);
}

template <class>
Result<VectorXd> SubModel::stresses_by_resolve(const std::vector<Vector3d>& points,
                                               const VectorXd& u_b) const {
  const VectorXd u = solve(u_b);
  VectorXd out(6 * static_cast<Index>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) {
    auto s = fe::stress_at_point(*mesh_, model_->dofs, *locator_, u, points[i]);
    if (!s) return s.error();
    out.segment<6>(6 * static_cast<Index>(i)) = *s;
  }
  return out;
}
#endif

}  // namespace flexstress::stress

// This header's precompute entry points (core/precompute.hpp).
#define FLEXSTRESS_PRECOMPUTE_STRESS_SUB_MODEL(X)                           \
  X(10, Result<stress::SubModel>, stress::SubModel::build,                  \
    (fe::Mesh, const std::vector<stress::SubModelAttachment>&))             \
  X(10, Result<MatrixXd>, stress::SubModel::stress_influence,               \
    (const std::vector<Vector3d>&) const)                                   \
  X(10, Result<MatrixXd>, stress::SubModel::stress_influence,               \
    (const std::vector<Vector3d>&, const MatrixXd&) const)                  \
  X(10, Result<MatrixXd>, stress::SubModel::displacement_influence,         \
    (const std::vector<Vector3d>&) const)                                   \
  X(10, Result<MatrixXd>, stress::SubModel::displacement_influence,         \
    (const std::vector<Vector3d>&, const MatrixXd&) const)                  \
  X(10, MatrixXd, stress::SubModel::inertia_fields, () const)               \
  X(10, VectorXd, stress::SubModel::solve, (const VectorXd&) const)         \
  X(10, VectorXd, stress::SubModel::load_response, (const VectorXd&) const) \
  X(10, Result<VectorXd>, stress::SubModel::stresses_by_resolve,            \
    (const std::vector<Vector3d>&, const VectorXd&) const)
namespace flexstress {
FLEXSTRESS_PRECOMPUTE_EXTERN(FLEXSTRESS_PRECOMPUTE_STRESS_SUB_MODEL)
}  // namespace flexstress
