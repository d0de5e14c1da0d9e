// Mesh generator: a straight line of beam elements with nodes at requested positions.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/fe/mesh.hpp"

namespace flexstress::fe {

/// A straight beam from `start` to `end`, split into `num_elements` equal elements, with extra
/// nodes at `extra_positions` (distances from `start`, e.g. joint or attachment points).
struct BeamLineSpec {
  Vector3d start = Vector3d::Zero();
  Vector3d end = Vector3d::UnitX();
  int num_elements = 10;
  std::vector<double> extra_positions;
  Index material = 0;
  Index section = 0;
  Vector3d orientation = Vector3d::Zero();
  BeamTheory theory = BeamTheory::euler_bernoulli;
  /// Extra positions closer than this (relative to the length) to a node merge with it.
  double merge_tolerance = 1e-9;
};

/// Nodes of a generated beam line, in order along it, with their distances from the start.
struct BeamLine {
  std::vector<Index> nodes;
  std::vector<double> positions;
  std::vector<Index> elements;

  /// The node at distance s from the start (the nearest one).
  Index node_at(double s) const {
    std::size_t best = 0;
    for (std::size_t i = 1; i < positions.size(); ++i)
      if (std::abs(positions[i] - s) < std::abs(positions[best] - s)) best = i;
    return nodes[best];
  }
};

/// Adds the nodes and beams of `spec` to `mesh`. Positions outside [0, L] are clamped into it.
FLEXSTRESS_PRECOMPUTE
BeamLine add_beam_line(Mesh& mesh, const BeamLineSpec& spec) {
  const Vector3d d = spec.end - spec.start;
  const double length = d.norm();
  std::vector<double> s;
  const int ne = std::max(1, spec.num_elements);
  for (int i = 0; i <= ne; ++i) s.push_back(length * i / ne);
  for (double e : spec.extra_positions) s.push_back(std::clamp(e, 0.0, length));
  std::sort(s.begin(), s.end());
  std::vector<double> merged;
  for (double v : s)
    if (merged.empty() || v - merged.back() > spec.merge_tolerance * length) merged.push_back(v);
  // An extra position that merged into the last node: keep the exact end.
  merged.back() = length;
  BeamLine line;
  line.positions = merged;
  for (double v : merged)
    line.nodes.push_back(mesh.add_node(spec.start + (length > 0 ? v / length : 0.0) * d));
  for (std::size_t i = 0; i + 1 < line.nodes.size(); ++i)
    line.elements.push_back(mesh.add_beam(line.nodes[i], line.nodes[i + 1], spec.material,
                                          spec.section, spec.orientation, spec.theory));
  return line;
}

}  // namespace flexstress::fe
