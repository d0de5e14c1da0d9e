// Mesh generator: a segment of a rectangular hollow section (RHS) with a transverse plate (rib)
// welded on the top flange by double-sided fillet welds: the sub-model of the paper's welded
// detail D (Rantalainen, Mikkola, Bjork 2013, sec. 5, Fig. 6-7).
//
// Frame and units: metres, global axes; x along the segment, y up (section height), z across
// (section width); the section centre is on the x axis, so the top flange's outer surface is at
// y = height / 2. Hex8 only, no collapsed elements:
//  - the tube is a ring of quads around the section (n_through layers through the wall, sharp
//    corners: each corner's t x t square is shared by the first flange and web elements, which
//    are trapezoids) extruded along an x-grid that is uniform (element length 0.4 t / density)
//    within 1.5 t of each weld toe (IIW type-a fine mesh at density >= 1: Hobbacher, IIW
//    recommendations, sec. 2.2.3) and grows geometrically towards the segment ends;
//  - the plate and the two weld triangles are meshed in the x-y profile and extruded across the
//    attachment width through the flange's own z-stations, so that plate, welds and flange
//    share nodes (a fully fused joint, no root gap). Each weld triangle is split into three
//    quads (corner, edge midpoints, centroid), each subdivided m x m; the plate is graded from
//    the weld roots towards its middle and from the weld-leg height to its top.
// A single `density` multiplies every division count: density 1 gives about 1800 bricks (the
// paper's sub-model has 1800), 0.55 about 500, 1.5 about 8000 (counts are tested).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/fe/hex8.hpp"
#include "flexstress/fe/material.hpp"
#include "flexstress/fe/mesh.hpp"

namespace flexstress::fe {

/// Geometry and meshing parameters (SI units). Defaults: the crane boom's 150 x 100 x 4 RHS
/// and detail D (paper, Table 1-2): a 30 mm x 30 mm rib across the full flange width at x = 0.65,
/// 5 mm fillet welds, so the weld toes on the flange are at x = 0.63 and 0.67.
struct RhsAttachmentSpec {
  double height = 0.150;             ///< outer section height (y)
  double width = 0.100;              ///< outer section width (z)
  double wall = 0.004;               ///< wall thickness t
  double x0 = 0.50;                  ///< segment start
  double x1 = 0.80;                  ///< segment end
  double attachment_center = 0.65;   ///< x of the plate's mid-plane
  double attachment_length = 0.030;  ///< plate extent along x (its thickness)
  double attachment_height = 0.030;  ///< plate height above the flange surface
  double attachment_width = 0.100;   ///< plate extent along z, centred; <= width
  double weld_leg = 0.005;           ///< fillet weld leg (45 degree welds)
  double density = 1.0;              ///< multiplies every division count
  /// Longest element along x away from the toes (0: no cap; the graded zones then grow in a
  /// fixed number of steps). A long segment, such as a whole boom, needs one.
  double max_element_length = 0.0;
  /// Positions that must be x-stations, e.g. where loads or supports are tied to a section
  /// (at least 2 t outside the weld toes). The graded zone ends at the first one on each side;
  /// beyond it the steps are uniform.
  std::vector<double> extra_x_stations;
  Material material = steel();
  Hex8Formulation formulation = Hex8Formulation::incompatible_modes;
};

/// The generated mesh and the node sets a sub-model needs.
struct RhsAttachmentMesh {
  Mesh mesh;
  RhsAttachmentSpec spec;  ///< the parameters used
  Index material = 0;
  std::vector<Index> end_section_x0;           ///< all nodes of the cross-section x = x0
  std::vector<Index> end_section_x1;           ///< all nodes of the cross-section x = x1
  double flange_surface_y = 0.0;               ///< height / 2
  double weld_toe_x = 0.0;                     ///< toe on the +x side (0.67 by default)
  double opposite_weld_toe_x = 0.0;            ///< toe on the -x side (0.63)
  std::vector<Index> weld_toe_nodes;           ///< flange surface nodes at weld_toe_x, by z
  std::vector<Index> opposite_weld_toe_nodes;  ///< the same at opposite_weld_toe_x
  /// Flange surface nodes on the centre line z = 0 from the toe towards +x (the toe first),
  /// their coordinates and distances from the toe (the hot-spot read-out path).
  std::vector<Index> centerline_nodes;
  std::vector<Vector3d> centerline_points;
  std::vector<double> centerline_distances;
  std::vector<double> x_stations;    ///< x-grid of the tube
  std::vector<double> top_flange_z;  ///< z of the top flange's surface nodes
  int n_around = 0, n_through = 0;   ///< ring divisions
  Index num_tube_bricks = 0, num_attachment_bricks = 0;

