// flexstress: stress histories and fatigue damage from flexible multibody simulation.
// Umbrella header: includes every public header except opt-in integrations
// (flexstress/fe/eigen_solver_spectra.hpp needs Spectra and exceptions).
#pragma once

#include "flexstress/version.hpp"

#include "flexstress/core/assert.hpp"
#include "flexstress/core/euler_parameters.hpp"
#include "flexstress/core/scalar_traits.hpp"
#include "flexstress/core/skew.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/core/types.hpp"
