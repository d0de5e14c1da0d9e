// The hydraulic drive (dynamics/hydraulic_cylinder.hpp, added by ModelBuilder's
// add_hydraulic_cylinder) against the closed-form results of valve-controlled cylinder theory
// (Merritt, Hydraulic Control Systems, 1967, ch. 5 and 6; Watton, Fluid Power Systems, 1989,
// ch. 4): a mass on a cylinder slides along a prismatic joint, pushed by the oil and, in the
// second case, braked by a viscous damper.
#include <cmath>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include <flexstress/model/all.hpp>

namespace test_hydraulics {

using namespace flexstress;

namespace {

constexpr double kPi = 3.14159265358979323846;

// Cylinder 63/36 mm, 0.5 m stroke, 0.1 l dead volume per side; 160 bar supply; a valve passing
// 60 l/min at 35 bar per edge at full command; a 200 kg slide.
constexpr double kBore = kPi / 4 * 0.063 * 0.063, kRod = kPi / 4 * 0.036 * 0.036;
constexpr double kMass = 200.0, kBeta = 1.4e9, kDead = 1e-4, kStroke = 0.5, kRetracted = 0.2;
constexpr double kSupply = 160e5, kTank = 1e5;
const double kGain = 1e-3 / std::sqrt(35e5);

/// The slide: one rigid body on a prismatic joint along the ground's z, the cylinder and a
/// viscous damper from the ground's origin to the slide's frame.
struct Slide {
  Model<double> model;
  BodyId slide;
  ForceId cylinder;
};

// The slide at piston position x0, annulus area a2 (= bore for a double-rod cylinder), command
// u, damper c; chamber pressures p1, p2 (the cylinder's starting state).
struct Run {
  std::vector<double> t, x, v;
  double energy_residual = 0, energy_change = 0;  ///< the energy audit's max |r| and |E - E0|
};
Slide make_slide(double a2, double x0, double u, double c, double p1, double p2) {
  ModelBuilder<double> b;
  const BodyId body = b.add_rigid_body("slide", kMass, Vector3d::Zero(), Matrix3d::Identity());
  b.set_initial_pose(body, Vector3d(0, 0, kRetracted + x0));
  const MarkerId base = b.add_marker("base", b.ground(), -1, Vector3d::Zero());
  const MarkerId carriage = b.add_marker("carriage", body, -1, Vector3d::Zero());
  b.add_joint("guide", JointKind::prismatic, base, carriage);
  HydraulicParams<double> hp;
  hp.bore_area = kBore;
  hp.annulus_area = a2;
  hp.stroke = kStroke;
  hp.length_retracted = kRetracted;
  hp.dead_volume_cap = hp.dead_volume_rod = kDead;
  hp.bulk_modulus = kBeta;
  hp.supply_pressure = kSupply;
  hp.tank_pressure = kTank;
  hp.flow_gain = kGain;
  const ForceId cylinder = b.add_hydraulic_cylinder(
      "cylinder", base, carriage, hp, MotionLaw<double>::constant_acceleration(u), p1, p2);
  SpringDamperParams<double> damper;
  damper.damping = c;
  b.add_spring_damper("damper", base, carriage, damper);
  auto m = b.finalize();
  if (!m.ok()) FAIL(m.error().what());
  return {std::move(*m), body, cylinder};
}

/// The slide's travel x (from the retracted position) and velocity along the guide.
double travel(const Slide& s, const Data<double>& d) {
  return body_position(s.model, d, s.slide).z() - kRetracted;
}
double speed(const Slide& s, const Data<double>& d) {
  return body_velocity(s.model, d, s.slide).z();
}

// Initial velocity v0, step h, for `duration` seconds.
Run slide(double a2, double x0, double u, double c, double p1, double p2, double v0, double h,
          double duration) {
  const Slide s = make_slide(a2, x0, u, c, p1, p2);
  Data<double> d(s.model);
  d.settings.step = h;
  set_body_velocity(s.model, d, s.slide, Vector3d(0, 0, v0), Vector3d::Zero());
  REQUIRE(initialize(s.model, d).ok());
  EnergyBalance<double> audit;
  audit.start(s.model, d);
  Run r;
  const int steps = static_cast<int>(std::lround(duration / h));
  for (int i = 0; i < steps; ++i) {
    REQUIRE(step(s.model, d) == StepStatus::ok);
    r.t.push_back(d.t);
    r.x.push_back(travel(s, d));
    r.v.push_back(speed(s, d));
    audit.record(s.model, d);
  }
  r.energy_residual = audit.max_abs_residual();
  r.energy_change = audit.max_energy_change();
  return r;
}

}  // namespace

// Closed valve: the two oil columns are springs, k = beta (A1^2 / V1 + A2^2 / V2) (Merritt
// eq. 6-20 for a differential cylinder; Watton eq. 4.27), and the slide oscillates at
// sqrt(k / m). Pressures balanced (p1 A1 = p2 A2), a small initial velocity.
TEST_CASE("closed valve: the slide oscillates at the hydraulic natural frequency") {
  const double a2 = kBore - kRod, x0 = 0.25;
  const double v1 = kDead + kBore * x0, v2 = kDead + a2 * (kStroke - x0);
  const double k = kBeta * (kBore * kBore / v1 + a2 * a2 / v2);
  const double omega = std::sqrt(k / kMass);
  const double p1 = 50e5, p2 = p1 * kBore / a2;
  const Run r = slide(a2, x0, 0.0, 0.0, p1, p2, 1e-3, 1e-4, 0.1);
  // Period from the downward zero crossings of the velocity (linear interpolation).
  std::vector<double> crossings;
  for (std::size_t i = 1; i < r.v.size(); ++i)
    if (r.v[i - 1] > 0 && r.v[i] <= 0)
      crossings.push_back(r.t[i - 1] + (r.t[i] - r.t[i - 1]) * r.v[i - 1] / (r.v[i - 1] - r.v[i]));
  REQUIRE(crossings.size() >= 4);
  const double period = (crossings.back() - crossings.front()) / double(crossings.size() - 1);
  const double measured = 2 * kPi / period;
  MESSAGE("hydraulic natural frequency " << measured / (2 * kPi) << " Hz, closed form "
                                         << omega / (2 * kPi) << " Hz");
  CHECK(measured == doctest::Approx(omega).epsilon(1e-3));
  // Amplitude v0 / omega: the oil spring neither gains nor (at rho = 0.8, h omega = 0.036)
  // visibly loses energy.
  double x_max = 0;
  for (double x : r.x) x_max = std::max(x_max, std::abs(x - x0));
  CHECK(x_max == doctest::Approx(1e-3 / omega).epsilon(1e-2));
}

// Open valve against a viscous load F = c v on a double-rod (symmetric) cylinder: in the steady
// state p1 + p2 = ps + pt and each valve edge passes Q = A v, so with the load pressure
// pL = p1 - p2 = c v / A, Q = K u sqrt((ps - pt - pL) / 2) (Merritt eq. 5-45 for a matched,
// symmetric valve). Solved for v: A^2 v^2 = (K u)^2 (ps - pt - c v / A) / 2, a quadratic.
TEST_CASE("open valve: the slide reaches the load-flow velocity of the valve") {
  const double a = kBore, u = 0.1, c = 8e4;
  const double g = (kGain * u) * (kGain * u) / 2;  // A^2 v^2 + g c v / A - g (ps - pt) = 0
  const double qa = a * a, qb = g * c / a, qc = -g * (kSupply - kTank);
  const double v_expected = (-qb + std::sqrt(qb * qb - 4 * qa * qc)) / (2 * qa);
  const double p_mid = 0.5 * (kSupply + kTank);
  const Run r = slide(a, 0.1, u, c, p_mid, p_mid, 0.0, 1e-3, 1.0);
  const double v_end = r.v.back();
  MESSAGE("steady velocity " << v_end << " m/s, closed form " << v_expected << " m/s");
  // The orifice's laminar regularization below 0.1 bar changes the flow at the 73 bar drop by
  // sqrt(73 / 73.1) - 1 = -0.07 %.
  CHECK(v_end == doctest::Approx(v_expected).epsilon(2e-3));
  CHECK(v_expected > 0.03);  // a real motion: about 4 cm/s
  // It started from rest and got there: moving, not stuck at the initial pressures.
  CHECK(r.x.back() > 0.1 + 0.5 * v_expected);
}

// The energy audit counts the oil force's work: with a closed valve and no damper, the slide's
// kinetic energy is exchanged with the oil springs and W follows it.
TEST_CASE("energy audit of a hydraulic model: the oil force's work balances the motion") {
  const double a2 = kBore - kRod, p1 = 50e5, p2 = p1 * kBore / a2;
  const Run r = slide(a2, 0.25, 0.0, 0.0, p1, p2, 0.05, 1e-4, 0.05);
  MESSAGE("max |r| " << r.energy_residual << " J of max |E - E0| " << r.energy_change << " J");
  CHECK(r.energy_change > 0.2);  // 1/2 m v0^2 = 0.25 J goes into the oil and back
  CHECK(r.energy_residual < 1e-3 * r.energy_change);
}

// Bad parameters are reported, naming the element and the parameter, instead of dividing by a
// zero chamber volume inside the step: the runtime model checks them in finalize() (the
// compile-time scene did in initialize()).
TEST_CASE("a hydraulic cylinder with bad parameters is refused at initialize") {
  const auto build = [](double dead_volume_rod) {
    ModelBuilder<double> b;
    const BodyId body = b.add_rigid_body("slide", kMass, Vector3d::Zero(), Matrix3d::Identity());
    b.set_initial_pose(body, Vector3d(0, 0, 0.3));
    const MarkerId base = b.add_marker("base", b.ground(), -1, Vector3d::Zero());
    const MarkerId carriage = b.add_marker("carriage", body, -1, Vector3d::Zero());
    b.add_joint("guide", JointKind::prismatic, base, carriage);
    HydraulicParams<double> hp;
    hp.bore_area = hp.annulus_area = kBore;
    hp.stroke = kStroke;
    hp.dead_volume_cap = kDead;
    hp.dead_volume_rod = dead_volume_rod;
    hp.supply_pressure = kSupply;
    b.add_hydraulic_cylinder("cylinder", base, carriage, hp,
                             MotionLaw<double>::constant_acceleration(0.0), 0.0, 0.0);
    return b.finalize();
  };
  const auto refused = build(0.0);  // the rod side's dead volume is left at 0
  REQUIRE_FALSE(refused.ok());
  MESSAGE(refused.error().what());
  // The runtime model names the element ("force element 0" on the compile-time scene).
  CHECK(refused.error().what().find("force 'cylinder'") != std::string::npos);
  CHECK(refused.error().what().find("dead volume") != std::string::npos);
  const auto fixed = build(kDead);  // fixed: it starts
  REQUIRE(fixed.ok());
  Data<double> d(*fixed);
  CHECK(initialize(*fixed, d).ok());
}

// Checkpoints carry the chamber pressures (force-element states) with the rest: a run stopped
// mid-stroke and restored ends bit-identical to one that never stopped.
TEST_CASE("checkpoint of a hydraulic model restores the chamber pressures bit-identically") {
  const Slide s = make_slide(kBore - kRod, 0.2, 0.3, 2000.0, 50e5, 50e5 * kBore / (kBore - kRod));
  Data<double> a(s.model);
  a.settings.step = 1e-4;
  REQUIRE(initialize(s.model, a).ok());
  std::vector<unsigned char> bytes;
  for (int i = 0; i < 600; ++i) {
    if (i == 200) bytes = *save_checkpoint(s.model, a);
    REQUIRE(step(s.model, a) == StepStatus::ok);
  }
  Data<double> b(s.model);
  REQUIRE(restore_checkpoint(s.model, b, bytes.data(), bytes.size()).ok());
  for (int i = 200; i < 600; ++i) REQUIRE(step(s.model, b) == StepStatus::ok);
  // (No read-out gives a force element's state by handle: Data::force_states, by ForceId.)
  const auto& pa = a.force_states[static_cast<std::size_t>(s.cylinder.index)];
  const auto& pb = b.force_states[static_cast<std::size_t>(s.cylinder.index)];
  MESSAGE("after 60 ms: x = " << travel(s, a) << " m, p1 = " << pa.p1 * 1e-5
                              << " bar, p2 = " << pa.p2 * 1e-5 << " bar");
  CHECK(travel(s, a) > 0.2);  // the open valve moved it
  CHECK(pb.p1 == pa.p1);
  CHECK(pb.p2 == pa.p2);
  CHECK(body_position(s.model, b, s.slide) == body_position(s.model, a, s.slide));
  CHECK(b.v == a.v);
  CHECK(b.lambda == a.lambda);
}

}  // namespace test_hydraulics