  /// All tube nodes of the cross-section at x-station x (empty if x is not a station).
  std::vector<Index> section_nodes(double x) const {
    std::vector<Index> nodes;
    const auto per_station = static_cast<Index>(n_around) * (n_through + 1);
    for (std::size_t ix = 0; ix < x_stations.size(); ++ix)
      if (std::abs(x_stations[ix] - x) <= 1e-9 * spec.height)
        for (Index k = 0; k < per_station; ++k)
          nodes.push_back(static_cast<Index>(ix) * per_station + k);
    return nodes;
  }
};

namespace detail {

// Positions 0 < ... < length of `count` steps growing geometrically from `first` (ratio >= 1
// found by bisection); uniform steps when `first` * count already covers the length.
FLEXSTRESS_PRECOMPUTE
std::vector<double> geometric_positions(double length, double first, int count) {
  std::vector<double> s{0.0};
  count = std::max(count, 1);
  if (first * count >= length) {
    for (int k = 1; k <= count; ++k) s.push_back(length * k / count);
    return s;
  }
  auto total = [&](double r) { return first * (std::pow(r, count) - 1.0) / (r - 1.0); };
  double lo = 1.0 + 1e-12, hi = 2.0;
  while (total(hi) < length) hi *= 2.0;
  for (int it = 0; it < 200; ++it) (total(0.5 * (lo + hi)) < length ? lo : hi) = 0.5 * (lo + hi);
  const double r = 0.5 * (lo + hi);
  for (int k = 1; k < count; ++k) s.push_back(first * (std::pow(r, k) - 1.0) / (r - 1.0));
  s.push_back(length);
  return s;
}

// Zone from a weld toe outwards: uniform steps h0 over at least fine_length, then
// geometric growth in n_grow steps to the zone's end, or in as many more steps as keep the last
// one at most `cap` (cap > 0).
FLEXSTRESS_PRECOMPUTE
std::vector<double> toe_zone_positions(double length, double h0, double fine_length, int n_grow,
                                       double cap = 0.0) {
  const int n_fine = static_cast<int>(std::ceil(fine_length / h0 - 1e-9));
  if (n_fine * h0 >= length - 0.5 * h0)
    return geometric_positions(length, length, static_cast<int>(std::ceil(length / h0)));
  std::vector<double> s;
  for (int k = 0; k <= n_fine; ++k) s.push_back(k * h0);
  std::vector<double> rest = geometric_positions(length - n_fine * h0, h0, n_grow);
  while (cap > 0.0 && rest.size() >= 2 && rest[rest.size() - 1] - rest[rest.size() - 2] > cap)
    rest = geometric_positions(length - n_fine * h0, h0, static_cast<int>(rest.size()));
  for (std::size_t k = 1; k < rest.size(); ++k) s.push_back(n_fine * h0 + rest[k]);
  return s;
}

// A whole outer zone from a toe: the toe zone up to the first stop (distances from the toe,
// ascending, inside (0, length)) or the zone's end, then uniform steps between the stops, no
// longer than `cap` (cap > 0) or than the toe zone's last step.
FLEXSTRESS_PRECOMPUTE
std::vector<double> outer_zone_positions(double length, double h0, double fine_length, int n_grow,
                                         double cap, const std::vector<double>& stops) {
  const double first_end = stops.empty() ? length : stops.front();
  std::vector<double> s = toe_zone_positions(first_end, h0, fine_length, n_grow, cap);
  const double last_step = s.size() >= 2 ? s[s.size() - 1] - s[s.size() - 2] : first_end;
  const double step = cap > 0.0 ? cap : last_step;
  if (stops.empty()) return s;
  std::vector<double> ends(stops.begin() + 1, stops.end());
  ends.push_back(length);
  double from = first_end;
  for (double to : ends) {
    const int n = std::max(1, static_cast<int>(std::ceil((to - from) / step - 1e-9)));
    for (int k = 1; k <= n; ++k) s.push_back(from + (to - from) * k / n);
    from = to;
  }
  return s;
}

// 2D points (x-y profile) with merging of coincident points (shared edges of sub-meshes).
class ProfilePoints {
 public:
  explicit ProfilePoints(double tolerance) : tol_(tolerance) {}
  Index add(const Eigen::Vector2d& p) {
    const long long kx = std::llround(p.x() / tol_), ky = std::llround(p.y() / tol_);
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy) {
        auto it = index_.find({kx + dx, ky + dy});
        if (it != index_.end() &&
            (points_[static_cast<std::size_t>(it->second)] - p).norm() <= 2 * tol_)
          return it->second;
      }
    points_.push_back(p);
    const auto id = static_cast<Index>(points_.size()) - 1;
    index_[{kx, ky}] = id;
    return id;
  }
  const std::vector<Eigen::Vector2d>& points() const { return points_; }

