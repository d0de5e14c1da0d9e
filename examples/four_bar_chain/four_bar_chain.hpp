// IFToMM benchmark A02, the N four-bar mechanism (Gonzalez, Dopico, Lugris, Cuadrado, "A
// benchmarking system for MBS simulation software", Multibody Syst. Dyn. 16 (2006) 179-190;
// the IFToMM library of computational benchmark problems): N + 1 cranks of 1 m pinned to the
// ground 1 m apart and N couplers of 1 m joining their tips; every link a 1 kg rod, g = 9.81,
// the tip B0 of the first crank starts at 1 m/s. Whenever the cranks lie horizontal, cranks and
// couplers are collinear and the mobility jumps from 1 to N + 1: a singular configuration,
// passed twice per revolution. Modelled in 3D with revolute joints, (3N + 1) x 5 constraint
// equations on (2N + 1) x 6 coordinates: heavily redundant, the plain KKT matrix is singular
// everywhere.
//
// The exact motion keeps every crank parallel to the first and every coupler horizontal (a
// chain of parallelograms); a solver that jumps branch at a singular configuration folds a
// parallelogram into an anti-parallelogram. Mechanical energy is conserved.
//
// A runtime model (docs/model.md): N is a run-time number, N = 40 (81 bodies, 121 joints) is
// built by the same loops as N = 1.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <flexstress/model/all.hpp>

namespace four_bar_chain {

using namespace flexstress;

/// The chain of N parallelograms: its model and the handles a run reads.
struct Chain {
  int bars = 0;
  Model<double> model;
  std::vector<BodyId> cranks;    ///< N + 1, crank k pinned to the ground at (k, 0)
  std::vector<BodyId> couplers;  ///< N, coupler k from the tip of crank k to that of crank k + 1
  std::vector<JointId> pins;     ///< the revolute joints: ground pins, left pins, right pins
  JointId launch;                ///< drives the first crank until released (start())
};

/// A slender 1 kg, 1 m rod along its body x axis, frame at its centre (1 cm square section).
inline BodyId add_rod(ModelBuilder<double>& b, const std::string& name) {
  const double a = 0.01, transverse = (1.0 + a * a) / 12, axial = a * a / 6;
  return b.add_rigid_body(name, 1.0, Vector3d::Zero(),
                          Vector3d(axial, transverse, transverse).asDiagonal());
}

/// The chain at the benchmark's start: cranks vertical, couplers horizontal at y = 1. Every
/// joint axis (marker z) is global z. Integrator settings: where the cranks pass the horizontal,
/// the constraint Jacobian loses rank: in a direction where its singular value is sigma, the
/// augmented Lagrangian's multiplier update contracts by about 1 / (1 + penalty_factor sigma^2)
/// per iteration. A penalty factor of 1e5 (default 1e3) keeps that below 1/2 except within
/// about 3 mrad of the singular configuration; the few steps closer than that are kept at the
/// iteration budget (their multipliers are ill-defined there; their positions are not), and
/// velocity projection removes what they leave in the velocities.
inline Result<Chain> make_chain(int n, double h) {
  Chain c;
  c.bars = n;
  ModelBuilder<double> b;
  // A crank's body x points along global y (up); body z = global z.
  const Matrix3d crank_axes = (Matrix3d() << 0, -1, 0, 1, 0, 0, 0, 0, 1).finished();
  for (int k = 0; k <= n; ++k) {
    c.cranks.push_back(add_rod(b, "crank " + std::to_string(k)));
    b.set_initial_pose(c.cranks.back(), Vector3d(k, 0.5, 0),
                       from_rotation_matrix<double>(crank_axes));
  }
  for (int k = 0; k < n; ++k) {
    c.couplers.push_back(add_rod(b, "coupler " + std::to_string(k)));
    b.set_initial_pose(c.couplers.back(), Vector3d(k + 0.5, 1.0, 0));
  }
  std::vector<MarkerId> root, tip;  // of the cranks
  for (int k = 0; k <= n; ++k) {
    const std::string name = "crank " + std::to_string(k);
    const MarkerId ground = b.add_marker(name + " pivot", b.ground(), -1, Vector3d(k, 0, 0));
    root.push_back(b.add_marker(name + " root", c.cranks[k], -1, Vector3d(-0.5, 0, 0)));
    tip.push_back(b.add_marker(name + " tip", c.cranks[k], -1, Vector3d(0.5, 0, 0)));
    c.pins.push_back(b.add_joint(name + " on the ground", JointKind::revolute, ground, root[k]));
  }
  std::vector<MarkerId> left, right;  // of the couplers
  for (int k = 0; k < n; ++k) {
    const std::string name = "coupler " + std::to_string(k);
    left.push_back(b.add_marker(name + " left", c.couplers[k], -1, Vector3d(-0.5, 0, 0)));
    right.push_back(b.add_marker(name + " right", c.couplers[k], -1, Vector3d(0.5, 0, 0)));
    c.pins.push_back(b.add_joint(name + " left pin", JointKind::revolute, tip[k], left[k]));
  }
  for (int k = 0; k < n; ++k)
    c.pins.push_back(b.add_joint("coupler " + std::to_string(k) + " right pin", JointKind::revolute,
                                 right[k], tip[k + 1]));
  // The model has no initial velocities: the first crank is driven at -1 rad/s (its tip at
  // +1 m/s) while initialize() projects the velocities, then released (start()). Added last,
  // so the pins' rows are those of the chain alone.
  const MarkerId pivot = b.add_marker("launch pivot", b.ground(), -1);
  c.launch = b.add_driver("launch", JointKind::revolute_driver, pivot, root[0],
                          MotionLaw<double>::constant_acceleration(std::acos(0.0), -1.0));
  b.set_gravity(Vector3d(0, -9.81, 0));
  auto& set = b.settings();
  set.step = h;
  set.penalty_factor = 1e5;
  set.accept_at_iteration_limit = true;
  set.project_velocities = true;
  auto m = b.finalize();
  if (!m) return m.error();
  c.model = std::move(*m);
  return c;
}

/// Consistent initial conditions at the benchmark's start: assembled with the launch driver on
/// (velocities from the first crank's -1 rad/s), then again with it released, so that the
/// accelerations and multipliers are those of the free chain.
inline Status start(const Chain& c, Data<double>& d) {
  if (Status st = initialize(c.model, d); !st) return st;
  set_joint_active(c.model, d, c.launch, false);
  return initialize(c.model, d);
}

/// The exact motion of the chain of make_chain from start(): every crank parallel to the first,
/// whose angle phi (from the horizontal) is the one degree of freedom,
/// J phi'' = -m g (N + 1 + 2 N) / 2 cos(phi), J = (N + 1) (1/3 + a^2/12) + N for the N + 1
/// cranks turning about their ends and the N couplers translating (unit rods of add_rod, a the
/// section's side). Integrated by RK4 in steps of 1e-5 s: a reference for the implicit step.
class ExactMotion {
 public:
  explicit ExactMotion(int n)
      : inertia_((n + 1) * (1.0 / 3 + kSide * kSide / 12) + n), load_(9.81 * ((n + 1) / 2.0 + n)) {}
  double angle() const { return phi_; }
  /// Advances by `duration`, a whole number of RK4 steps.
  void advance(double duration) {
    const long steps = std::lround(duration / kStep);
    const auto acceleration = [&](double phi) { return -load_ * std::cos(phi) / inertia_; };
    const double h = kStep;
    for (long i = 0; i < steps; ++i) {
      const double k1p = w_, k1w = acceleration(phi_);
      const double k2p = w_ + h / 2 * k1w, k2w = acceleration(phi_ + h / 2 * k1p);
      const double k3p = w_ + h / 2 * k2w, k3w = acceleration(phi_ + h / 2 * k2p);
      const double k4p = w_ + h * k3w, k4w = acceleration(phi_ + h * k3p);
      phi_ += h / 6 * (k1p + 2 * k2p + 2 * k3p + k4p);
      w_ += h / 6 * (k1w + 2 * k2w + 2 * k3w + k4w);
    }
  }

