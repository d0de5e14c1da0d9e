// Geometric stiffening (ModelBuilder::add_geometric_stiffening) on the spin-up beam of Kane, Ryan &
// Banerjee, J. Guidance 10 (1987) (data and model: examples/spin_up_beam/spin_up_model.hpp).
// References:
// * Southwell coefficient of the first bending mode of a uniform cantilever on a zero-radius
//   hub, K1 = 1.193 (rotor dynamics literature, e.g. Bielawa, Rotary Wing Structural Dynamics
//   and Aeroelasticity, 2nd ed. 2006): the Rayleigh quotient int T phi'^2 / int m phi^2 of the
//   non-rotating mode under the centrifugal tension T = m Omega^2 (L^2 - x^2) / 2 (recomputed
//   from that definition with the exact mode shape: 1.19334). Spinning at Omega, in-plane
//   bending has omega^2 = omega0^2 + (K1 - 1) Omega^2 (the -Omega^2 is the centrifugal
//   softening that the FFRF's quadratic velocity terms carry); a Rayleigh estimate, within a
//   fraction of a percent at these speeds.
// * Axial stretch at steady spin: EA u'' = -rho A Omega^2 x gives u(L) = rho A Omega^2 L^3 /
//   (3 EA); one axial mode (sin(pi x / 2L)) captures 96 / pi^4 = 98.55 % of it.
// * The linear model in the hub-attached frame: the in-plane mode's stiffness omega0^2 - Omega^2
//   turns negative once the spin passes omega0 = 3.80 rad/s and the deflection grows
//   exponentially (Kane et al.'s "conventional" model).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include <flexstress/model/all.hpp>

#include "../../examples/spin_up_beam/spin_up_model.hpp"