 private:
  double tol_;
  std::vector<Eigen::Vector2d> points_;
  std::map<std::pair<long long, long long>, Index> index_;
};

// Adds the m x m bilinear subdivision of a convex quad (corners counter-clockwise or not).
FLEXSTRESS_PRECOMPUTE
void add_subdivided_quad(ProfilePoints& pts, std::vector<std::array<Index, 4>>& quads,
                         const std::array<Eigen::Vector2d, 4>& c, int m) {
  auto at = [&](double s, double t) -> Eigen::Vector2d {
    return (1 - s) * (1 - t) * c[0] + s * (1 - t) * c[1] + s * t * c[2] + (1 - s) * t * c[3];
  };
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      const double s0 = double(i) / m, s1 = double(i + 1) / m;
      const double t0 = double(j) / m, t1 = double(j + 1) / m;
      quads.push_back(
          {pts.add(at(s0, t0)), pts.add(at(s1, t0)), pts.add(at(s1, t1)), pts.add(at(s0, t1))});
    }
}

// Twice the signed area of a quad in the plane of its two coordinates.
FLEXSTRESS_PRECOMPUTE
double signed_area2(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                    const Eigen::Vector2d& d) {
  auto cross = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
    return p.x() * q.y() - p.y() * q.x();
  };
  return cross(a, b) + cross(b, c) + cross(c, d) + cross(d, a);
}

inline int scaled_count(double base, double density, int minimum) {
  return std::max(minimum, static_cast<int>(std::lround(base * density)));
}

}  // namespace detail

