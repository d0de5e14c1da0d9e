// Random mechanisms on the integrator's defaults. A seeded generator builds chains and planar
// or spatial loops (random lengths, masses, joint kinds and axes; flexible links with random
// mode counts whose lowest frequency spans 1 Hz to 5 kHz; random initial velocities, gravity
// and drives) and runs each for 2 s on ImplicitSettings{}. The contract, for every mechanism:
//  - it runs to the end, or a step (or the initialization) returns a status whose message names
//    a part of the model (a body or a joint, by its name), and the state it leaves is finite;
//  - no state is ever non-finite after an accepted step;
//  - the energy balance of a conservative one (model/energy_balance.hpp: E - E(0) + D_damping,
//    no drive) does not grow by more than 1 % of the largest kinetic energy of the run, or, where
//    it does, the growth is the step's truncation error, not an instability: at h / 4 it is at
//    least 4 times smaller (measured: seed 4 grows by 1.5 %, 0.14 % and 0.028 % of its kinetic
//    energy at h, h / 2 and h / 4, about third order).
// Mechanisms are not tuned to run: a driven loop may be driven into a toggle position, where its
// joints lock, and then the step must say so. The test reports how many ran to the end.
//
// FLEXSTRESS_RANDOM_MECHANISMS (default 200) sets how many seeds run, from
// FLEXSTRESS_RANDOM_FIRST_SEED (default 1): a wider search is one environment variable away,
// and ctest runs the default 200 as two halves in parallel (tests/CMakeLists.txt).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include <flexstress/model/all.hpp>

#include "support/beam_fixtures.hpp"