namespace test_geometric_stiffening {

using namespace flexstress;

namespace {

constexpr int kModes = 10;
constexpr double kSouthwell = 1.19334;
constexpr double kPi = 3.14159265358979323846;

constexpr bool kLinear = false, kStiffened = true;

const spin_up::Beam& beam(spin_up::Frame frame) {
  auto make = [](spin_up::Frame f) {
    auto r = spin_up::make_beam(spin_up::Spec{}, kModes, f);
    REQUIRE(r.ok());
    return std::move(*r);
  };
  static const spin_up::Beam attached = make(spin_up::Frame::attached);
  static const spin_up::Beam floating = make(spin_up::Frame::floating);
  return frame == spin_up::Frame::attached ? attached : floating;
}

struct Run {
  std::vector<double> t, tip_y, tip_x, p0;
  StepStatus status = StepStatus::ok;
  double failed_at = -1;
  double max_tip(double t0, double t1) const {
    double m = 0;
    for (std::size_t i = 0; i < t.size(); ++i)
      if (t[i] >= t0 && t[i] <= t1) m = std::max(m, std::abs(tip_y[i]));
    return m;
  }
};

// Simulates to t_end from the hub's initial rate. Tip deflection relative to the hub's
// tangent frame (the hub node's own deformation removed, which is zero in the attached frame).
// The hub law reads `spec`, which outlives the run.
Run simulate(bool stiffening, spin_up::Frame frame, const spin_up::Spec& spec, double t_end,
             double h, double initial_rate = 0, double mode0_velocity = 0) {
  const spin_up::Beam& b = beam(frame);
  auto built = spin_up::make_model(b, spec, stiffening, kModes);
  REQUIRE_MESSAGE(built.ok(), built.error().what());
  const spin_up::SpinUp& m = *built;
  // A hard case for index-3 integration: the beam spins about its intermediate principal axis
  // (J_xx < J_zz < J_yy with the stiff out-of-plane section), and the velocity component
  // normal to the constraints, which index 3 leaves to itself, is amplified by w x J w until
  // Newton fails (at t = 3 s at 6 rad/s). Projecting the velocities removes it every step
  // (spin_up::make_model switches it on).
  REQUIRE(m.model.settings().project_velocities);
  Data<double> d(m.model);
  set_step_size(d, h);
  set_body_velocity(m.model, d, m.beam, Vector3d::Zero(), Vector3d(0, 0, initial_rate));
  Eigen::VectorXd p = Eigen::VectorXd::Zero(kModes), p_dot = Eigen::VectorXd::Zero(kModes);
  p_dot(0) = mode0_velocity;
  REQUIRE(set_modal_state(m.model, d, m.beam, p, p_dot).ok());
  const Status init = initialize(m.model, d);
  if (!init) MESSAGE(init.error().what());
  REQUIRE(init.ok());
  const double length = spec.length;  // the beam line's end: the undeformed tip
  Run run;
  const long steps = std::lround(t_end / h);
  for (long k = 0; k < steps; ++k) {
    const StepStatus st = step(m.model, d);
    if (st != StepStatus::ok) {
      run.status = st;
      run.failed_at = d.t;
      break;
    }
    const spin_up::TipDeflection tip = spin_up::tip_deflection(m, d, length);
    run.t.push_back(d.t);
    run.tip_y.push_back(tip.in_plane);
    run.tip_x.push_back(tip.axial);
    run.p0.push_back(modal_coordinates(m.model, d, m.beam)(0));
  }
  return run;
}

// Angular frequency of a signal from its upward zero crossings about its mean.
double crossing_frequency(const std::vector<double>& t, const std::vector<double>& y) {
  double mean = 0;
  for (double v : y) mean += v;
  mean /= static_cast<double>(y.size());
  std::vector<double> up;
  for (std::size_t i = 1; i < t.size(); ++i) {
    const double a = y[i - 1] - mean, b = y[i] - mean;
    if (a < 0 && b >= 0) up.push_back(t[i - 1] + (t[i] - t[i - 1]) * (-a) / (b - a));
  }
  REQUIRE(up.size() >= 3);
  return 2 * kPi * static_cast<double>(up.size() - 1) / (up.back() - up.front());
}

}  // namespace

TEST_CASE("modal geometric stiffness of the cantilever modes: Southwell coefficient") {
  const auto& b = beam(spin_up::Frame::attached);
  const spin_up::Spec spec;
  const double w0 =
      1.87510407 * 1.87510407 *
      std::sqrt(spec.bending_stiffness / (spec.mass_per_length * std::pow(spec.length, 4)));
  CHECK(std::sqrt(b.data.eigenvalues(0)) == doctest::Approx(w0).epsilon(1e-3));
  // Spin about z: K_G = -Omega^2 (G_xx + G_yy); per unit modal mass, -(G_xx + G_yy)_00 is the
  // Southwell coefficient of the first mode.
  using Case = reduction::InertialLoadCase;
  const auto& g = b.geometric.cases;
  const double k1 =
      -(g[static_cast<int>(Case::spin_xx)](0, 0) + g[static_cast<int>(Case::spin_yy)](0, 0));
  MESSAGE("Southwell coefficient of mode 1: " << k1 << " (reference " << kSouthwell << ")");
  CHECK(k1 == doctest::Approx(kSouthwell).epsilon(2e-3));
  // Geometric stiffness matrices are symmetric, and a load case that only bends the beam
  // (acceleration across it) leaves no axial force: no geometric stiffness.
  for (const auto& c : g) CHECK((c - c.transpose()).norm() <= 1e-12 * (1 + c.norm()));
  CHECK(g[static_cast<int>(Case::accel_y)].norm() <=
        1e-9 * g[static_cast<int>(Case::spin_xx)].norm());
}

TEST_CASE("spin-up beam: the linear model diverges, geometric stiffening keeps it straight" *
          doctest::test_suite("long")) {
  const spin_up::Spec spec0;
  const Run lin = simulate(kLinear, spin_up::Frame::attached, spec0, 30.0, 4e-3);
  const Run gs = simulate(kStiffened, spin_up::Frame::attached, spec0, 30.0, 4e-3);
  MESSAGE("linear (attached frame): " << std::string(to_string(lin.status))
                                      << " at t = " << lin.failed_at << " s; max |tip| to 10 s "
                                      << lin.max_tip(0, 10) << " m, to 30 s " << lin.max_tip(0, 30)
                                      << " m");
  MESSAGE("stiffened: max |tip| 0-15 s " << gs.max_tip(0, 15) << " m, 15-20 s "
                                         << gs.max_tip(15, 20) << " m, 25-30 s "
                                         << gs.max_tip(25, 30) << " m");
  // Linear: fails (or passes 10 % of the length) once the spin nears omega0 (at t = 8.5 s on
  // the hub law; at 6 s the spin is 1.8 rad/s).
  CHECK(lin.max_tip(0, 6) < 1.0);
  CHECK((lin.status != StepStatus::ok || lin.max_tip(0, 30) > 1.0));
  // Stiffened: the whole run completes, the deflection stays below the static deflection of
  // the non-rotating beam under the peak angular acceleration (0.8 rad/s^2: 11 q L^4 / (120 EI)
  // = 0.63 m; the spin only stiffens it), and it does not grow once the spin is steady.
  REQUIRE(gs.status == StepStatus::ok);
  const spin_up::Spec spec;
  const double q_tip = spec.mass_per_length * 0.8 * spec.length;
  const double static_bound =
      11 * q_tip * std::pow(spec.length, 4) / (120 * spec.bending_stiffness);
  CHECK(gs.max_tip(0, 30) < static_bound);
  CHECK(gs.max_tip(25, 30) <= 1.05 * gs.max_tip(15, 20));
  // Steady axial stretch (t > 20 s: spin 6 rad/s) against rho A Omega^2 L^3 / (3 EA).
  double mean_x = 0;
  int n = 0;
  for (std::size_t i = 0; i < gs.t.size(); ++i)
    if (gs.t[i] > 20) {
      mean_x += gs.tip_x[i];
      ++n;
    }
  mean_x /= n;
  const double stretch =
      spec.mass_per_length * 36 * std::pow(spec.length, 3) / (3 * spec.axial_stiffness);
  MESSAGE("axial tip stretch " << mean_x << " m, analytic " << stretch << " m");
  CHECK(mean_x == doctest::Approx(stretch).epsilon(0.02));

  // The physics does not depend on where the body frame sits once K_G is in: the floating
  // frame's tip history follows the attached frame's. (Without the effect the floating frame
  // does not diverge either, but it is wrong: its exact rigid rotation escapes the spurious
  // softening only in part.)
  const Run fl = simulate(kStiffened, spin_up::Frame::floating, spec0, 30.0, 4e-3);
  REQUIRE(fl.status == StepStatus::ok);
  REQUIRE(fl.t.size() == gs.t.size());
  double diff = 0;
  for (std::size_t i = 0; i < gs.t.size(); ++i)
    diff = std::max(diff, std::abs(fl.tip_y[i] - gs.tip_y[i]));
  MESSAGE("floating vs attached frame (stiffened): max tip difference " << diff << " m of "
                                                                        << gs.max_tip(0, 30));
  CHECK(diff < 0.02 * gs.max_tip(0, 30));
}

TEST_CASE("constant spin: the in-plane frequency follows Southwell's formula") {
  const auto& b = beam(spin_up::Frame::attached);
  const double w0 = std::sqrt(b.data.eigenvalues(0));
  for (double omega : {0.0, 3.0, 6.0}) {
    CAPTURE(omega);
    spin_up::Spec spec;
    spec.spin_up_time = 0;  // constant rate from t = 0
    spec.final_rate = omega;
    const Run r = simulate(kStiffened, spin_up::Frame::attached, spec, 12.0, 4e-3, omega, 0.05);
    REQUIRE(r.status == StepStatus::ok);
    const double measured = crossing_frequency(r.t, r.p0);
    const double southwell = std::sqrt(w0 * w0 + (kSouthwell - 1) * omega * omega);
    MESSAGE("Omega " << omega << " rad/s: first in-plane frequency " << measured
                     << " rad/s, Southwell " << southwell);
    // Southwell's formula is Rayleigh's quotient with the non-rotating mode shape: an upper
    // bound whose error grows with Omega / omega0 (0.8 and 1.6 here) as the rotating mode
    // shape departs from the non-rotating one; the subtraction of Omega^2 in the in-plane case
    // magnifies it. Hence the tolerances: 0.5 % at 3 rad/s, the bound and 3 % at 6 rad/s.
    CHECK(measured <= southwell * 1.001);
    CHECK(measured == doctest::Approx(southwell).epsilon(omega < 4 ? 0.005 : 0.03));
    if (omega == 0.0) {
      // Nothing loads the beam: the effect adds nothing.
      const Run lin = simulate(kLinear, spin_up::Frame::attached, spec, 12.0, 4e-3, omega, 0.05);
      // (Only the round-off of the held frame's accelerations, ~1e-16, loads it.)
      double diff = 0, size = 0;
      for (std::size_t i = 0; i < r.t.size(); ++i) {
        diff = std::max(diff, std::abs(lin.p0[i] - r.p0[i]));
        size = std::max(size, std::abs(r.p0[i]));
      }
      CHECK(diff <= 1e-12 * size);
    }
  }
}

TEST_CASE("geometric stiffening without enough geometric stiffness data is an error") {
  // The data must cover the body's modes: too few is refused at setup, naming the body.
  reduction::ModalGeometricStiffness small = beam(spin_up::Frame::attached).geometric;
  auto fewer = small.truncated(3);
  REQUIRE(fewer.ok());
  ModelBuilder<double> b;
  const BodyId body = b.add_flexible_body("blade", beam(spin_up::Frame::attached).data, kModes);
  b.add_geometric_stiffening(body, *fewer);
  auto model = b.finalize();
  REQUIRE_FALSE(model.ok());
  MESSAGE(model.error().what());
  CHECK(std::string(model.error().what()).find("body 'blade'") != std::string::npos);
  CHECK(std::string(model.error().what()).find("3") != std::string::npos);
  // A rigid body has none to give.
  ModelBuilder<double> r;
  const BodyId hub = r.add_rigid_body("hub", 1.0, Vector3d::Zero(), Matrix3d::Identity());
  r.add_geometric_stiffening(hub, beam(spin_up::Frame::attached).geometric);
  auto rigid = r.finalize();
  REQUIRE_FALSE(rigid.ok());
  CHECK(std::string(rigid.error().what()).find("body 'hub'") != std::string::npos);
}

}  // namespace test_geometric_stiffening
