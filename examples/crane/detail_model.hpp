// The welded detail's sub-model, in full (crane_precompute.hpp holds what the crane keeps of
// it as data): its brick mesh, the sub-model on it and its stress outputs. Includes the FE and
// stress headers; the units that solve or draw the sub-model include it, the others do not.
#pragma once

#include <optional>

#include <flexstress/fe/rhs_attachment_mesh.hpp>
#include <flexstress/stress/stress_outputs.hpp>
#include <flexstress/stress/sub_model.hpp>

#include "crane_precompute.hpp"

namespace crane {

/// The welded detail's sub-model (Detail::model): the brick mesh of the rectangular hollow
/// section with its attachment, the sub-model on it and the outputs read from it.
struct DetailModel {
  fe::RhsAttachmentMesh mesh;
  std::optional<stress::SubModel> sub;
  stress::StressOutputs outputs;
};

}  // namespace crane
