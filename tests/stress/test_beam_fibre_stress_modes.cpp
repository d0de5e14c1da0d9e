// Fibre-stress modes of a reduced beam body (stress/beam_fibre_stress_modes.hpp) against beam
// theory and against the mesh's own element stress (fe::beam_fibre_stress), and their errors.
#include <cmath>
#include <string>

#include <doctest/doctest.h>

#include <flexstress/fe/beam3d.hpp>
#include <flexstress/fe/beam_section.hpp>
#include <flexstress/stress/beam_fibre_stress_modes.hpp>

#include "support/beam_fixtures.hpp"

namespace test_beam_fibre_stress_modes {

using namespace flexstress;

// A 1.5 m steel RHS 60 x 30 x 3 mm beam of 8 elements along x, reduced with its x = 0 node as the
// interface and every fixed-interface mode (8 nodes x 6 DOFs): with the body's rigid motions
// the modes span every displacement of its 9 nodes.
testing::BeamBody all_modes_beam() {
  return testing::make_beam_body(1.5, fe::rectangular_hollow_section(0.06, 0.03, 0.003), 8, {0.0},
                                 48);
}

/// The modal coordinates of nodal displacements u (6 per node: translation, rotation): u = R a +
/// Phi p with R the rigid motions about the body frame, solved exactly.
VectorXd modal_coordinates(const reduction::ModalBodyData& data, const VectorXd& u) {
  const Index nodes = data.num_nodes(), n = data.num_modes;
  MatrixXd basis = MatrixXd::Zero(6 * nodes, 6 + n);
  for (Index i = 0; i < nodes; ++i) {
    const Vector3d x = data.node_positions[static_cast<std::size_t>(i)];
    basis.block<3, 3>(6 * i, 0).setIdentity();
    basis.block<3, 3>(6 * i, 3) << 0, x.z(), -x.y(), -x.z(), 0, x.x(), x.y(), -x.x(), 0;  // -[x]
    basis.block<3, 3>(6 * i + 3, 3).setIdentity();
    basis.block(6 * i, 6, 3, n) = data.phi_r(i);
    basis.block(6 * i + 3, 6, 3, n) = data.phi_theta(i);
  }
  return basis.colPivHouseholderQr().solve(u).tail(n);
}

TEST_CASE("fibre stress modes: a cantilever's clamp carries P L c / I under a tip load") {
  const auto body = all_modes_beam();
  REQUIRE(body.data.num_modes == 48);
  const fe::BeamSection& section = body.mesh.section(0);
  const double e = fe::steel().youngs_modulus, l = 1.5, load = 1000.0;
  // The clamped cantilever under a tip force along y, and one along z (Euler-Bernoulli; the
  // cubic element's nodal values are exact): v = P x^2 (3 L - x) / (6 E Iz), theta_z = v';
  // w = P x^2 (3 L - x) / (6 E Iy), theta_y = -w'.
  VectorXd uy = VectorXd::Zero(6 * body.data.num_nodes()), uz = uy;
  for (Index i = 0; i < body.data.num_nodes(); ++i) {
    const double x = body.data.node_positions[static_cast<std::size_t>(i)].x();
    uy(6 * i + 1) = load * x * x * (3 * l - x) / (6 * e * section.iz);
    uy(6 * i + 5) = load * x * (2 * l - x) / (2 * e * section.iz);
    uz(6 * i + 2) = load * x * x * (3 * l - x) / (6 * e * section.iy);
    uz(6 * i + 4) = -load * x * (2 * l - x) / (2 * e * section.iy);
  }
  const VectorXd py = modal_coordinates(body.data, uy), pz = modal_coordinates(body.data, uz);
  stress::BeamFibre fibre;
  fibre.node_a = body.line.nodes[0];
  fibre.node_b = body.line.nodes[1];
  fibre.youngs_modulus = e;
  fibre.y = section.half_height_y;
  auto row = stress::beam_fibre_stress_modes(body.data, fibre, 48);
  REQUIRE_MESSAGE(row.ok(), row.error().what());
  // At the clamp M = P L; the +y fibre is compressed by a load along +y: sigma = -P L c / Iz.
  const double expected = -load * l * section.half_height_y / section.iz;
  CHECK(row->dot(py) == doctest::Approx(expected).epsilon(1e-8));
  CHECK(std::abs(row->dot(pz)) < 1e-8 * std::abs(expected));  // the y fibre of the z bending
  // Half way along the last element, L / 16 from the tip: M = P L / 16.
  fibre.node_a = body.line.nodes[7];
  fibre.node_b = body.line.nodes[8];
  fibre.xi = 0.5;
  auto mid = stress::beam_fibre_stress_modes(body.data, fibre, 48);
  REQUIRE(mid.ok());
  CHECK(mid->dot(py) == doctest::Approx(expected / 16).epsilon(1e-8));
  // Bending about y: the +z fibre at the clamp, -P L c_z / Iy.
  fibre.node_a = body.line.nodes[0];
  fibre.node_b = body.line.nodes[1];
  fibre.xi = 0.0;
  fibre.y = 0.0;
  fibre.z = section.half_width_z;
  auto rz = stress::beam_fibre_stress_modes(body.data, fibre, 48);
  REQUIRE(rz.ok());
  CHECK(rz->dot(pz) ==
        doctest::Approx(-load * l * section.half_width_z / section.iy).epsilon(1e-8));
}

TEST_CASE("fibre stress modes are the mesh element's fibre stress, mode by mode") {
  const auto body = testing::make_beam_body(1.5, fe::rectangular_hollow_section(0.06, 0.03, 0.003),
                                            8, {0.0, 1.5}, 6);
  const Index element = 3;
  const fe::BeamElement& beam = body.mesh.beams()[static_cast<std::size_t>(element)];
  stress::BeamFibre fibre;
  fibre.node_a = beam.nodes[0];
  fibre.node_b = beam.nodes[1];
  fibre.orientation = beam.orientation;
  fibre.youngs_modulus = body.mesh.material(beam.material).youngs_modulus;
  fibre.xi = 0.3;
  fibre.y = 0.02;
  fibre.z = -0.01;
  const Index modes = body.data.num_modes - 2;  // fewer than the data has
  auto row = stress::beam_fibre_stress_modes(body.data, fibre, modes);
  REQUIRE(row.ok());
  REQUIRE(row->size() == modes);
  for (Index k = 0; k < modes; ++k) {
    fe::Vector12d u;
    u << body.data.phi_r(beam.nodes[0]).col(k), body.data.phi_theta(beam.nodes[0]).col(k),
        body.data.phi_r(beam.nodes[1]).col(k), body.data.phi_theta(beam.nodes[1]).col(k);
    CHECK((*row)(k) == doctest::Approx(fe::beam_fibre_stress(body.mesh, beam, u, 0.3, 0.02, -0.01))
                           .epsilon(1e-12));
  }
}

TEST_CASE("a fibre's nodes found by position in the body data") {
  // 8 elements of 0.1875 m along x: node k at x = 0.1875 k (the line's own numbering).
  const auto body = all_modes_beam();
  for (std::size_t k = 0; k < body.line.nodes.size(); ++k) {
    const double x = body.line.positions[k];
    CHECK(body.data.nearest_node(Vector3d(x, 0, 0)) == body.line.nodes[k]);
    // Off the line and a little past the node, still nearer it than its neighbours.
    CHECK(body.data.nearest_node(Vector3d(x + 0.09, 0.05, -0.02)) == body.line.nodes[k]);
  }
  CHECK(body.data.nearest_node(Vector3d(-5, 0, 0)) == body.line.nodes.front());
  CHECK(reduction::ModalBodyData{}.nearest_node(Vector3d::Zero()) == -1);
}

TEST_CASE("fibre stress modes name what is wrong") {
  const auto body =
      testing::make_beam_body(1.0, fe::rectangular_hollow_section(0.06, 0.03, 0.003), 4, {0.0}, 4);
  const Index a = body.line.nodes[0], b = body.line.nodes[1];
  const auto message = [&](stress::BeamFibre f, Index modes = 4) {
    auto r = stress::beam_fibre_stress_modes(body.data, f, modes);
    REQUIRE_FALSE(r.ok());
    return r.error().what();
  };
  stress::BeamFibre ok;
  ok.node_a = a;
  ok.node_b = b;
  REQUIRE(stress::beam_fibre_stress_modes(body.data, ok, 4).ok());
  auto f = ok;
  f.node_b = 99;
  CHECK(message(f).find("node 99 does not exist (the body has 5 nodes)") != std::string::npos);
  f = ok;
  f.node_b = a;
  CHECK(message(f).find("coincide") != std::string::npos);
  f = ok;
  f.orientation = Vector3d(2, 0, 0);  // along the beam (x)
  CHECK(message(f).find("orientation lies along the beam") != std::string::npos);
  f = ok;
  f.youngs_modulus = 0;
  CHECK(message(f).find("Young's modulus") != std::string::npos);
  f = ok;
  f.xi = -0.1;
  CHECK(message(f).find("xi -0.1") != std::string::npos);
  CHECK(message(ok, 5).find("5 modes asked, the body data has 4") != std::string::npos);
}

}  // namespace test_beam_fibre_stress_modes
