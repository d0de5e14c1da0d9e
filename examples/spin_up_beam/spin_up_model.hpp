// The spin-up beam (Kane, Ryan & Banerjee, J. Guidance 10 (1987) 139; Simo & Vu-Quoc 1988;
// ANSYS VM258): a 10 m beam clamped to a rigid hub of zero radius whose angle is prescribed,
// spun up from rest to 6 rad/s in 15 s, no gravity. The spin passes the first bending frequency
// (3.8 rad/s): a linear FFRF model softens without bound there, the real beam stays nearly
// straight because the centrifugal tension stiffens it.
//
// The benchmark is planar (bending in the plane of rotation, the x-y plane here). Our beam is 3D;
// its out-of-plane bending and torsion are made 100 times stiffer in frequency (iy = 1e4 iz, a
// large torsion constant) so that the lowest modes are the in-plane ones, which is what a planar
// model keeps. Nothing excites the out-of-plane modes, so this changes none of the results.
#pragma once

#include <cmath>

#include <flexstress/dynamics/motion_laws.hpp>
#include <flexstress/fe/beam_line.hpp>
#include <flexstress/model/all.hpp>
#include <flexstress/reduction/modal_body_data.hpp>
#include <flexstress/reduction/modal_geometric_stiffness.hpp>

namespace spin_up {

using namespace flexstress;

/// Benchmark data (validation sheet; Kane et al. 1987).
struct Spec {
  double length = 10.0;              ///< m
  double axial_stiffness = 2.8e7;    ///< EA, N
  double bending_stiffness = 1.4e4;  ///< EI (in-plane), N m^2
  double mass_per_length = 1.2;      ///< rho A, kg/m
  int elements = 20;
  double spin_up_time = 15.0;  ///< s
  double final_rate = 6.0;     ///< rad/s
};

/// The hub angle: theta = (W/T) [t^2/2 + (T/(2 pi))^2 (cos(2 pi t/T) - 1)] up to T, then
/// theta = W t - W T/2 (rate W, smooth acceleration).
template <class Scalar>
struct HubAngle {
  Scalar spin_up_time = Scalar(15), final_rate = Scalar(6);
  MotionValue<Scalar> operator()(Scalar t) const {
    const Scalar T = spin_up_time, w = final_rate;
    if (t >= T) return {w * t - w * T / 2, w, Scalar(0)};
    const Scalar k = Scalar(2 * 3.14159265358979323846) / T;
    return {w / T * (t * t / 2 + (std::cos(k * t) - Scalar(1)) / (k * k)),
            w / T * (t - std::sin(k * t) / k), w / T * (Scalar(1) - std::cos(k * t))};
  }
};

/// The beam's FE model, reduced body and modal geometric stiffness.
struct Beam {
  fe::Mesh mesh;
  fe::BeamLine line;
  reduction::ModalBodyData data;
  reduction::ModalGeometricStiffness geometric;
  Index hub_node = 0, tip_node = 0;
};

/// Where the beam's body frame sits: attached to the hub (the cantilever modes, the frame of
/// rotor-blade codes and of Kane's "conventional" model), or floating (the library's default:
/// orthonormalized modes, rigid motion exact in the frame).
enum class Frame { attached, floating };

/// Builds the beam along x from the hub, Craig-Bampton with the hub node as the interface and
/// `modes` fixed-interface modes.
inline Result<Beam> make_beam(const Spec& spec, int modes, Frame frame = Frame::attached) {
  Beam b;
  // E, A, I chosen to give the benchmark's EA, EI and rho A.
  const double area = 4e-4;
  fe::Material mat;
  mat.youngs_modulus = spec.axial_stiffness / area;
  mat.density = spec.mass_per_length / area;
  const double iz = spec.bending_stiffness / mat.youngs_modulus;
  fe::BeamSection section;
  section.area = area;
  section.iz = iz;
  section.iy = 1e4 * iz;
  section.torsion_constant = 1e4 * (section.iy + section.iz);
  fe::BeamLineSpec line;
  line.end = Vector3d(spec.length, 0, 0);
  line.num_elements = spec.elements;
  line.material = b.mesh.add_material(mat);
  line.section = b.mesh.add_section(section);
  b.line = fe::add_beam_line(b.mesh, line);
  b.hub_node = b.line.nodes.front();
  b.tip_node = b.line.nodes.back();
  reduction::ReductionSpec rs;
  rs.interface.push_back({b.hub_node});
  rs.dynamic_modes.count = modes;
  rs.interface_attached_frame = frame == Frame::attached;
  auto data = reduction::reduce(b.mesh, rs);
  if (!data) return data.error();
  b.data = std::move(*data);
  auto g = reduction::modal_geometric_stiffness(b.mesh, b.data,
                                                reduction::clamp_interface_nodes(b.data));
  if (!g) return g.error();
  b.geometric = std::move(*g);
  return b;
}

/// The hub angle as a motion law's callback (user data: the Spec).
inline void hub_angle(double t, double* out, void* user) {
  const Spec& spec = *static_cast<const Spec*>(user);
  const MotionValue<double> v = HubAngle<double>{spec.spin_up_time, spec.final_rate}(t);
  out[0] = v.value;
  out[1] = v.rate;
  out[2] = v.acceleration;
}

/// The model: the beam on a revolute joint at the hub (axis z) driven by the hub angle, no
/// gravity; with or without geometric stiffening. Markers at the hub and the tip read the
/// deflection.
struct SpinUp {
  Model<double> model;
  BodyId beam;
  MarkerId hub, tip;
  JointId hinge, driver;
};

/// `spec` must outlive the model (the hub law reads it).
inline Result<SpinUp> make_model(const Beam& beam, const Spec& spec, bool stiffening, int modes) {
  ModelBuilder<double> b;
  SpinUp s;
  s.beam = b.add_flexible_body("beam", beam.data, modes);
  if (stiffening) b.add_geometric_stiffening(s.beam, beam.geometric);
  const MarkerId hub_ground = b.add_marker("hub on ground", b.ground(), -1);
  s.hub = b.add_marker("hub", s.beam, beam.hub_node);
  s.tip = b.add_marker("tip", s.beam, beam.tip_node);
  s.hinge = b.add_joint("hub", JointKind::revolute, hub_ground, s.hub);
  s.driver = b.add_driver("hub angle", JointKind::revolute_driver, hub_ground, s.hub,
                          MotionLaw<double>::from_callback(&hub_angle, const_cast<Spec*>(&spec)));
  // The beam spins about its intermediate principal axis: without velocity projection the
  // velocity error normal to the joints grows (docs/dynamics.md, "Spinning bodies").
  b.settings().project_velocities = true;
  auto model = b.finalize();
  if (!model) return model.error();
  s.model = std::move(*model);
  return s;
}

/// The tip's deflection in the plane of rotation relative to the hub's tangent (the hub node's
/// own rotation removed; zero in the attached frame) and its axial stretch, from the elastic
/// displacements of the two markers in the body frame.
struct TipDeflection {
  double in_plane = 0, axial = 0;
};
inline TipDeflection tip_deflection(const SpinUp& s, const Data<double>& d, double length) {
  const flexstress::Frame<double> hub = marker_frame_in_body(s.model, d, s.hub);
  const flexstress::Frame<double> tip = marker_frame_in_body(s.model, d, s.tip);
  // Elastic parts: the undeformed tip lies `length` along x from the hub, axes aligned.
  const Vector3d rel = tip.origin - hub.origin - Vector3d(length, 0, 0);
  const double hub_turn = hub.axes(1, 0);  // the hub's x axis turned about z
  return {rel.y() - hub_turn * length, rel.x()};
}

}  // namespace spin_up
