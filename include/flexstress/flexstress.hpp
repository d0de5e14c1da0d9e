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

#include "flexstress/fe/assembly.hpp"
#include "flexstress/fe/beam3d.hpp"
#include "flexstress/fe/beam_line.hpp"
#include "flexstress/fe/beam_section.hpp"
#include "flexstress/fe/boundary_conditions.hpp"
#include "flexstress/fe/constraint_transform.hpp"
#include "flexstress/fe/dof_map.hpp"
#include "flexstress/fe/eigen_solver.hpp"
#include "flexstress/fe/hex8.hpp"
#include "flexstress/fe/mass_options.hpp"
#include "flexstress/fe/material.hpp"
#include "flexstress/fe/mesh.hpp"
#include "flexstress/fe/rigid_body_modes.hpp"
#include "flexstress/fe/static_solver.hpp"
