// The flexible slider crank of Simeon (B. Simeon, "Modelling a flexible slider crank mechanism by
// a mixed system of DAEs and PDEs", Math. Modelling of Systems 2 (1996) 1-18), as the IVP Test
// Set defines it (F. Mazzia, C. Magherini, F. Iavernaro, Test Set for IVP Solvers, release 2.3,
// 2006, problem "crank", file crank.f): a rigid crank of 0.15 m turned at 150 rad/s about a
// ground pivot, a flexible steel connecting rod of 0.30 m (E = 2e11 Pa, rho = 7870 kg/m^3,
// 8 x 8 mm square section, EI = 68.27 N m^2, rho A = 0.504 kg/m; no rotary inertia, linear
// stiffness, no damping), pinned to the crank and to a 0.075552 kg slider on the ground x axis;
// no gravity, planar. The crank starts along +x (top dead centre: crank and rod collinear).
//
// The Test Set's reference at t = 0.1 s: the rod's midpoint deflection relative to the line
// through its pins q1 = 1.893192899613509e-4 m (its first lateral sine-mode amplitude; the
// second mode is zero at the midpoint). simeon_reference.cpp integrates the Test Set's own
// equations (it reproduces that value to 8 digits) for the whole history.
//
// The rod here is an FE beam line reduced by Craig-Bampton with both pin nodes as the interface
// (docs/reduction.md), the lowest `modes` orthonormalized modes kept. The benchmark is planar;
// our beam is 3D, so, as in examples/spin_up_beam, its out-of-plane bending and torsion are
// made 100 times stiffer in frequency (section `planar`), which keeps the lowest modes in the
// plane (a square section has each bending frequency twice, in and out of the plane). Nothing
// excites the out-of-plane modes. `square` keeps the true section.
#pragma once

#include <cmath>
#include <string>

#include <flexstress/dynamics/motion_laws.hpp>
#include <flexstress/fe/beam_line.hpp>
#include <flexstress/fe/beam_section.hpp>
#include <flexstress/model/all.hpp>
#include <flexstress/reduction/modal_body_data.hpp>

