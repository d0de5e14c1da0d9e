// IIW hot-spot extrapolation rules (Hobbacher, IIW-2259-15 section 2.2.3; the table in the
// validation reference): the printed weights, and exactness on linear and quadratic surface
// fields, which is what the rules are built for.
#include <cmath>

#include <doctest/doctest.h>

#include <flexstress/stress/fused_stress.hpp>
#include <flexstress/stress/hot_spot.hpp>

namespace test_hot_spot {

using namespace flexstress;
using namespace flexstress::stress;

TEST_CASE("IIW rules have the published weights") {
  const double t = 0.004;
  auto a = hot_spot_rule(HotSpotRule::iiw_type_a_linear, t);
  REQUIRE(a.ok());
  CHECK(a->weights[0] == doctest::Approx(5.0 / 3.0).epsilon(1e-14));   // printed 1.67
  CHECK(a->weights[1] == doctest::Approx(-2.0 / 3.0).epsilon(1e-14));  // printed -0.67
  auto q = hot_spot_rule(HotSpotRule::iiw_type_a_quadratic, t);
  REQUIRE(q.ok());
  CHECK(q->weights[0] == doctest::Approx(2.52).epsilon(1e-13));
  CHECK(q->weights[1] == doctest::Approx(-2.24).epsilon(1e-13));
  CHECK(q->weights[2] == doctest::Approx(0.72).epsilon(1e-13));
  auto c = hot_spot_rule(HotSpotRule::iiw_type_a_coarse, t);
  REQUIRE(c.ok());
  CHECK(c->weights[0] == doctest::Approx(1.5).epsilon(1e-14));
  CHECK(c->weights[1] == doctest::Approx(-0.5).epsilon(1e-14));
  auto bf = hot_spot_rule(HotSpotRule::iiw_type_b_fine, t);
  REQUIRE(bf.ok());
  CHECK(bf->distances[0] == 0.004);
  CHECK(bf->weights[0] == doctest::Approx(3.0).epsilon(1e-13));
  CHECK(bf->weights[1] == doctest::Approx(-3.0).epsilon(1e-13));
  CHECK(bf->weights[2] == doctest::Approx(1.0).epsilon(1e-13));
  auto bc = hot_spot_rule(HotSpotRule::iiw_type_b_coarse, t);
  REQUIRE(bc.ok());
  CHECK(bc->weights[0] == doctest::Approx(1.5).epsilon(1e-14));
  CHECK(bc->weights[1] == doctest::Approx(-0.5).epsilon(1e-14));
  // The paper's own read-out points, 4 and 10 mm: 10/6 and -4/6.
  auto user = hot_spot_rule(HotSpotRule::user_points, t, {0.004, 0.010});
  REQUIRE(user.ok());
  CHECK(user->weights[0] == doctest::Approx(10.0 / 6.0).epsilon(1e-14));
}

TEST_CASE("each rule reproduces the toe value of linear (and quadratic) surface fields") {
  const double t = 0.012, s0 = 137e6;
  for (HotSpotRule r : {HotSpotRule::iiw_type_a_linear, HotSpotRule::iiw_type_a_quadratic,
                        HotSpotRule::iiw_type_a_coarse, HotSpotRule::iiw_type_b_fine,
                        HotSpotRule::iiw_type_b_coarse}) {
    CAPTURE(name(r));
    auto rule = hot_spot_rule(r, t);
    REQUIRE(rule.ok());
    auto extrapolate = [&](auto field) {
      double s = 0;
      for (std::size_t i = 0; i < rule->distances.size(); ++i)
        s += rule->weights[i] * field(rule->distances[i]);
      return s;
    };
    CHECK(extrapolate([&](double d) { return s0 - 4e9 * d; }) == doctest::Approx(s0));
    const bool quadratic = rule->distances.size() == 3;
    const double q = extrapolate([&](double d) { return s0 - 4e9 * d + 3e11 * d * d; });
    if (quadratic)
      CHECK(q == doctest::Approx(s0).epsilon(1e-12));
    else
      CHECK(std::abs(q - s0) > 1e-6 * s0);  // a two-point rule cannot see curvature
  }
}

TEST_CASE("bad hot-spot rules are refused with the reason") {
  auto no_t = hot_spot_rule(HotSpotRule::iiw_type_a_linear, 0.0);
  REQUIRE_FALSE(no_t.ok());
  CHECK(no_t.error().message.find("thickness") != std::string::npos);
  auto same = hot_spot_rule(HotSpotRule::user_points, 0.0, {0.004, 0.004});
  REQUIRE_FALSE(same.ok());
  CHECK(same.error().message.find("same distance") != std::string::npos);
  auto one = hot_spot_rule(HotSpotRule::user_points, 0.0, {0.004});
  CHECK_FALSE(one.ok());
  auto negative = hot_spot_rule(HotSpotRule::user_points, 0.0, {-0.004, 0.01});
  CHECK_FALSE(negative.ok());
  HotSpotLocation h;
  h.away = Vector3d::Zero();
  CHECK_FALSE(readout_points(h, *hot_spot_rule(HotSpotRule::iiw_type_b_fine, 0.0)).ok());
}

TEST_CASE("principal stress within 60 degrees of the toe normal") {
  // Uniaxial 100 MPa along x plus 40 MPa along y: along n = x the principal 100 is chosen.
  Vec6<double> s;
  s << 100e6, 40e6, 0, 0, 0, 0;
  CHECK(principal_near_direction<double>(s, Vector3d::UnitX(), 60 * M_PI / 180) ==
        doctest::Approx(100e6));
  // Pure shear tau: principal +tau at 45 degrees to x, -tau at -45: both within 60 degrees,
  // equal magnitude; the answer has magnitude tau.
  s << 0, 0, 0, 50e6, 0, 0;
  CHECK(std::abs(principal_near_direction<double>(s, Vector3d::UnitX(), 60 * M_PI / 180)) ==
        doctest::Approx(50e6));
  // 80 MPa across n = z only: the principal along z is zero, not the 80 MPa 90 degrees away.
  s << 0, 80e6, 0, 0, 0, 0;
  CHECK(principal_near_direction<double>(s, Vector3d::UnitZ(), 60 * M_PI / 180) ==
        doctest::Approx(0.0));
}

}  // namespace test_hot_spot
