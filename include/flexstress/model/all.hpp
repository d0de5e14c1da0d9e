// The runtime model in one include: ModelBuilder, Model, Data, the implicit and explicit steps,
// equilibrium, read-outs, outputs, the energy balance and checkpoints.
#pragma once

#include "flexstress/model/checkpoint.hpp"
#include "flexstress/model/compiled.hpp"
#include "flexstress/model/data.hpp"
#include "flexstress/model/energy_balance.hpp"
#include "flexstress/model/equilibrium.hpp"
#include "flexstress/model/explicit_step.hpp"
#include "flexstress/model/handles.hpp"
#include "flexstress/model/implicit_step.hpp"
#include "flexstress/model/model.hpp"
#include "flexstress/model/model_builder.hpp"
#include "flexstress/model/motion_law.hpp"
#include "flexstress/model/outputs.hpp"
#include "flexstress/model/readouts.hpp"
#include "flexstress/model/step.hpp"