namespace slider_crank {

using namespace flexstress;

/// Benchmark data (crank.f).
struct Spec {
  double crank_length = 0.15;       ///< L1, m
  double rod_length = 0.30;         ///< L2, m
  double crank_mass = 0.36;         ///< M1, kg
  double crank_inertia = 0.002727;  ///< J1 about the pivot, kg m^2 (the driver holds it)
  double slider_mass = 0.075552;    ///< M3, kg
  double youngs_modulus = 2.0e11;   ///< Pa
  double poissons_ratio = 0.3;
  double density = 7870.0;        ///< kg/m^3
  double section_height = 0.008;  ///< m (in the plane of motion)
  double section_width = 0.008;   ///< m
  double crank_rate = 150.0;      ///< Omega, rad/s
  int elements = 20;
  bool planar = true;  ///< out-of-plane bending and torsion 100 times stiffer in frequency
  /// Joints: false, every pin a revolute (a planar loop of 3D hinges: redundant, which the
  /// augmented Lagrangian takes); true, the crank pin spherical and the slider pin universal
  /// (18 equations on the 18 rigid coordinates, none redundant).
  bool nonredundant_joints = false;
  /// The crank's inertia about its own axis relative to the transverse one (a slender bar).
  double crank_axial_inertia_ratio = 1e-3;
};

/// The rod's FE model and reduced body.
struct Rod {
  fe::Mesh mesh;
  fe::BeamLine line;
  reduction::ModalBodyData data;
  Index pin_a = 0, middle = 0, pin_b = 0;  ///< nodes: at the crank, at L2/2, at the slider
};

/// The rod along x from its crank pin, Craig-Bampton with both pins as six-DOF interface
/// nodes and `fixed_interface_modes` fixed-interface modes (the full basis has 6 + that many
/// deformation modes; a model keeps the lowest of them).
inline Result<Rod> make_rod(const Spec& spec, int fixed_interface_modes = 4) {
  Rod r;
  fe::Material mat;
  mat.youngs_modulus = spec.youngs_modulus;
  mat.poissons_ratio = spec.poissons_ratio;
  mat.density = spec.density;
  fe::BeamSection section = fe::rectangular_section(spec.section_height, spec.section_width);
  if (spec.planar) {
    section.iy = 1e4 * section.iz;
    section.torsion_constant = 1e4 * (section.iy + section.iz);
  }
  fe::BeamLineSpec line;
  line.end = Vector3d(spec.rod_length, 0, 0);
  line.num_elements = spec.elements;
  line.material = r.mesh.add_material(mat);
  line.section = r.mesh.add_section(section);
  r.line = fe::add_beam_line(r.mesh, line);
  r.pin_a = r.line.nodes.front();
  r.middle = r.line.node_at(0.5 * spec.rod_length);
  r.pin_b = r.line.nodes.back();
  reduction::ReductionSpec rs;
  rs.interface = {{r.pin_a}, {r.pin_b}};
  rs.dynamic_modes.count = fixed_interface_modes;
  rs.mass.beam_rotary_inertia = false;  // Simeon's Euler-Bernoulli rod has none
  auto data = reduction::reduce(r.mesh, rs);
  if (!data) return data.error();
  r.data = std::move(*data);
  return r;
}

/// The mechanism and the handles a run reads.
struct SliderCrank {
  Model<double> model;
  BodyId crank, rod, slider;
  MarkerId rod_a, rod_middle, rod_b;
  JointId drive;
};

/// Crank (frame at the pivot), rod (frame at its crank pin), slider, all starting along +x;
/// every hinge axis is global z; the slider's prismatic joint slides along global x.
/// `settings` are the integrator's (the defaults unless a caller changes them).
inline Result<SliderCrank> make_model(const Spec& spec, const Rod& rod, int modes,
                                      const ImplicitSettings<double>* settings = nullptr) {
  ModelBuilder<double> b;
  SliderCrank s;
  const double l1 = spec.crank_length, l2 = spec.rod_length, m1 = spec.crank_mass;
  // A slender crank: centre of mass halfway, inertia about it J1 - M1 (L1/2)^2.
  const double jc = spec.crank_inertia - m1 * 0.25 * l1 * l1;
  s.crank = b.add_rigid_body("crank", m1, Vector3d(0.5 * l1, 0, 0),
                             Vector3d(spec.crank_axial_inertia_ratio * jc, jc, jc).asDiagonal());
  s.rod = b.add_flexible_body("rod", rod.data, modes);
  b.set_initial_pose(s.rod, Vector3d(l1, 0, 0));
  const double ms = spec.slider_mass;  // a small block; its rotations are held
  s.slider = b.add_rigid_body("slider", ms, Vector3d::Zero(),
                              Vector3d(1e-6 * ms, 1e-6 * ms, 1e-6 * ms).asDiagonal());
  b.set_initial_pose(s.slider, Vector3d(l1 + l2, 0, 0));

  const MarkerId pivot = b.add_marker("pivot", b.ground(), -1);
  const MarkerId crank_root = b.add_marker("crank root", s.crank, -1);
  const MarkerId crank_pin = b.add_marker("crank pin", s.crank, -1, Vector3d(l1, 0, 0));
  s.rod_a = b.add_marker("rod at crank", s.rod, rod.pin_a);
  s.rod_middle = b.add_marker("rod middle", s.rod, rod.middle);
  s.rod_b = b.add_marker("rod at slider", s.rod, rod.pin_b);
  const MarkerId slider_pin = b.add_marker("slider pin", s.slider, -1);
  // Prismatic joint: slides along marker z; z = global x, x = global y, y = global z.
  const Matrix3d along_x = (Matrix3d() << 0, 0, 1, 1, 0, 0, 0, 1, 0).finished();
  const MarkerId guide = b.add_marker("guide", b.ground(), -1, Vector3d::Zero(), along_x);
  const MarkerId slider_guide =
      b.add_marker("slider on guide", s.slider, -1, Vector3d::Zero(), along_x);
  b.add_joint("pivot", JointKind::revolute, pivot, crank_root);
  s.drive = b.add_driver("crank drive", JointKind::revolute_driver, pivot, crank_root,
                         MotionLaw<double>::constant_acceleration(0.0, spec.crank_rate));
  if (!spec.nonredundant_joints) {
    b.add_joint("crank pin", JointKind::revolute, crank_pin, s.rod_a);
    b.add_joint("slider pin", JointKind::revolute, s.rod_b, slider_pin);
  } else {
    // Universal: z_i (the slider's, global z) perpendicular to z_j (the rod's in-plane
    // transverse axis): the rod turns in the plane and tilts about that axis, never spins.
    const Matrix3d z_along_y = (Matrix3d() << 1, 0, 0, 0, 0, 1, 0, -1, 0).finished();
    const MarkerId rod_b_cross =
        b.add_marker("rod at slider, cross", s.rod, rod.pin_b, Vector3d::Zero(), z_along_y);
    b.add_joint("crank pin", JointKind::spherical, crank_pin, s.rod_a);
    b.add_joint("slider pin", JointKind::universal, slider_pin, rod_b_cross);
  }
  b.add_joint("guide", JointKind::prismatic, guide, slider_guide);
  if (settings) b.settings() = *settings;
  auto m = b.finalize();
  if (!m) return m.error();
  s.model = std::move(*m);
  return s;
}

/// The rod's midpoint deflection relative to the line through its two pins, in the plane,
/// positive towards the left of the pin line (crank pin to slider pin): Simeon's q1.
inline double midpoint_deflection(const SliderCrank& s, const Data<double>& d) {
  const Vector3d a = marker_frame(s.model, d, s.rod_a).origin;
  const Vector3d b = marker_frame(s.model, d, s.rod_b).origin;
  const Vector3d m = marker_frame(s.model, d, s.rod_middle).origin;
  const Vector3d e = (b - a).normalized();
  return e.x() * (m - a).y() - e.y() * (m - a).x();
}

/// Initial velocities before initialize(). Its projection onto the joints is the least change
/// in the mass metric, so it must start from the rigid motion: from zero velocities the least
/// kinetic energy that meets the pins' velocities puts most of the rod's velocity into its
/// modes (an elastic velocity of metres per second, a 1.2 cm oscillation of the midpoint).
/// `smooth` = false: the rod undeformed and moving rigidly (the Test Set's second start:
/// crank pin at L1 Omega upwards, slider at rest at top dead centre, rod turning at
/// -L1 Omega / L2). `smooth` = true: the Test Set's smooth start (crank.f, init1), the rod's
/// elastic velocity q1_dot sin(pi xi) + q2_dot sin(2 pi xi) laterally with q1_dot = 0.444896105
/// and q2_dot = 0.463434311e-2 m/s added (its axial parts, 1e-5 m and 1e-6 m/s, are left
/// out); the rod's frame velocity and modal rates are fitted by least squares to the nodal
/// velocities of that field plus the rigid motion, and initialize() removes the small
/// remainder the joints do not allow.
inline Status set_start_velocities(const Spec& spec, const Rod& rod, SliderCrank& s,
                                   Data<double>& d, bool smooth) {
  const int k = static_cast<int>(s.model.body(s.rod).modes);
  const double l1 = spec.crank_length, l2 = spec.rod_length, w = spec.crank_rate;
  const double pi = 3.14159265358979323846;
  const double q1_dot = smooth ? 0.444896105 : 0.0, q2_dot = smooth ? 0.463434311e-2 : 0.0;
  const double rod_rate = -l1 * w / l2;  // phi2_dot at top dead centre
  const Index n = rod.data.num_nodes();
  // Unknowns: R_dot x, R_dot y, w_z, p_dot (k); equations: x and y velocity of every node.
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(2 * n, 3 + k);
  Eigen::VectorXd rhs(2 * n);
  for (Index i = 0; i < n; ++i) {
    const Vector3d x = rod.data.node_positions[static_cast<std::size_t>(i)];
    const double xi = x.x() / l2;
    a(2 * i, 0) = 1;
    a(2 * i, 2) = -x.y();
    a(2 * i + 1, 1) = 1;
    a(2 * i + 1, 2) = x.x();
    a.block(2 * i, 3, 2, k) = rod.data.phi_r(i).topRows<2>().leftCols(k);
    rhs(2 * i) = 0;
    rhs(2 * i + 1) =
        l1 * w + rod_rate * x.x() + q1_dot * std::sin(pi * xi) + q2_dot * std::sin(2 * pi * xi);
  }
  const Eigen::VectorXd sol = a.colPivHouseholderQr().solve(rhs);
  set_body_velocity(s.model, d, s.crank, Vector3d::Zero(), Vector3d(0, 0, w));
  set_body_velocity(s.model, d, s.rod, Vector3d(sol(0), sol(1), 0), Vector3d(0, 0, sol(2)));
  set_body_velocity(s.model, d, s.slider, Vector3d::Zero(), Vector3d::Zero());
  return set_modal_state(s.model, d, s.rod, Eigen::VectorXd::Zero(k), sol.tail(k));
}

}  // namespace slider_crank
