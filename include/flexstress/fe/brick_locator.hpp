// Locating physical points in a brick mesh: which hex8 element contains a point, and at which
// natural coordinates (the inverse isoparametric map x(xi) = sum_a N_a(xi) x_a = p, solved by
// Newton's method in hex8_natural_coordinates).
//
// A uniform grid over the mesh's bounding box lists, per cell, the bricks whose (slightly
// inflated) axis-aligned bounding boxes overlap it; a query tests only the bricks of the point's
// cell whose boxes contain the point, so it costs O(1) bricks on meshes of similar-sized
// elements. The locator copies the brick coordinates it needs: it does not refer to the mesh
// after build(). Coordinates in the mesh's units (metres), global frame.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/fe/hex8.hpp"
#include "flexstress/fe/mesh.hpp"

namespace flexstress::fe {

/// A point of a brick mesh: the element that contains it and the natural coordinates there
/// (each in [-1, 1]).
struct BrickPoint {
  Index element = -1;
  Vector3d xi = Vector3d::Zero();
};

class BrickLocator {
 public:
  /// Builds the search grid over the bricks of `mesh`. `tolerance` is how far outside
  /// [-1, 1] (in natural coordinates) a point may lie and still count as inside, so that points
  /// on faces are found despite round-off. Fails if the mesh has no bricks, does not validate
  /// or has a non-finite coordinate.
  FLEXSTRESS_PRECOMPUTE
  static Result<BrickLocator> build(const Mesh& mesh, double tolerance = 1e-8);

  /// The brick containing `p` and its natural coordinates (clamped to [-1, 1]). When several
  /// bricks contain p (a point on a shared face or node), the one in whose interior p lies
  /// deepest (smallest max |xi_k|) wins, the lowest element id on a tie. Fails with a message
  /// naming the point if it is not finite or lies outside every brick.
  /// (A template, like the precompute: including this header then compiles no Newton solve.)
  FLEXSTRESS_PRECOMPUTE
  Result<BrickPoint> locate(const Vector3d& p) const;

  /// Bounding box of all bricks (inflated by the tolerance).
  const Eigen::AlignedBox3d& bounds() const { return bounds_; }
  Index num_bricks() const { return static_cast<Index>(coords_.size()); }

 private:
  std::array<int, 3> cell_of(const Vector3d& p) const {
    std::array<int, 3> c{};
    const Vector3d rel = p - bounds_.min();
    const Vector3d extent = bounds_.sizes();
    for (int a = 0; a < 3; ++a) {
      const double f = extent(a) > 0.0 ? rel(a) / extent(a) : 0.0;
      c[static_cast<std::size_t>(a)] = std::clamp(static_cast<int>(f * dims_[a]), 0, dims_[a] - 1);
    }
    return c;
  }
  std::size_t cell_index(int i, int j, int k) const {
    return (static_cast<std::size_t>(k) * static_cast<std::size_t>(dims_[1]) +
            static_cast<std::size_t>(j)) *
               static_cast<std::size_t>(dims_[0]) +
           static_cast<std::size_t>(i);
  }

