// The paper's crane (Rantalainen et al. 2013, section 5), composed at run time: a flexible boom on
// a support, a hydraulic cylinder and its piston rod, a payload, gravity, a prescribed stroke or
// a valve-driven cylinder, and the welded detail D as a sub-model whose stresses come per step
// from fused modal rows, with a damage meter on its hot spot. Any boom mode count the reduction
// offers. Every number and every choice the paper leaves open is in docs/crane.md.
//
// This header holds the model's side only. What the crane precomputes (the boom's reduction, the
// detail's sub-model) is made in crane_precompute.cpp, the one unit that parses the FE, reduction
// and stress headers for it, and the only crane unit that does not parse the model's headers;
// the other units see its results as plain data (crane_precompute.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <flexstress/fatigue/damage.hpp>
#include <flexstress/fatigue/sn_curve.hpp>
#include <flexstress/model/all.hpp>

#include "crane_precompute.hpp"

namespace crane {

using namespace flexstress;

/// The damage meter of every crane run: IIW hot-spot FAT 100, slope 3 to the knee at 1e7 and
/// Haibach (5) beyond, as IIW recommends for variable amplitude; streaming rainflow on 128
/// classes over +-400 MPa, fed in MPa. One place for the numbers: the C export writes them.
struct MeterSpec {
  double fat = 100;                  ///< MPa at 2e6 cycles
  double lower = -400, upper = 400;  ///< the class window (MPa)
  int classes = 128;
  double scale = 1e-6;  ///< the hot spot's Pa to MPa
};

template <class Scalar = double>
Result<DamageMeter<Scalar>> make_damage_meter() {
  const MeterSpec s;
  auto curve = fatigue::iiw_normal_curve(Scalar(s.fat), fatigue::IiwBeyondKnee::haibach);
  if (!curve) return curve.error();
  auto model = fatigue::DamageModel<Scalar>::create(*curve);
  if (!model) return model.error();
  auto grid = fatigue::ClassGrid<Scalar>::create(Scalar(s.lower), Scalar(s.upper), s.classes);
  if (!grid) return grid.error();
  return DamageMeter<Scalar>::create(*grid, 0, *model);
}

/// The crane's rigid parts and where its joints hold them, in double (add_crane_parts casts
/// them; the C export writes them). Cylinder and rod: slender bodies, frames with z along
/// C -> B, origins at C and B, centres of mass half a length inside.
struct PartsLayout {
  double cylinder_mass = 0, rod_mass = 0;
  Vector3d cylinder_com, rod_com;          ///< in the body frames
  Matrix3d cylinder_inertia, rod_inertia;  ///< about the centres of mass, body axes
  Vector3d cylinder_position, rod_position;
  EulerParameters<double> orientation;  ///< of both: z along C -> B
  Vector3d support_a, support_c;        ///< A's and C's markers on the ground
  /// C's marker on the cylinder: z along the in-plane cross axis, so that the universal joint
  /// with the support's z axis leaves the loop not over-constrained.
  Matrix3d cylinder_c_axes;
  Vector3d boom_b_offset;  ///< B's marker on the boom, from the node at b_node_x
  Vector3d gravity;
};

inline PartsLayout parts_layout(const CraneSpec& spec) {
  PartsLayout l;
  const double lc = spec.cylinder_length, lr = spec.rod_length;
  const double ic = spec.cylinder_mass * lc * lc / 12, ir = spec.rod_mass * lr * lr / 12;
  l.cylinder_mass = spec.cylinder_mass;
  l.rod_mass = spec.rod_mass;
  l.cylinder_com = Vector3d(0, 0, lc / 2);
  l.rod_com = Vector3d(0, 0, -lr / 2);
  l.cylinder_inertia = Vector3d(ic, ic, 1e-3 * ic).asDiagonal().toDenseMatrix();
  l.rod_inertia = Vector3d(ir, ir, 1e-3 * ir).asDiagonal().toDenseMatrix();
  const Vector3d cb = (spec.b - spec.c).normalized();
  const Matrix3d frame = frame_with_z_axis<double>(cb);
  l.cylinder_position = spec.c;
  l.rod_position = spec.b;
  l.orientation = from_rotation_matrix<double>(frame);
  l.support_a = spec.a;
  l.support_c = spec.c;
  l.cylinder_c_axes = frame.transpose() * frame_with_z_axis<double>(Vector3d(cb.y(), -cb.x(), 0));
  l.boom_b_offset = spec.b - Vector3d(spec.b_node_x, 0, 0);
  l.gravity = Vector3d(0, -9.81, 0);
  return l;
}

/// The crane: its model, the state it starts from (static equilibrium at the cycle's start) and
/// the handles a run reads. Scalar: the model's (float for the accuracy study's float runs).
template <class Scalar>
struct BasicCrane {
  CraneSpec spec;
  CraneOptions options;
  Boom boom;
  Detail detail;
  Model<Scalar> model;
  Data<Scalar> initial;
  BodyId boom_body, cylinder, rod;
  JointId joint_a, joint_b;    ///< the boom's hinge on the support and the rod's joint on it
  JointId stroke_driver;       ///< the prescribed stroke (invalid with the hydraulic drive)
  ForceId hydraulic_cylinder;  ///< the valve-driven cylinder (hydraulic drive only)
  OutputRange outputs;         ///< the detail's outputs, in Detail's order
  MeterId hot_spot_meter;
  /// The cylinder length at t = 0 (the stroke is measured from it).
  double initial_length = 0;

  OutputId output(Index row) const { return outputs[static_cast<int>(row)]; }
};
using Crane = BasicCrane<double>;

/// Builds the crane with the work cycle (t, stroke offset): precomputes the detail, puts the
/// crane in static equilibrium at t = 0. With the hydraulic drive the stroke cycle becomes the
/// valve's command cycle (crane_model.cpp). Fails with the first error. Compiled once, in
/// crane_model.cpp, for double and float.
template <class Scalar = double>
Result<BasicCrane<Scalar>> make_crane(const CraneSpec& spec, const CraneOptions& options,
                                      const std::vector<double>& t, const std::vector<double>& ds);
extern template Result<BasicCrane<double>> make_crane<double>(const CraneSpec&, const CraneOptions&,
                                                              const std::vector<double>&,
                                                              const std::vector<double>&);
extern template Result<BasicCrane<float>> make_crane<float>(const CraneSpec&, const CraneOptions&,
                                                            const std::vector<double>&,
                                                            const std::vector<double>&);

/// Boom angle about z (rad) from the boom's orientation.
template <class Scalar>
double boom_angle(const BasicCrane<Scalar>& cr, const Data<Scalar>& d) {
  const Mat3<Scalar> r = rotation_matrix<Scalar>(body_orientation(cr.model, d, cr.boom_body));
  return std::atan2(double(r(1, 0)), double(r(0, 0)));
}

/// The stroke as the bodies have it (cylinder origin at C, rod origin at B).
template <class Scalar>
double stroke(const BasicCrane<Scalar>& cr, const Data<Scalar>& d) {
  return double((body_position(cr.model, d, cr.rod) - body_position(cr.model, d, cr.cylinder))
                    .norm()) -
         cr.initial_length;
}

}  // namespace crane
