// What the crane precomputes before its model is assembled, as plain data: the reduced boom, the
// welded detail's fused rows and what the options ask for besides. Declares precompute_crane
// (crane_precompute.cpp). Light on purpose: it includes neither the model's headers nor the FE
// and stress solvers, so the unit that precomputes parses no model and the model's units parse
// no solver (detail_model.hpp holds the sub-model itself).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <flexstress/core/status.hpp>
#include <flexstress/core/types.hpp>
#include <flexstress/reduction/modal_geometric_stiffness_data.hpp>

#include "boom_model.hpp"

namespace crane {

using namespace flexstress;

/// How the crane is built besides its CraneSpec.
struct CraneOptions {
  int modes = 10;             ///< boom deformation modes (6 static + fixed-interface ones)
  bool hydraulic = false;     ///< the valve-driven cylinder instead of the prescribed stroke
  bool with_inertia = false;  ///< the detail's own weight and inertia in its stresses
  // What the model evaluates (docs/model.md); the accuracy study and the benchmarks vary them.
  bool gravity = true;
  bool modal_damping = true;  ///< the boom's damping ratios from its reduction; off: none
  /// Off: the quadratic velocity terms left out, as an approximation.
  bool quadratic_velocity = true;
  /// K_G of the boom under its inertial and gravity loads, A and B clamped for the load cases.
  bool geometric_stiffening = false;
};

/// The detail's sub-model, its mesh and its stress outputs (detail_model.hpp).
struct DetailModel;

/// The welded detail D: its sub-model, the read-outs on it and their fused rows in the boom's
/// modal coordinates.
struct Detail {
  /// The sub-model and what it is made of: immutable once made, so crane copies share it.
  std::shared_ptr<const DetailModel> model;
  MatrixXd boundary_modes;  ///< Phi_b of the two sub-model ends (12 x modes)
  MatrixXd fused;           ///< outputs x modes
  std::vector<std::string> names;
  Index hot_spot = -1, paper_hot_spot = -1, gauge_04t = -1, gauge_10t = -1, nominal = -1;
  Index toe_line_first = -1, toe_line_count = 0;
  Index num_bricks = 0;  ///< of the sub-model's mesh
};

/// What the crane precomputes before its model is assembled: the reduced boom, the detail, and
/// what the options ask for besides.
struct Precomputed {
  Boom boom;
  Detail detail;
  /// K_G of the boom under its inertial and gravity loads, A and B clamped for the load cases
  /// (CraneOptions::geometric_stiffening).
  std::optional<reduction::ModalGeometricStiffness> boom_stiffening;
  /// The detail's own weight and inertia in its outputs, outputs x 12 (CraneOptions::with_inertia;
  /// stress/sub_model_inertia.hpp).
  MatrixXd detail_inertia;
};

/// Reduces the boom with `options.modes` modes and makes the detail on it (crane_precompute.cpp).
Result<Precomputed> precompute_crane(const CraneSpec& spec, const CraneOptions& options);

/// Writes the detail's sub-model, driven by the boom's modal coordinates p (its first p.size()
/// modes), with its displacement and stress fields as a VTK file (crane_precompute.cpp).
Status write_detail_vtu(const Detail& detail, const VectorXd& p, const std::string& path);

}  // namespace crane
