// The two component-mode syntheses a body can be reduced with (reduction/component_modes.hpp).
#pragma once

namespace flexstress::reduction {

/// Craig-Bampton (fixed-interface modes plus static constraint modes) or Craig-Chang (free-free
/// modes plus residual attachment modes).
enum class ReductionMethod : unsigned char { craig_bampton, craig_chang };

}  // namespace flexstress::reduction