 private:
  static constexpr double kSide = 0.01, kStep = 1e-5;
  double inertia_, load_;
  double phi_ = std::acos(0.0), w_ = -1.0;  // cranks vertical, the first crank's tip at 1 m/s
};

/// Planar angle of a body's x axis.
inline double heading(const Chain& c, const Data<double>& d, BodyId body) {
  const Matrix3d a = rotation_matrix(body_orientation(c.model, d, body));
  return std::atan2(a(1, 0), a(0, 0));
}

/// What the benchmark asks of a run, measured step by step against the exact motion (every
/// crank parallel to the first, every coupler horizontal, energy constant).
struct Monitor {
  double crank_spread = 0;  ///< largest angle between a crank and the first crank (rad)
  double coupler_tilt = 0;  ///< largest angle of a coupler from the horizontal (rad)
  double energy_error = 0;  ///< largest |E - E0| (J)
  int singular_passes = 0;  ///< sign changes of the first crank's tip height
  double budget_angle = 0;  ///< largest crank angle from the horizontal at a budget-kept step
  double first_crank = 0;   ///< current angle of the first crank (rad)

  void record(const Chain& c, const Data<double>& d, double energy, double e0,
              bool kept_at_budget) {
    constexpr double two_pi = 6.283185307179586;
    const double a0 = heading(c, d, c.cranks.front());
    for (const BodyId k : c.cranks)
      crank_spread =
          std::max(crank_spread, std::abs(std::remainder(heading(c, d, k) - a0, two_pi)));
    for (const BodyId k : c.couplers)
      coupler_tilt = std::max(coupler_tilt, std::abs(std::remainder(heading(c, d, k), two_pi)));
    energy_error = std::max(energy_error, std::abs(energy - e0));
    if (started_ && (std::sin(a0) > 0) != (std::sin(first_crank) > 0)) ++singular_passes;
    started_ = true;
    first_crank = a0;
    if (kept_at_budget)  // angle from the horizontal, folded into [0, pi/2]
      budget_angle = std::max(budget_angle, std::abs(std::asin(std::sin(a0))));
  }

 private:
  bool started_ = false;
};

}  // namespace four_bar_chain