  double tolerance_ = 1e-8;
  std::vector<Hex8Coordinates> coords_;
  std::vector<Eigen::AlignedBox3d> boxes_;
  Eigen::AlignedBox3d bounds_;
  int dims_[3] = {1, 1, 1};
  std::vector<Index> cell_start_;
  std::vector<Index> cell_items_;
};

#if FLEXSTRESS_PRECOMPUTE_BODIES
template <class>
Result<BrickLocator> BrickLocator::build(const Mesh& mesh, double tolerance) {
  if (Status s = mesh.validate(); !s) return s.error();
  const auto& hexes = mesh.hexes();
  if (hexes.empty())
    return make_error(ErrorCode::invalid_mesh, "brick locator: the mesh has no hex8 elements");
  if (!(tolerance >= 0.0) || !std::isfinite(tolerance))
    return make_error(ErrorCode::invalid_argument, "brick locator: tolerance ", tolerance,
                      " must be non-negative and finite");
  BrickLocator loc;
  loc.tolerance_ = tolerance;
  const std::size_t ne = hexes.size();
  loc.coords_.resize(ne);
  loc.boxes_.resize(ne);
  for (std::size_t e = 0; e < ne; ++e) {
    loc.coords_[e] = hex8_coordinates(mesh, hexes[e]);
    const Vector3d lo = loc.coords_[e].rowwise().minCoeff();
    const Vector3d hi = loc.coords_[e].rowwise().maxCoeff();
    // Inflate by the tolerance times the element size: a point on a face must pass.
    const double pad = (hi - lo).norm() * std::max(tolerance, 1e-12);
    loc.boxes_[e] = Eigen::AlignedBox3d(lo - Vector3d::Constant(pad), hi + Vector3d::Constant(pad));
    loc.bounds_.extend(loc.boxes_[e]);
  }
  // About one cell per brick, cubic cells, at most 256 per axis.
  const Vector3d extent = loc.bounds_.sizes();
  const double volume = std::max(extent.prod(), 1e-300);
  const double cell = std::cbrt(volume / static_cast<double>(ne));
  for (int a = 0; a < 3; ++a)
    loc.dims_[a] = std::clamp(static_cast<int>(std::ceil(extent(a) / cell)), 1, 256);
  const std::size_t ncells = static_cast<std::size_t>(loc.dims_[0]) *
                             static_cast<std::size_t>(loc.dims_[1]) *
                             static_cast<std::size_t>(loc.dims_[2]);
  // Two passes (count, fill): compressed rows of brick ids per cell.
  loc.cell_start_.assign(ncells + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<Index> fill(loc.cell_start_.begin(), loc.cell_start_.end() - 1);
    if (pass == 1) loc.cell_items_.resize(static_cast<std::size_t>(loc.cell_start_.back()));
    for (std::size_t e = 0; e < ne; ++e) {
      const auto lo = loc.cell_of(loc.boxes_[e].min()), hi = loc.cell_of(loc.boxes_[e].max());
      for (int i = lo[0]; i <= hi[0]; ++i)
        for (int j = lo[1]; j <= hi[1]; ++j)
          for (int k = lo[2]; k <= hi[2]; ++k) {
            const std::size_t c = loc.cell_index(i, j, k);
            if (pass == 0)
              ++loc.cell_start_[c + 1];
            else
              loc.cell_items_[static_cast<std::size_t>(fill[c]++)] = static_cast<Index>(e);
          }
    }
    if (pass == 0)
      for (std::size_t c = 0; c < ncells; ++c) loc.cell_start_[c + 1] += loc.cell_start_[c];
  }
  return loc;
}

template <class>
Result<BrickPoint> BrickLocator::locate(const Vector3d& p) const {
  if (!p.allFinite())
    return make_error(ErrorCode::invalid_argument, "brick locator: point (", p.x(), ", ", p.y(),
                      ", ", p.z(), ") is not finite");
  BrickPoint best;
  double best_excess = std::numeric_limits<double>::infinity();
  if (bounds_.contains(p)) {
    const auto c = cell_of(p);
    const std::size_t cell = cell_index(c[0], c[1], c[2]);
    for (Index k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
      const Index e = cell_items_[static_cast<std::size_t>(k)];
      if (!boxes_[static_cast<std::size_t>(e)].contains(p)) continue;
      auto xi = hex8_natural_coordinates(coords_[static_cast<std::size_t>(e)], p, e);
      if (!xi || !hex8_contains(*xi, tolerance_)) continue;
      const double excess = xi->cwiseAbs().maxCoeff();
      if (excess < best_excess || (excess == best_excess && e < best.element)) {
        best_excess = excess;
        best.element = e;
        best.xi = xi->cwiseMax(-1.0).cwiseMin(1.0);
      }
    }
  }
  if (best.element >= 0) return best;
  // Not found: name the nearest brick (by centroid) to help the caller.
  Index nearest = 0;
  double nearest_d = std::numeric_limits<double>::infinity();
  for (std::size_t e = 0; e < coords_.size(); ++e) {
    const double d = (coords_[e].rowwise().mean() - p).norm();
    if (d < nearest_d) {
      nearest_d = d;
      nearest = static_cast<Index>(e);
    }
  }
  return make_error(ErrorCode::invalid_argument, "point (", p.x(), ", ", p.y(), ", ", p.z(),
                    ") lies outside the brick mesh (no hex8 element contains it; the nearest "
                    "element by centroid is ",
                    nearest, " at distance ", nearest_d, ")");
}
#endif

}  // namespace flexstress::fe

// This header's precompute entry points (core/precompute.hpp).
#define FLEXSTRESS_PRECOMPUTE_FE_BRICK_LOCATOR(X)                                    \
  X(5, Result<fe::BrickLocator>, fe::BrickLocator::build, (const fe::Mesh&, double)) \
  X(5, Result<fe::BrickPoint>, fe::BrickLocator::locate, (const Vector3d&) const)
namespace flexstress {
FLEXSTRESS_PRECOMPUTE_EXTERN(FLEXSTRESS_PRECOMPUTE_FE_BRICK_LOCATOR)
}  // namespace flexstress
