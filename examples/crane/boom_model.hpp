// The crane's parameters and its boom: the beam model with the payload and its modal data,
// where the sub-model's ends read it, and the synthetic work cycle. Only the types: making the
// boom (its Craig-Bampton reduction, boom_reduction.hpp) needs the FE and reduction headers,
// which the units that only read a boom need not parse.
#pragma once

#include <cmath>
#include <vector>

#include <flexstress/core/status.hpp>
#include <flexstress/core/types.hpp>
#include <flexstress/fe/beam_line.hpp>
#include <flexstress/fe/mesh.hpp>
#include <flexstress/reduction/modal_body.hpp>
#include <flexstress/reduction/reduction_method.hpp>
#include <flexstress/stress/host_point.hpp>

namespace crane {

using namespace flexstress;

/// Parameters of the crane (SI units). Defaults: the paper's Tables 1 and 2 and DESIGN choices.
struct CraneSpec {
  double boom_length = 4.5;
  int boom_elements = 19;  ///< 20 nodes, plus nodes at B, the sub-model ends and the payload
  double payload_mass = 100.0;
  double payload_x = 2.5;
  double cylinder_mass = 20.0, rod_mass = 10.0;
  double cylinder_length = 0.6, rod_length = 0.6;  ///< slender bodies along their axis
  Vector3d a{0, 0, 0}, b{0.32, -0.125, 0}, c{0, -0.925, 0};
  double b_node_x = 0.32;  ///< B hangs 0.125 m below this boom node (rigid offset)
  double damping_ratio = 0.02;
  int fixed_interface_modes = 4;  ///< 6 static + 4 = 10 deformation modes
  /// How the boom is reduced: Craig-Bampton (the paper's), or Craig-Chang (free-free modes and
  /// inertia-relief attachment modes; bench/accuracy_vs_time compares them).
  reduction::ReductionMethod boom_reduction = reduction::ReductionMethod::craig_bampton;
  double submodel_density = 1.0;  ///< 1792 bricks
  double submodel_x0 = 0.5, submodel_x1 = 0.8;
  /// Longest sub-model brick along x away from the toes (0: the generator's grading, the paper's
  /// sub-model; see fe::RhsAttachmentSpec::max_element_length).
  double submodel_max_element_length = 0.0;
  /// How the sub-model's x1 end is driven: by the boom's displacement (the paper; both ends),
  /// or by the boom's section force there, the x0 end holding it (stress/sub_model.hpp; needs
  /// the end at a boom node; docs/accuracy-vs-time.md compares them with a whole-boom model).
  stress::AttachmentDrive submodel_drive = stress::AttachmentDrive::displacement;
  double wall = 0.004;
  fe::Hex8Formulation formulation = fe::Hex8Formulation::incompatible_modes;
  /// false: the boom has nodes at the sub-model's ends (the paper). true: it does not, and the
  /// ends are read between nodes with `interpolation` (linear as in the paper, or Hermite).
  bool attach_between_nodes = false;
  stress::BoundaryInterpolation interpolation = stress::BoundaryInterpolation::linear;
  /// The hydraulic drive (examples/crane --hydraulic). The paper models its circuit by lumped
  /// fluid but gives no data and drives its comparison by the stroke; these are our choices for
  /// a small crane (docs/crane.md).
  struct Hydraulics {
    double bore = 0.050, rod = 0.028;             ///< piston and rod diameters (m)
    double stroke = 0.4, initial_position = 0.1;  ///< piston travel; position at t = 0 (m)
    double dead_volume = 2e-4;                    ///< per chamber: hoses and clearance (m^3)
    double bulk_modulus = 1.0e9;                  ///< effective, oil with hoses (Pa)
    double supply = 160e5, tank = 2e5;            ///< (Pa)
    double rated_flow = 20.0 / 60000, rated_drop = 35e5;  ///< valve: 20 l/min at 35 bar/edge
    double rod_side_pressure = 20e5;  ///< p2 at t = 0 (p1 then balances the load)
    double command_interval = 0.025;  ///< the command table's spacing (s)
  } hydraulics;
};

/// The boom as a beam model with the payload as a point mass, and its reduction.
struct Boom {
  fe::Mesh mesh;
  fe::BeamLine line;
  reduction::ModalBodyData data;
  Index node_a = -1, node_b = -1, node_x0 = -1, node_x1 = -1;
};

/// Where the sub-model end at x reads the boom: its node, or between the two nodes around x.
inline stress::HostPoint host_point(const Boom& boom, double x,
                                    stress::BoundaryInterpolation kind) {
  const auto& pos = boom.line.positions;
  for (std::size_t i = 0; i + 1 < pos.size(); ++i) {
    if (std::abs(pos[i] - x) < 1e-12) return stress::HostPoint::at_node(boom.line.nodes[i]);
    if (pos[i] < x && x < pos[i + 1])
      return stress::HostPoint::between(boom.line.nodes[i], boom.line.nodes[i + 1],
                                        (x - pos[i]) / (pos[i + 1] - pos[i]), kind);
  }
  return stress::HostPoint::at_node(boom.line.node_at(x));
}

/// The synthetic work cycle (documented in docs/crane.md): stroke offsets from the initial
/// cylinder length at times t. Lift 0.20 m, hold with two operator corrections, lower.
inline void synthetic_cycle(std::vector<double>& t, std::vector<double>& ds) {
  t = {0.0, 0.5, 1.5, 2.5, 3.5, 4.0, 4.6, 5.2, 5.8, 6.5, 7.5, 8.5, 9.5, 10.0, 11.0};
  ds = {0.0, 0.0, 0.04, 0.13, 0.20, 0.20, 0.185, 0.185, 0.195, 0.195, 0.12, 0.03, 0.0, 0.0, 0.0};
}

}  // namespace crane
