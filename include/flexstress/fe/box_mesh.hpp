// A structured block of hex8 bricks: an axis-aligned box divided into nx x ny x nz bricks, the
// first brick mesh most tests and studies need (columns, plates, cantilevers of bricks).
#pragma once

#include <array>

#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
#include "flexstress/fe/mesh.hpp"

namespace flexstress::fe {

struct BoxMeshSpec {
  Vector3d origin = Vector3d::Zero();  ///< the corner with the smallest coordinates
  Vector3d size = Vector3d::Ones();    ///< edge lengths along x, y, z
  std::array<int, 3> divisions{1, 1, 1};
  Index material = 0;
};

/// The nodes of a generated box: node(i, j, k) for 0 <= i <= nx, ... (lattice indices).
struct BoxMesh {
  Index first_node = 0;
  std::array<int, 3> divisions{1, 1, 1};
  Index node(int i, int j, int k) const {
    return first_node + static_cast<Index>((k * (divisions[1] + 1) + j) * (divisions[0] + 1) + i);
  }
};

/// Adds the box's nodes and bricks to `mesh` (node order of Hex8Element). Fails for
/// non-positive sizes or divisions, naming them.
inline Result<BoxMesh> add_box_mesh(Mesh& mesh, const BoxMeshSpec& spec) {
  for (int a = 0; a < 3; ++a)
    if (spec.divisions[static_cast<std::size_t>(a)] < 1 || !(spec.size(a) > 0.0))
      return make_error(ErrorCode::invalid_argument, "box mesh: axis ", a, " has size ",
                        spec.size(a), " and ", spec.divisions[static_cast<std::size_t>(a)],
                        " divisions (need a positive size and at least one division)");
  BoxMesh box;
  box.first_node = mesh.num_nodes();
  box.divisions = spec.divisions;
  const auto [nx, ny, nz] = spec.divisions;
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
        mesh.add_node(spec.origin + Vector3d(spec.size.x() * i / nx, spec.size.y() * j / ny,
                                             spec.size.z() * k / nz));
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        mesh.add_hex8({box.node(i, j, k), box.node(i + 1, j, k), box.node(i + 1, j + 1, k),
                       box.node(i, j + 1, k), box.node(i, j, k + 1), box.node(i + 1, j, k + 1),
                       box.node(i + 1, j + 1, k + 1), box.node(i, j + 1, k + 1)},
                      spec.material);
  return box;
}

}  // namespace flexstress::fe