/// Checks the parameters: everything finite and positive, 2 t < min(height, width), the
/// attachment no wider than the flange (and, if narrower, at least 1.5 t clear of each web so
/// that the flange's z-stations stay off the corners), the weld leg below the plate height, the
/// weld toes at least 2 t inside the segment, 0 < density <= 4.
FLEXSTRESS_PRECOMPUTE
Status validate(const RhsAttachmentSpec& s) {
  const std::pair<const char*, double> values[] = {{"height", s.height},
                                                   {"width", s.width},
                                                   {"wall", s.wall},
                                                   {"attachment_length", s.attachment_length},
                                                   {"attachment_height", s.attachment_height},
                                                   {"attachment_width", s.attachment_width},
                                                   {"weld_leg", s.weld_leg},
                                                   {"density", s.density}};
  for (const auto& [name, v] : values)
    if (!std::isfinite(v) || !(v > 0.0))
      return make_error(ErrorCode::invalid_argument, "RHS attachment mesh: ", name,
                        " must be positive and finite, got ", v);
  for (const auto& [name, v] : {std::pair<const char*, double>{"x0", s.x0},
                                {"x1", s.x1},
                                {"attachment_center", s.attachment_center}})
    if (!std::isfinite(v))
      return make_error(ErrorCode::invalid_argument, "RHS attachment mesh: ", name,
                        " is not finite");
  if (Status m = validate(s.material, "RHS attachment mesh material"); !m) return m;
  if (!(2.0 * s.wall < std::min(s.height, s.width)))
    return make_error(ErrorCode::invalid_argument, "RHS attachment mesh: wall thickness ", s.wall,
                      " must be less than half the section's height ", s.height, " and width ",
                      s.width);
  if (s.attachment_width > s.width * (1.0 + 1e-12))
    return make_error(ErrorCode::invalid_argument, "RHS attachment mesh: attachment width ",
                      s.attachment_width, " is wider than the flange (section width ", s.width,
                      ")");
  const bool full = s.attachment_width >= s.width * (1.0 - 1e-12);
  if (!full && 0.5 * (s.width - s.attachment_width) < 1.5 * s.wall)
    return make_error(ErrorCode::invalid_argument, "RHS attachment mesh: attachment width ",
                      s.attachment_width, " leaves ", 0.5 * (s.width - s.attachment_width),
                      " to each web, less than 1.5 t = ", 1.5 * s.wall,
                      "; use the full flange width or a narrower attachment");
  if (!(s.weld_leg < s.attachment_height))
    return make_error(ErrorCode::invalid_argument, "RHS attachment mesh: weld leg ", s.weld_leg,
                      " must be less than the attachment height ", s.attachment_height);
  const double toe_lo = s.attachment_center - 0.5 * s.attachment_length - s.weld_leg;
  const double toe_hi = s.attachment_center + 0.5 * s.attachment_length + s.weld_leg;
  if (!(toe_lo - s.x0 >= 2.0 * s.wall) || !(s.x1 - toe_hi >= 2.0 * s.wall))
    return make_error(ErrorCode::invalid_argument,
                      "RHS attachment mesh: the weld toes at x = ", toe_lo, " and ", toe_hi,
                      " must lie at least 2 t inside the segment [", s.x0, ", ", s.x1, "]");
  if (!std::isfinite(s.max_element_length) || s.max_element_length < 0.0)
    return make_error(ErrorCode::invalid_argument, "RHS attachment mesh: max_element_length ",
                      s.max_element_length, " must be finite and >= 0 (0: no cap)");
  if (s.max_element_length > 0.0 && (s.x1 - s.x0) / s.max_element_length > 1e5)
    return make_error(ErrorCode::invalid_argument, "RHS attachment mesh: max_element_length ",
                      s.max_element_length, " makes over 100000 x-stations on [", s.x0, ", ", s.x1,
                      "]");
  for (std::size_t k = 0; k < s.extra_x_stations.size(); ++k) {
    const double x = s.extra_x_stations[k];
    if (!std::isfinite(x) || x < s.x0 || x > s.x1)
      return make_error(ErrorCode::invalid_argument, "RHS attachment mesh: extra x-station ", k,
                        " at x = ", x, " is outside the segment [", s.x0, ", ", s.x1, "]");
    if (x > toe_lo - 2.0 * s.wall && x < toe_hi + 2.0 * s.wall)
      return make_error(ErrorCode::invalid_argument, "RHS attachment mesh: extra x-station ", k,
                        " at x = ", x, " is within 2 t of the weld toes at x = ", toe_lo, " and ",
                        toe_hi, " (the fine zone there has its own stations)");
  }
  if (!(s.density <= 4.0))
    return make_error(ErrorCode::invalid_argument, "RHS attachment mesh: density ", s.density,
                      " is above 4 (over 100000 bricks); refine locally instead");
  return Status::success();
}

