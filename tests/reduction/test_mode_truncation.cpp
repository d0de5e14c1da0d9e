// The static flexibility a body's kept modes carry (reduction/mode_truncation.hpp). Reference:
// Euler-Bernoulli's cantilever, whose tip flexibility L^3 / (3 E I) is the sum over its modes of
// phi_k(L)^2 / omega_k^2 = 4 L^3 / (E I (beta_k L)^4): the first bending mode carries
// 12 / 1.875104^4 = 97.08 % of it (beta_1 L = 1.875104; Blevins, table 8-1).
#include <algorithm>
#include <cmath>

#include <doctest/doctest.h>

#include <flexstress/fe/beam_line.hpp>
#include <flexstress/reduction/modal_body_data.hpp>
#include <flexstress/reduction/mode_truncation.hpp>

namespace test_mode_truncation {

using namespace flexstress;
using namespace flexstress::reduction;

namespace {

struct Beam {
  ModalBodyData data;
  fe::BeamLine line;
  fe::BeamSection section;
};

/// A steel tube 1 m long (40 x 25 x 2 mm, the 40 mm side along y), `elements` elements,
/// reduced with six-DOF interface nodes at x = 0 (and at x = 1 m with `both_ends`) and `fixed`
/// fixed-interface modes; with `attached`, the frame is the root node's (the modes are then
/// the clamped beam's own).
Beam reduced_tube(int elements, bool both_ends, int fixed, bool attached) {
  Beam b;
  b.section = fe::rectangular_hollow_section(0.04, 0.025, 0.002);
  fe::Mesh mesh;
  fe::BeamLineSpec spec;
  spec.end = Vector3d(1.0, 0, 0);
  spec.num_elements = elements;
  spec.material = mesh.add_material(fe::steel());
  spec.section = mesh.add_section(b.section);
  b.line = fe::add_beam_line(mesh, spec);
  ReductionSpec rs;
  rs.interface.push_back({b.line.nodes.front()});
  if (both_ends) rs.interface.push_back({b.line.nodes.back()});
  rs.dynamic_modes.count = fixed;
  rs.interface_attached_frame = attached;
  auto data = reduce(mesh, rs);
  REQUIRE(data.ok());
  b.data = std::move(*data);
  return b;
}

}  // namespace

TEST_CASE("a cantilever's modes carry its tip flexibility L^3 / (3 E I), the first 97.08 %") {
  // Clamped at x = 0 (one interface node, the frame attached to it: the modes are the
  // cantilever's), 40 elements, 30 modes: the sum leaves out the modes above the 30th (about
  // 1e-6 of it), and the section's rotary inertia moves the modes but not the static
  // flexibility they sum to.
  const Beam b = reduced_tube(40, /*both_ends=*/false, 30, /*attached=*/true);
  const Index tip = b.line.nodes.back();
  const double e = fe::steel().youngs_modulus, length = 1.0;
  for (const int dof : {1, 2}) {  // deflection along y (bending about z: iz), along z (iy)
    const double second_moment = dof == 1 ? b.section.iz : b.section.iy;
    const double beam_theory = std::pow(length, 3) / (3 * e * second_moment);
    const double all = modal_flexibility(b.data, tip, dof, b.data.num_modes);
    // The weaker plane (z) bends first: the first y-bending mode is the body's second.
    const double first_bending = modal_flexibility(b.data, tip, dof, dof == 1 ? 2 : 1);
    MESSAGE("tip flexibility along " << (dof == 1 ? "y" : "z") << ": " << all
                                     << " m/N, beam theory " << beam_theory
                                     << "; the first bending mode's share " << first_bending / all);
    CHECK(all == doctest::Approx(beam_theory).epsilon(1e-4));
    CHECK(first_bending / all == doctest::Approx(12 / std::pow(1.875104, 4)).epsilon(1e-3));
  }
  // The clamped root moves in no mode: no interface flexibility to keep or lose.
  CHECK(kept_interface_flexibility(b.data, 1).empty());
  CHECK(std::isnan(modal_flexibility(b.data, 999, 0, 3)));
  CHECK(std::isnan(modal_flexibility(b.data, tip, 6, 3)));
  CHECK(modal_flexibility(b.data, tip, 1, 0) == 0.0);
}

TEST_CASE("a link with joints at both ends loses its joints' static shapes when it keeps fewer") {
  // The two-link arm's upper link of docs/reduction.md: interface nodes at both ends, 8
  // fixed-interface modes, 14 in all (floating frame). Keeping 10 of them gave its root bending
  // stress with the wrong sign; the shares of the interface flexibility say so before a run.
  // Kept whole, every share is 1; a share never falls as modes are added (each adds a
  // non-negative term phi_k(i)^2 / omega_k^2).
  const Beam b = reduced_tube(20, /*both_ends=*/true, 8, /*attached=*/false);
  REQUIRE(b.data.num_modes == 14);
  const auto whole = kept_interface_flexibility(b.data, 14);
  CHECK(whole.size() == 12);  // two nodes, six DOFs each
  for (const KeptFlexibility& k : whole) CHECK(k.fraction == doctest::Approx(1.0).epsilon(1e-12));
  std::vector<double> previous(whole.size(), 0.0);
  double bending_at_ten = 1.0;
  for (Index kept = 1; kept <= 14; ++kept) {
    const auto shares = kept_interface_flexibility(b.data, kept);
    REQUIRE(shares.size() == whole.size());
    for (std::size_t i = 0; i < shares.size(); ++i) {
      CHECK(shares[i].fraction >= previous[i] - 1e-12);
      previous[i] = shares[i].fraction;
      const bool bending = shares[i].dof != 0 && shares[i].dof != 3;  // not axial, not torsion
      if (kept == 10 && bending) bending_at_ten = std::min(bending_at_ten, shares[i].fraction);
    }
    if (kept == 10)
      for (const KeptFlexibility& k : shares)
        MESSAGE("10 of 14 modes: node " << k.node << " DOF " << k.dof << " keeps "
                                        << 100 * k.fraction << " %");
  }
  // docs/reduction.md asks for 99 % at the DOFs joints load; this truncation is far from it.
  CHECK(bending_at_ten < 0.99);
}

}  // namespace test_mode_truncation
