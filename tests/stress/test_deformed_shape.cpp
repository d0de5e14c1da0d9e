// The deformed shape at points of the user's choice. References: the FFRF kinematics
// x = R + A (x0 + Phi p) (a rigid motion moves the points rigidly; at a node the shape is the
// node's mode shape), small-rotation kinematics for an offset point, and the body's own nodal
// mode shapes on a fine beam for points hosted between the nodes of a coarser line (cubic Hermite
// interpolation converges much faster than linear, as beam theory says it must).
#include <cmath>
#include <vector>

#include <doctest/doctest.h>

#include <flexstress/core/euler_parameters.hpp>
#include <flexstress/core/skew.hpp>
#include <flexstress/fe/beam_section.hpp>
#include <flexstress/stress/deformed_shape.hpp>

#include "support/beam_fixtures.hpp"

namespace test_deformed_shape {

using namespace flexstress;
using namespace flexstress::stress;

constexpr int N = 4;

// A 1.2 m RHS cantilever clamped at x = 0, 48 elements (the fine reference line).
const testing::BeamBody& cantilever() {
  static const testing::BeamBody body = testing::make_beam_body(
      1.2, fe::rectangular_hollow_section(0.150, 0.100, 0.004), 48, {0.0}, N);
  return body;
}

TEST_CASE("a rigid motion moves the points rigidly; at a node the shape is the node's") {
  const auto& beam = cantilever();
  const Index node = beam.line.nodes[30];
  auto shape =
      DeformedShape<N>::build(beam.data, {{HostPoint::at_node(node), Vector3d::Zero()},
                                          {HostPoint::at_node(node), Vector3d(0, 0.05, 0.02)}});
  REQUIRE(shape.ok());
  // At the node: the node's own translational mode shapes.
  CHECK((shape->modes().topRows<3>() - beam.data.phi_r(node).leftCols(N)).norm() == 0.0);
  // Offset rigidly: u = Phi_u p + (Phi_theta p) x offset.
  const Vec<double, N> p(2e-3, -1e-3, 5e-4, 3e-4);
  const Vector3d offset(0, 0.05, 0.02);
  const Vector3d expected = beam.data.phi_r(node).leftCols(N) * p +
                            (beam.data.phi_theta(node).leftCols(N) * p).cross(offset);
  CHECK((shape->modes().middleRows<3>(3) * p - expected).norm() < 1e-15);
  // p = 0: x = R + A x0 exactly.
  const Vector3d r(0.5, -1.0, 2.0);
  const Vec4<double> theta = Vec4<double>(0.9, 0.1, -0.3, 0.2).normalized();
  Eigen::Matrix3Xd out(3, 2);
  shape->evaluate(r, theta, Vec<double, N>::Zero(), out);
  const Matrix3d a = rotation_matrix<double>(theta);
  for (Index i = 0; i < 2; ++i) CHECK((out.col(i) - (r + a * shape->rest().col(i))).norm() < 1e-15);
}

TEST_CASE("between nodes, Hermite interpolation on a coarse line converges to the fine shape") {
  // Points on the fine beam's nodes, hosted on a line that uses every 4th or every 8th node
  // only: their shapes, interpolated between the coarse line's nodes, against the fine nodes'
  // own mode shapes. Cubic Hermite error falls as h^4 (16x per halving of h), linear as h^2.
  const auto& beam = cantilever();
  std::vector<Vector3d> positions;
  std::vector<Index> fine_nodes;
  for (std::size_t k = 1; k < beam.line.nodes.size(); k += 2) {
    fine_nodes.push_back(beam.line.nodes[k]);
    positions.push_back(beam.data.node_positions[static_cast<std::size_t>(beam.line.nodes[k])]);
  }
  auto error = [&](int stride, BoundaryInterpolation kind) {
    std::vector<Index> coarse;
    for (std::size_t k = 0; k < beam.line.nodes.size(); k += static_cast<std::size_t>(stride))
      coarse.push_back(beam.line.nodes[k]);
    auto shape = DeformedShape<N>::along_beam(beam.data, coarse, positions, kind);
    REQUIRE(shape.ok());
    double worst = 0.0, scale = 0.0;
    for (std::size_t i = 0; i < fine_nodes.size(); ++i) {
      const auto exact = beam.data.phi_r(fine_nodes[i]).leftCols(N);
      worst = std::max(
          worst,
          (shape->modes().middleRows<3>(3 * static_cast<Index>(i)) - exact).cwiseAbs().maxCoeff());
      scale = std::max(scale, exact.cwiseAbs().maxCoeff());
    }
    return worst / scale;
  };
  const double hermite8 = error(8, BoundaryInterpolation::hermite);
  const double hermite4 = error(4, BoundaryInterpolation::hermite);
  const double linear4 = error(4, BoundaryInterpolation::linear);
  MESSAGE("relative shape error: Hermite, 8 elements per span ", hermite8, ", 4: ", hermite4,
          "; linear, 4: ", linear4);
  CHECK(hermite4 < 1e-3);
  CHECK(hermite4 < linear4 / 10);
  CHECK(hermite8 / hermite4 > 8.0);  // fourth order: 16 in the limit
}

TEST_CASE("deformed shape: bad input is refused naming it") {
  const auto& beam = cantilever();
  auto few = DeformedShape<N + 30>::build(beam.data, {});
  REQUIRE_FALSE(few.ok());
  CHECK(few.error().message ==
        "deformed shape: the body has 4 modes, the shape was compiled for 34");
  auto missing = DeformedShape<N>::build(beam.data, {{HostPoint::at_node(999), Vector3d::Zero()}});
  REQUIRE_FALSE(missing.ok());
  CHECK(missing.error().message.find("host node 999 does not exist") != std::string::npos);
  auto nan =
      DeformedShape<N>::along_beam(beam.data, beam.line.nodes, {Vector3d(0.1, std::nan(""), 0)});
  REQUIRE_FALSE(nan.ok());
  CHECK(nan.error().message == "deformed shape: vertex 0 has a non-finite position");
  auto short_line = DeformedShape<N>::along_beam(beam.data, {beam.line.nodes[0]}, {});
  REQUIRE_FALSE(short_line.ok());
  CHECK(short_line.error().message ==
        "deformed shape: a beam line needs at least two nodes, got 1");
}

}  // namespace test_deformed_shape