namespace test_random_mechanisms {

using namespace flexstress;

namespace {

constexpr double kPi = 3.14159265358979323846;

long environment_count(const char* name, long fallback) {
  const char* s = std::getenv(name);
  return s != nullptr ? std::strtol(s, nullptr, 10) : fallback;
}

struct Rng {
  std::mt19937_64 engine;
  explicit Rng(unsigned long seed) : engine(seed) {}
  double uniform(double lo, double hi) { return std::uniform_real_distribution<>(lo, hi)(engine); }
  double log_uniform(double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); }
  int integer(int lo, int hi) { return std::uniform_int_distribution<>(lo, hi)(engine); }
  bool chance(double p) { return uniform(0, 1) < p; }
  Vector3d direction() {
    Vector3d v;
    do v = Vector3d(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
    while (v.norm() < 0.1 || v.norm() > 1);
    return v.normalized();
  }
  Vector3d perpendicular_to(const Vector3d& a) {
    Vector3d v;
    do v = direction() - direction().dot(a) * a;
    while (v.norm() < 0.1);
    return (v - v.dot(a) * a).normalized();
  }
};

/// A frame whose x axis points along `x` (y and z completed deterministically).
Matrix3d frame_with_x_axis(const Vector3d& x) {
  const Matrix3d f = frame_with_z_axis<double>(x);
  Matrix3d r;
  r.col(0) = f.col(2);
  r.col(1) = f.col(0);
  r.col(2) = f.col(1);
  return r;
}

/// One link, from point p to point q: its body (frame at p, x along q - p) and where its end
/// markers go (a flexible link's end nodes, a rigid link's frame and its far end).
struct Link {
  BodyId body;
  std::string name;
  Matrix3d axes;  ///< body axes in the world at the start
  Index start_node = -1, end_node = -1;
  double length = 0;
};

/// A generated mechanism: its model, the velocities drawn, and the part names a failure may
/// cite.
struct Mechanism {
  Model<double> model;
  std::vector<BodyId> bodies;
  std::vector<Vector3d> linear, angular;  ///< initial velocities drawn per body (global, body)
  std::vector<std::string> names;         ///< of the bodies and joints
  std::string description;
  bool driven = false;
  std::vector<double> first_frequencies;  ///< of the flexible links (Hz)
};

/// Draws and builds one mechanism. A joint sits at a point two links share, its two markers
/// aligned in the world, so every drawn configuration is assembled.
Mechanism generate(unsigned long seed) {
  Rng rng(seed);
  ModelBuilder<double> b;
  Mechanism mech;
  std::ostringstream what;
  what.precision(3);
  const bool loop = rng.chance(0.4);
  const int links = loop ? rng.integer(3, 5) : rng.integer(1, 5);

  // The points: a loop is a polygon between two ground pivots in a plane turned at random
  // (redrawn until no link is shorter than 0.2 m), a chain a random walk from its pivot.
  std::vector<Vector3d> points;
  Vector3d plane_normal = Vector3d::UnitZ();
  if (loop) {
    const Matrix3d plane = frame_with_z_axis<double>(rng.direction());
    plane_normal = plane.col(2);
    for (bool ok = false; !ok;) {
      points.assign(1, Vector3d::Zero());
      for (int k = 1; k < links; ++k)
        points.push_back(plane * Vector3d(rng.uniform(-1, 1.5), rng.uniform(0.3, 1.2), 0));
      points.push_back(plane * Vector3d(rng.uniform(0.4, 1.2), 0, 0));
      ok = true;
      for (int k = 0; k < links; ++k)
        ok = ok && (points[std::size_t(k) + 1] - points[std::size_t(k)]).norm() > 0.2;
    }
    what << links << "-link loop in the plane normal to (" << plane_normal.transpose() << "); ";
  } else {
    points.push_back(Vector3d::Zero());
    for (int k = 0; k < links; ++k)
      points.push_back(points.back() + rng.uniform(0.2, 1.5) * rng.direction());
    what << links << "-link chain; ";
  }

  std::vector<Link> chain;
  for (int k = 0; k < links; ++k) {
    Link l;
    const Vector3d p = points[std::size_t(k)], q = points[std::size_t(k) + 1];
    l.length = (q - p).norm();
    l.axes = frame_with_x_axis(q - p);
    l.name = "link " + std::to_string(k);
    if (rng.chance(0.35)) {
      // A steel tube made as stiff as a lowest frequency drawn from 1 Hz to 5 kHz: the
      // frequencies scale with the square root of Young's modulus. Both ends are interface
      // nodes (Craig-Bampton), 4 fixed-interface modes: 16 modes, of which a random number.
      const double side = l.length / rng.uniform(10, 30);
      const fe::BeamSection section = fe::rectangular_hollow_section(side, side, side / 10);
      const testing::BeamBody steel =
          testing::make_beam_body(l.length, section, 6, {0.0, l.length}, 4);
      const double target = rng.log_uniform(1, 5000);
      const double f_steel = std::sqrt(steel.data.eigenvalues(0)) / (2 * kPi);
      fe::Material material = fe::steel();
      material.youngs_modulus *= (target / f_steel) * (target / f_steel);
      const testing::BeamBody beam =
          testing::make_beam_body(l.length, section, 6, {0.0, l.length}, 4, {}, material);
      const int modes = rng.integer(1, int(beam.data.eigenvalues.size()));
      const double f1 = std::sqrt(beam.data.eigenvalues(0)) / (2 * kPi);
      mech.first_frequencies.push_back(f1);
      l.body = b.add_flexible_body(l.name, beam.data, modes);
      l.start_node = beam.interface_nodes[0];
      l.end_node = beam.interface_nodes[1];
      what << l.name << ": flexible " << l.length << " m, " << modes << " modes, first " << f1
           << " Hz; ";
    } else {
      const double side = l.length * rng.uniform(0.03, 0.1);
      const double mass = rng.uniform(1000, 8000) * side * side * l.length;
      const double t = mass * (l.length * l.length + side * side) / 12;
      const double axial = mass * side * side / 6;
      l.body = b.add_rigid_body(l.name, mass, Vector3d(l.length / 2, 0, 0),
                                Vector3d(axial, t, t).asDiagonal());
      what << l.name << ": rigid " << l.length << " m, " << mass << " kg; ";
    }
    b.set_initial_pose(l.body, p, from_rotation_matrix<double>(l.axes));
    mech.bodies.push_back(l.body);
    mech.names.push_back(l.name);
    chain.push_back(l);
  }

  // Marker at point k on the link before it (its end) or after it (its start), or the ground,
  // with the given world axes.
  auto marker = [&](int k, bool on_parent, const Matrix3d& world_axes, const std::string& joint) {
    const int link = on_parent ? k - 1 : k;
    const std::string name = joint + (on_parent ? " i" : " j");
    if (link < 0 || link >= links)
      return b.add_marker(name, b.ground(), -1, points[std::size_t(k)], world_axes);
    const Link& l = chain[std::size_t(link)];
    const Matrix3d local = l.axes.transpose() * world_axes;
    const bool at_end = on_parent;
    if (l.start_node >= 0)
      return b.add_marker(name, l.body, at_end ? l.end_node : l.start_node, Vector3d::Zero(),
                          local);
    return b.add_marker(name, l.body, -1, Vector3d(at_end ? l.length : 0.0, 0, 0), local);
  };

  // The joints at points 0 .. links (the last only in a loop). A loop's are revolutes about
  // the plane's normal (3D revolutes: the planar loop is redundant), sometimes with one
  // spherical and one universal joint that make it spatial and non-redundant (as the crane's).
  const int joints = loop ? links + 1 : links;
  const int spatial_at = loop && rng.chance(0.3) ? rng.integer(1, links - 1) : -1;
  for (int k = 0; k < joints; ++k) {
    const std::string name = "joint " + std::to_string(k);
    mech.names.push_back(name);
    JointKind kind = JointKind::revolute;
    Vector3d axis = plane_normal;
    if (loop) {
      if (k == spatial_at) kind = JointKind::spherical;
      if (k == spatial_at + 1 && spatial_at >= 0) kind = JointKind::universal;
    } else {
      const double pick = rng.uniform(0, 1);
      kind = pick < 0.35   ? JointKind::revolute
             : pick < 0.6  ? JointKind::spherical
             : pick < 0.75 ? JointKind::universal
             : pick < 0.85 ? JointKind::cylindrical
             : pick < 0.95 ? JointKind::prismatic
                           : JointKind::fixed;
      axis = rng.direction();
    }
    const Matrix3d axes_i = frame_with_z_axis<double>(axis);
    Matrix3d axes_j = axes_i;
    if (kind == JointKind::universal) {  // z_i and z_j perpendicular: the cross axes
      const Vector3d second = loop ? Vector3d((points[std::size_t(k)] - points[std::size_t(k) - 1])
                                                  .cross(plane_normal)
                                                  .normalized())
                                   : rng.perpendicular_to(axis);
      axes_j = frame_with_z_axis<double>(second);
    }
    const MarkerId i = marker(k, true, axes_i, name);
    const MarkerId j = marker(k, false, axes_j, name);
    b.add_joint(name, kind, i, j);
    what << name << ": " << to_string(kind) << "; ";
    // A drive on some revolute and prismatic joints: from rest or from a speed, accelerating.
    if ((kind == JointKind::revolute || kind == JointKind::prismatic) && rng.chance(0.2) &&
        !mech.driven) {
      const bool turn = kind == JointKind::revolute;
      const double v = rng.chance(0.5) ? rng.uniform(-1, 1) * (turn ? 5 : 0.5) : 0.0;
      const double a = rng.uniform(-1, 1) * (turn ? 10 : 1);
      b.add_driver(name + " drive", turn ? JointKind::revolute_driver : JointKind::prismatic_driver,
                   i, j, MotionLaw<double>::constant_acceleration(0, v, a));
      mech.names.push_back(name + " drive");
      mech.driven = true;
      what << name << " driven at " << v << (turn ? " rad/s + " : " m/s + ") << a << " t; ";
    }
  }
  if (rng.chance(0.9)) {
    const Vector3d g = 9.81 * rng.direction();
    b.set_gravity(g);
    what << "gravity (" << g.transpose() << "); ";
  }
  for (std::size_t k = 0; k < chain.size(); ++k) {
    mech.linear.push_back(rng.uniform(0, 2) * rng.direction());
    mech.angular.push_back(rng.uniform(0, 5) * rng.direction());
  }
  mech.description = what.str();
  auto m = b.finalize();
  if (!m.ok()) FAIL("seed " << seed << ": " << m.error().what() << "\n" << mech.description);
  mech.model = std::move(*m);
  return mech;
}

bool names_a_part(const std::string& message, const Mechanism& mech) {
  for (const std::string& n : mech.names)
    if (message.find("'" + n + "'") != std::string::npos) return true;
  return false;
}

struct Outcome {
  bool ran = false;
  std::string failure;
  double growth = 0;  ///< largest growth of the energy balance over the largest kinetic energy
  bool conservative = false;  ///< no drive
};

/// Runs one mechanism for `duration` on the defaults (the step divided by `refine`, the local
/// error tolerance by its cube) and checks the contract.
Outcome run(const Mechanism& mech, unsigned long seed, double duration, int refine = 1) {
  Outcome out;
  const Model<double>& m = mech.model;
  CAPTURE(seed);
  CAPTURE(refine);
  CAPTURE(mech.description);
  Data<double> d(m);
  if (refine > 1) {  // the local error tolerance with it, as the local error goes with h^3
    d.settings.local_error_tolerance /= refine * refine * refine;
    set_step_size(d, d.settings.step / refine);
  }
  for (std::size_t k = 0; k < mech.bodies.size(); ++k)
    set_body_velocity(m, d, mech.bodies[k], mech.linear[k], mech.angular[k]);
  if (Status s = initialize(m, d); !s.ok()) {
    out.failure = std::string("initialize: ") + s.error().what();
    CHECK_MESSAGE(names_a_part(out.failure, mech), out.failure);
    return out;
  }
  EnergyBalance<double> balance;
  balance.start(m, d);
  double kinetic = energy(m, d).kinetic;
  const long steps = std::lround(duration / d.settings.step);
  for (long i = 0; i < steps; ++i) {
    const StepStatus st = step(m, d);
    // budget_reached on the defaults: a step kept with Newton stalled within the joints'
    // tolerance (keep_stalled_steps); the run goes on.
    if (st == StepStatus::budget_reached)
      CHECK_MESSAGE(d.statistics.stalled_steps == d.statistics.over_budget,
                    "seed " << seed << ": a step kept at the budget was not stalled");
    if (st != StepStatus::ok && st != StepStatus::budget_reached) {
      out.failure =
          std::string(to_string(st)) + " at t = " + std::to_string(d.t) + ": " + d.message.data();
      CHECK_MESSAGE(names_a_part(d.message.data(), mech), out.failure);
      CHECK_MESSAGE((d.q.allFinite() && d.v.allFinite()), "state left non-finite: " << out.failure);
      return out;
    }
    if (!(d.q.allFinite() && d.v.allFinite())) {
      FAIL_CHECK("an accepted step left a non-finite state at t = " << d.t);
      return out;
    }
    balance.record(m, d);
    kinetic = std::max(kinetic, energy(m, d).kinetic);
    out.growth = std::max(out.growth, balance.residual() / std::max(kinetic, 1e-12));
  }
  if (std::getenv("FLEXSTRESS_RANDOM_VERBOSE"))
    MESSAGE("seed " << seed << std::string(mech.driven ? " (driven)" : "") << ": energy growth "
                    << out.growth << ", " << d.statistics.split_steps << " steps split");
  out.ran = true;
  return out;
}

/// Runs one mechanism and, when it is conservative (no drive) and its energy grew by more than
/// 1 %, again at h / 4, where the growth must have shrunk at least 4 times. (A driven one's
/// balance has the drive's work, from multipliers that converge at a lower order than the
/// motion: at h / 4, 2 to 3 times smaller on three seeds.)
Outcome run_and_check_energy(unsigned long seed, double duration) {
  const Mechanism mech = generate(seed);
  Outcome o = run(mech, seed, duration);
  o.conservative = !mech.driven;
  if (!o.ran || mech.driven || o.growth <= 0.01) return o;
  const Outcome fine = run(mech, seed, duration, 4);
  CAPTURE(seed);
  CAPTURE(mech.description);
  CHECK_MESSAGE(fine.ran, "ran at h but not at h / 4: " << fine.failure);
  CHECK_MESSAGE(fine.growth <= o.growth / 4,
                "the energy grew by " << o.growth << " of the largest kinetic energy at h and by "
                                      << fine.growth << " at h / 4");
  return o;
}

}  // namespace

TEST_CASE("random mechanisms run on the defaults or fail naming the part, never silently") {
  const long count = environment_count("FLEXSTRESS_RANDOM_MECHANISMS", 200);
  const long first = environment_count("FLEXSTRESS_RANDOM_FIRST_SEED", 1);
  long ran = 0, grew = 0, conservative_grew = 0;
  double worst_growth = 0;
  std::ostringstream failures;
  for (long seed = first; seed < first + count; ++seed) {
    const Outcome o = run_and_check_energy(static_cast<unsigned long>(seed), 2.0);
    if (o.ran) {
      ++ran;
      grew += o.growth > 0.01;
      conservative_grew += o.conservative && o.growth > 0.01;
      worst_growth = std::max(worst_growth, o.growth);
    } else {
      failures << "  seed " << seed << ": " << o.failure << "\n";
    }
  }
  MESSAGE(ran << " of " << count << " mechanisms ran 2 s (" << grew
              << " of them with an energy growth above 1 % of their largest kinetic energy, "
              << conservative_grew << " of those conservative; the largest growth " << worst_growth
              << "); the others stopped with:\n"
              << failures.str());
  // A guard against regressions of the defaults on the first 200 seeds (the default run) and
  // on their halves (ctest runs the halves in parallel): 192 of them ran, 96 and 96 (clang 14,
  // -O1, the tests' build), and no conservative one grew its energy by more than 1 % of its
  // largest kinetic energy (at most 0.36 %; 6 did, by up to 6.0 %, before drifted velocities
  // were projected in the mass metric).
  struct Guard {
    long first, count, at_least;
  };
  for (const Guard g : {Guard{1, 200, 188}, Guard{1, 100, 93}, Guard{101, 100, 93}})
    if (first == g.first && count == g.count) {
      CHECK(ran >= g.at_least);
      CHECK(conservative_grew == 0);
    }
}

}  // namespace test_random_mechanisms
