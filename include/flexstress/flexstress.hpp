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

#include "flexstress/fatigue/class_grid.hpp"
#include "flexstress/fatigue/cycle.hpp"
#include "flexstress/fatigue/cycle_matrix.hpp"
#include "flexstress/fatigue/damage.hpp"
#include "flexstress/fatigue/mean_stress.hpp"
#include "flexstress/fatigue/multiaxial.hpp"
#include "flexstress/fatigue/rainflow.hpp"
#include "flexstress/fatigue/reversals.hpp"
#include "flexstress/fatigue/sn_curve.hpp"
#include "flexstress/fatigue/streaming_damage.hpp"
#include "flexstress/fatigue/streaming_rainflow.hpp"
#include "flexstress/fatigue/weld_line.hpp"

#include "flexstress/reduction/component_modes.hpp"
#include "flexstress/reduction/inertia_integrals.hpp"
#include "flexstress/reduction/interface.hpp"
#include "flexstress/reduction/modal_body_data.hpp"
#include "flexstress/reduction/orthonormalize.hpp"