/// Generates the RHS segment with the welded attachment. Fails with a message naming the bad
/// parameter, or (should the parameters still produce one) the first brick with a
/// non-positive Jacobian.
FLEXSTRESS_PRECOMPUTE
Result<RhsAttachmentMesh> make_rhs_attachment_mesh(const RhsAttachmentSpec& spec = {})
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  if (Status s = validate(spec); !s) return s.error();
  using detail::scaled_count;
  using V2 = Eigen::Vector2d;
  const double h = spec.height, b = spec.width, t = spec.wall, d = spec.density;
  const double leg = spec.weld_leg, yf = 0.5 * h;
  const double xl = spec.attachment_center - 0.5 * spec.attachment_length;
  const double xr = spec.attachment_center + 0.5 * spec.attachment_length;
  const bool full_width = spec.attachment_width >= b * (1.0 - 1e-12);

  // Division counts (density 1: 8 across each flange, 8 per web, 1 through the wall, 2 x 2 per
  // weld quad, 8 plate columns, 3 plate rows above the weld, 6 graded steps per outer zone).
  const int n_t = scaled_count(1.0, d, 1);
  const int n_f = 2 * scaled_count(4.0, d, 1);
  const int n_w = scaled_count(8.0, d, 2);
  const int m = scaled_count(2.0, d, 1);
  const int n_px = 2 * scaled_count(4.0, d, 1);
  const int n_py = scaled_count(3.0, d, 1);
  const int n_grow = scaled_count(6.0, d, 1);
  const double h0 = 0.4 * t / d, foot_step = leg / (2 * m);
  if (!((b - t) / n_f > 0.5 * t) || !((h - t) / n_w > 0.5 * t))
    return make_error(ErrorCode::invalid_argument, "RHS attachment mesh: density ", d,
                      " makes the flange or web elements narrower than half the wall thickness ", t,
                      " (the corner elements would invert); lower the density");

  RhsAttachmentMesh out;
  out.spec = spec;
  out.flange_surface_y = yf;
  out.weld_toe_x = xr + leg;
  out.opposite_weld_toe_x = xl - leg;

  // x-stations: outer zone, weld foot, plate, weld foot, outer zone.
  std::vector<double>& xs = out.x_stations;
  // Extra stations as distances from the toe on each side, nearest first (the segment's ends
  // are stations anyway).
  std::vector<double> stops_left, stops_right;
  for (double x : spec.extra_x_stations) {
    if (x > spec.x0 && x < out.opposite_weld_toe_x)
      stops_left.push_back(out.opposite_weld_toe_x - x);
    if (x > out.weld_toe_x && x < spec.x1) stops_right.push_back(x - out.weld_toe_x);
  }
  for (auto* stops : {&stops_left, &stops_right}) {
    std::sort(stops->begin(), stops->end());
    stops->erase(std::unique(stops->begin(), stops->end()), stops->end());
  }
  const double cap = spec.max_element_length;
  const auto left = detail::outer_zone_positions(out.opposite_weld_toe_x - spec.x0, h0, 1.5 * t,
                                                 n_grow, cap, stops_left);
  for (std::size_t k = left.size(); k-- > 1;) xs.push_back(out.opposite_weld_toe_x - left[k]);
  const auto ix_toe_left = static_cast<Index>(xs.size());
  for (int k = 0; k < 2 * m; ++k) xs.push_back(out.opposite_weld_toe_x + k * foot_step);
  const auto half = detail::geometric_positions(0.5 * spec.attachment_length, foot_step, n_px / 2);
  for (std::size_t k = 0; k + 1 < half.size(); ++k) xs.push_back(xl + half[k]);
  for (std::size_t k = half.size(); k-- > 1;) xs.push_back(xr - half[k]);
  for (int k = 0; k < 2 * m; ++k) xs.push_back(xr + k * foot_step);
  const auto ix_toe = static_cast<Index>(xs.size());
  for (double s : detail::outer_zone_positions(spec.x1 - out.weld_toe_x, h0, 1.5 * t, n_grow, cap,
                                               stops_right))
    xs.push_back(out.weld_toe_x + s);
  xs.front() = spec.x0;
  xs.back() = spec.x1;
  const auto nx = static_cast<Index>(xs.size());

  // Ring stations around the section in (y, z): inner and outer wall points. Top flange first
  // (corner to corner, z ascending), then the +z web, the bottom flange, the -z web.
  std::vector<std::pair<V2, V2>> ring;
  const double hi_y = yf - t, hi_z = 0.5 * b - t;
  std::vector<double> top_mid;  // mid-line z of the top flange's interior stations
  if (full_width) {
    for (int k = 1; k < n_f; ++k) top_mid.push_back(-0.5 * (b - t) + (b - t) * k / n_f);
  } else {
    const double side = 0.5 * (b - t) - 0.5 * spec.attachment_width;
    const int n_side = std::max(1, static_cast<int>(std::lround(n_f * side / (b - t))));
    const int n_mid =
        2 * std::max(1, static_cast<int>(std::lround(0.5 * n_f * spec.attachment_width / (b - t))));
    for (int k = 1; k <= n_side; ++k) top_mid.push_back(-0.5 * (b - t) + side * k / n_side);
    for (int k = 1; k <= n_mid; ++k)
      top_mid.push_back(-0.5 * spec.attachment_width + spec.attachment_width * k / n_mid);
    for (int k = 1; k < n_side; ++k)
      top_mid.push_back(0.5 * spec.attachment_width + side * k / n_side);
  }
  top_mid[top_mid.size() / 2] = 0.0;  // the centre line exactly (the count is odd)
  ring.push_back({V2(hi_y, -hi_z), V2(yf, -0.5 * b)});
  for (double z : top_mid) ring.push_back({V2(hi_y, z), V2(yf, z)});
  ring.push_back({V2(hi_y, hi_z), V2(yf, 0.5 * b)});
  for (int k = 1; k < n_w; ++k) {
    const double y = 0.5 * (h - t) - (h - t) * k / n_w;
    ring.push_back({V2(y, hi_z), V2(y, 0.5 * b)});
  }
  ring.push_back({V2(-hi_y, hi_z), V2(-yf, 0.5 * b)});
  for (int k = 1; k < n_f; ++k) {
    const double z = 0.5 * (b - t) - (b - t) * k / n_f;
    ring.push_back({V2(-hi_y, z), V2(-yf, z)});
  }
  ring.push_back({V2(-hi_y, -hi_z), V2(-yf, -0.5 * b)});
  for (int k = 1; k < n_w; ++k) {
    const double y = -0.5 * (h - t) + (h - t) * k / n_w;
    ring.push_back({V2(y, -hi_z), V2(y, -0.5 * b)});
  }
  const auto na = static_cast<Index>(ring.size());
  const auto n_top = static_cast<Index>(top_mid.size()) + 1;  // top flange elements
  out.n_around = static_cast<int>(na);
  out.n_through = n_t;
  for (Index k = 0; k <= n_top; ++k)
    out.top_flange_z.push_back(ring[static_cast<std::size_t>(k)].second.y());

  // Tube nodes and bricks.
  Mesh& mesh = out.mesh;
  out.material = mesh.add_material(spec.material);
  auto tube_node = [&](Index ix, Index s, Index j) { return (ix * na + s % na) * (n_t + 1) + j; };
  for (Index ix = 0; ix < nx; ++ix)
    for (Index s = 0; s < na; ++s)
      for (Index j = 0; j <= n_t; ++j) {
        const auto& [in, ou] = ring[static_cast<std::size_t>(s)];
        const V2 p = in + (double(j) / n_t) * (ou - in);
        mesh.add_node(Vector3d(xs[static_cast<std::size_t>(ix)], p.x(), p.y()));
      }
  auto add_brick = [&](std::array<Index, 4> q, std::array<Index, 4> r, bool flip) {
    if (flip) {
      std::swap(q[1], q[3]);
      std::swap(r[1], r[3]);
    }
    mesh.add_hex8({q[0], q[1], q[2], q[3], r[0], r[1], r[2], r[3]}, out.material, spec.formulation);
  };
  for (Index s = 0; s < na; ++s)
    for (Index j = 0; j < n_t; ++j) {
      // Orientation in (y, z): y x z = +x, the extrusion direction.
      auto yz = [&](Index node) { return V2(mesh.node(node).y(), mesh.node(node).z()); };
      const std::array<Index, 4> q0{tube_node(0, s, j), tube_node(0, s + 1, j),
                                    tube_node(0, s + 1, j + 1), tube_node(0, s, j + 1)};
      const bool flip = detail::signed_area2(yz(q0[0]), yz(q0[1]), yz(q0[2]), yz(q0[3])) < 0.0;
      for (Index ix = 0; ix + 1 < nx; ++ix)
        add_brick({tube_node(ix, s, j), tube_node(ix, s + 1, j), tube_node(ix, s + 1, j + 1),
                   tube_node(ix, s, j + 1)},
                  {tube_node(ix + 1, s, j), tube_node(ix + 1, s + 1, j),
                   tube_node(ix + 1, s + 1, j + 1), tube_node(ix + 1, s, j + 1)},
                  flip);
    }
  out.num_tube_bricks = static_cast<Index>(mesh.hexes().size());

  // Attachment profile in (x, y): plate block, then the two weld triangles.
  detail::ProfilePoints pts(1e-9 * h);
  std::vector<std::array<Index, 4>> quads;
  std::vector<double> py;  // plate rows above the flange
  for (int k = 0; k <= 2 * m; ++k) py.push_back(k * foot_step);
  for (double s : detail::geometric_positions(spec.attachment_height - leg, foot_step, n_py))
    if (s > 0.0) py.push_back(leg + s);
  const auto ix_l = ix_toe_left + 2 * m, ix_r = ix_toe - 2 * m;
  for (Index i = ix_l; i < ix_r; ++i)
    for (std::size_t j = 0; j + 1 < py.size(); ++j) {
      const double xa = xs[static_cast<std::size_t>(i)], xb = xs[static_cast<std::size_t>(i + 1)];
      quads.push_back({pts.add(V2(xa, yf + py[j])), pts.add(V2(xb, yf + py[j])),
                       pts.add(V2(xb, yf + py[j + 1])), pts.add(V2(xa, yf + py[j + 1]))});
    }
  for (double side : {-1.0, 1.0}) {
    const double root_x = side > 0 ? xr : xl;
    const V2 toe(root_x + side * leg, yf), root(root_x, yf), top(root_x, yf + leg);
    const V2 c = (toe + root + top) / 3.0;
    const V2 m_tr = 0.5 * (toe + root), m_rw = 0.5 * (root + top), m_tw = 0.5 * (toe + top);
    detail::add_subdivided_quad(pts, quads, {toe, m_tr, c, m_tw}, m);
    detail::add_subdivided_quad(pts, quads, {root, m_rw, c, m_tr}, m);
    detail::add_subdivided_quad(pts, quads, {top, m_tw, c, m_rw}, m);
  }
  // Profile points on the flange surface are tube nodes (matched to an x-station); the others
  // get one node per attachment z-station.
  const std::vector<V2>& pp = pts.points();
  std::vector<Index> station_of(pp.size(), -1);
  for (std::size_t p = 0; p < pp.size(); ++p) {
    if (std::abs(pp[p].y() - yf) > 1e-9 * h) continue;
    const auto it = std::lower_bound(xs.begin(), xs.end(), pp[p].x() - 1e-9 * h);
    if (it == xs.end() || std::abs(*it - pp[p].x()) > 1e-9 * h)
      return make_error(ErrorCode::invalid_mesh,
                        "RHS attachment mesh: internal error, profile "
                        "point x = ",
                        pp[p].x(), " on the flange matches no x-station");
    station_of[p] = static_cast<Index>(it - xs.begin());
  }
  std::vector<Index> zk;  // top-flange ring stations the attachment spans
  for (Index k = 0; k <= n_top; ++k)
    if (std::abs(out.top_flange_z[static_cast<std::size_t>(k)]) <=
        0.5 * spec.attachment_width * (1 + 1e-12))
      zk.push_back(k);
  std::vector<Index> first_node(pp.size(), -1);
  for (std::size_t p = 0; p < pp.size(); ++p) {
    if (station_of[p] >= 0) continue;
    first_node[p] = mesh.num_nodes();
    for (Index k : zk)
      mesh.add_node(Vector3d(pp[p].x(), pp[p].y(), out.top_flange_z[static_cast<std::size_t>(k)]));
  }
  auto profile_node = [&](Index p, std::size_t kz) {
    const auto pu = static_cast<std::size_t>(p);
    return station_of[pu] >= 0 ? tube_node(station_of[pu], zk[kz], n_t)
                               : first_node[pu] + static_cast<Index>(kz);
  };
  for (auto q : quads) {
    // Counter-clockwise in (x, y), so that x cross y = +z is the extrusion direction.
    if (detail::signed_area2(pp[static_cast<std::size_t>(q[0])], pp[static_cast<std::size_t>(q[1])],
                             pp[static_cast<std::size_t>(q[2])],
                             pp[static_cast<std::size_t>(q[3])]) < 0.0)
      std::swap(q[1], q[3]);
    for (std::size_t kz = 0; kz + 1 < zk.size(); ++kz)
      add_brick({profile_node(q[0], kz), profile_node(q[1], kz), profile_node(q[2], kz),
                 profile_node(q[3], kz)},
                {profile_node(q[0], kz + 1), profile_node(q[1], kz + 1), profile_node(q[2], kz + 1),
                 profile_node(q[3], kz + 1)},
                false);
  }
  out.num_attachment_bricks = static_cast<Index>(mesh.hexes().size()) - out.num_tube_bricks;

  // Node sets.
  for (Index s = 0; s < na; ++s)
    for (Index j = 0; j <= n_t; ++j) {
      out.end_section_x0.push_back(tube_node(0, s, j));
      out.end_section_x1.push_back(tube_node(nx - 1, s, j));
    }
  for (Index k = 0; k <= n_top; ++k) {
    out.weld_toe_nodes.push_back(tube_node(ix_toe, k, n_t));
    out.opposite_weld_toe_nodes.push_back(tube_node(ix_toe_left, k, n_t));
  }
  const Index centre = static_cast<Index>(top_mid.size() / 2) + 1;
  for (Index ix = ix_toe; ix < nx; ++ix) {
    const Index n = tube_node(ix, centre, n_t);
    out.centerline_nodes.push_back(n);
    out.centerline_points.push_back(mesh.node(n));
    out.centerline_distances.push_back(mesh.node(n).x() - out.weld_toe_x);
  }
  // Guard: every brick has a positive Jacobian at its centre and Gauss points.
  for (std::size_t e = 0; e < mesh.hexes().size(); ++e)
    if (auto k = hex8_kinematics(hex8_coordinates(mesh, mesh.hexes()[e]), static_cast<Index>(e));
        !k)
      return make_error(ErrorCode::degenerate_element, "RHS attachment mesh: ", k.error().message);
  return out;
}
#else
    ;
#endif

}  // namespace flexstress::fe

// This header's precompute entry points (core/precompute.hpp).
#define FLEXSTRESS_PRECOMPUTE_FE_RHS_ATTACHMENT_MESH(X) \
  X(4, Result<fe::RhsAttachmentMesh>, fe::make_rhs_attachment_mesh, (const fe::RhsAttachmentSpec&))
namespace flexstress {
FLEXSTRESS_PRECOMPUTE_EXTERN(FLEXSTRESS_PRECOMPUTE_FE_RHS_ATTACHMENT_MESH)
}  // namespace flexstress
