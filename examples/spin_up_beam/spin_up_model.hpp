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

#include <flexstress/dynamics/joints.hpp>
#include <flexstress/dynamics/motion_laws.hpp>
#include <flexstress/dynamics/scene.hpp>
#include <flexstress/fe/beam_line.hpp>
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

/// The scene: ground, the beam, a revolute joint at the hub (axis z) and its angle driver.
template <int N, class EffectList, int StorageLimit = fixed_storage_limit>
using SpinUpScene = typename Scene<double, Bodies<FFRFBody<N>>,
                                   Joints<Revolute<ground, 0>, RevoluteDriver<ground, 0, HubAngle>>,
                                   EffectList>::template with_storage_limit<StorageLimit>;

template <class SceneT>
Result<SceneT> make_scene(const Beam& beam, const Spec& spec) {
  SceneT scene;
  using Body = typename SceneT::template BodyType<0>;
  auto body = Body::from_modal_data(beam.data);
  if (!body) return body.error();
  if (Status s = body->set_geometric_stiffness(beam.geometric); !s) return s.error();
  scene.template body<0>() = std::move(*body);
  const auto hub_ground = fixed_marker<double>(Vector3d::Zero());
  const auto hub_beam = make_marker(scene.template body<0>(), beam.hub_node, Vector3d::Zero());
  scene.template joint<0>().marker_i = hub_ground;
  scene.template joint<0>().marker_j = hub_beam;
  scene.template joint<1>().marker_i = hub_ground;
  scene.template joint<1>().marker_j = hub_beam;
  scene.template joint<1>().params.law = HubAngle<double>{spec.spin_up_time, spec.final_rate};
  scene.gravity.setZero();
  return scene;
}

}  // namespace spin_up
