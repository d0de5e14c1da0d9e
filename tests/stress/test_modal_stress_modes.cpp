// Modal stress modes against the reference path they replace: for modal coordinates p, the
// boundary displacements Phi_b p, a fresh solve of the whole sub-model and the FE kernel's own
// nodal stress recovery (extrapolated, averaged) must give the same field at every node.
#include <cmath>

#include <doctest/doctest.h>

#include <flexstress/fe/rhs_attachment_mesh.hpp>
#include <flexstress/fe/stress_recovery.hpp>
#include <flexstress/stress/host_point.hpp>
#include <flexstress/stress/modal_stress_modes.hpp>
#include <flexstress/stress/sub_model.hpp>

#include "support/beam_fixtures.hpp"

namespace test_modal_stress_modes {

using namespace flexstress;

TEST_CASE("modal stress modes reproduce a full sub-model solve at every node") {
  constexpr int N = 6;
  // Host: a 1.2 m RHS 150x100x4 beam, Craig-Bampton with both ends as interface (6 static + 2
  // fixed-interface modes, 6 kept); the detail (density 0.6: 484 bricks) at 0.5 to 0.8 m.
  auto host = testing::make_beam_body(1.2, fe::rectangular_hollow_section(0.150, 0.100, 0.004), 12,
                                      {0.0, 1.2}, 2);
  fe::RhsAttachmentSpec rs;
  rs.density = 0.6;
  auto detail = fe::make_rhs_attachment_mesh(rs);
  REQUIRE(detail.ok());
  auto sub = stress::SubModel::build(detail->mesh, {{Vector3d(0.5, 0, 0), detail->end_section_x0},
                                                    {Vector3d(0.8, 0, 0), detail->end_section_x1}});
  REQUIRE(sub.ok());
  auto phi =
      stress::boundary_modes(host.data, {stress::HostPoint::at_node(host.line.node_at(0.5)),
                                         stress::HostPoint::at_node(host.line.node_at(0.8))});
  REQUIRE(phi.ok());
  auto modes = stress::ModalStressModes<N>::build(*sub, *phi);
  REQUIRE(modes.ok());
  CHECK(modes->num_nodes() == static_cast<Index>(detail->mesh.num_nodes()));  // spiders excluded

  // A deformation mixing all modes (amplitudes giving stresses of tens of MPa).
  Eigen::Matrix<double, N, 1> p;
  p << 2e-4, -1e-4, 1.5e-4, 5e-5, -8e-5, 1.2e-4;
  VectorXd field(6 * modes->num_nodes());
  modes->evaluate(p, field);
  const VectorXd u = sub->solve(phi->leftCols(N) * p);
  auto reference = fe::nodal_stresses(sub->mesh(), sub->model().dofs, u);
  REQUIRE(reference.ok());
  double worst = 0, scale = 0, vm_ref = 0;
  for (Index i = 0; i < modes->num_nodes(); ++i) {
    const Vec6<double> r = reference->at(modes->node(i));
    worst = std::max(worst, (field.segment<6>(6 * i) - r).cwiseAbs().maxCoeff());
    scale = std::max(scale, r.cwiseAbs().maxCoeff());
    const double a = r(0) - r(1), b = r(1) - r(2), c = r(2) - r(0);
    vm_ref = std::max(vm_ref, std::sqrt(0.5 * (a * a + b * b + c * c) +
                                        3 * (r(3) * r(3) + r(4) * r(4) + r(5) * r(5))));
  }
  MESSAGE("largest stress " << scale / 1e6 << " MPa; modal modes vs re-solve: " << worst / scale
                            << " relative");
  CHECK(scale > 1e6);  // a real load case, not a trivially zero field
  CHECK(worst <= 1e-9 * scale);
  Index where = -1;
  const double vm = modes->max_von_mises(p, &where);
  CHECK(vm == doctest::Approx(vm_ref).epsilon(1e-9));
  CHECK(where >= 0);
  // Linear in p: doubling p doubles the field.
  CHECK((modes->tensor(where, 2 * p) - 2 * modes->tensor(where, p)).norm() <= 1e-9 * scale);
}

TEST_CASE("modal stress modes refuse a host with too few modes or a mismatched boundary") {
  auto host = testing::make_beam_body(1.2, fe::rectangular_hollow_section(0.150, 0.100, 0.004), 12,
                                      {0.0}, 3);
  fe::RhsAttachmentSpec rs;
  rs.density = 0.6;
  auto detail = fe::make_rhs_attachment_mesh(rs);
  REQUIRE(detail.ok());
  auto sub = stress::SubModel::build(detail->mesh, {{Vector3d(0.5, 0, 0), detail->end_section_x0},
                                                    {Vector3d(0.8, 0, 0), detail->end_section_x1}});
  REQUIRE(sub.ok());
  auto phi =
      stress::boundary_modes(host.data, {stress::HostPoint::at_node(host.line.node_at(0.5)),
                                         stress::HostPoint::at_node(host.line.node_at(0.8))});
  REQUIRE(phi.ok());
  auto too_many = stress::ModalStressModes<8>::build(*sub, *phi);  // the host has 3 modes
  REQUIRE_FALSE(too_many.ok());
  CHECK(too_many.error().what().find("3 modes") != std::string::npos);
  auto wrong = stress::ModalStressModes<3>::build(*sub, phi->topRows(6));
  REQUIRE_FALSE(wrong.ok());
  CHECK(wrong.error().what().find("12 boundary DOFs") != std::string::npos);
}

}  // namespace test_modal_stress_modes
