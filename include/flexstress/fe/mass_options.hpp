// How element mass matrices are built (consistent or lumped, beam rotary inertia).
#pragma once

namespace flexstress::fe {

/// How mass is distributed.
enum class MassLumping : unsigned char {
  consistent,  ///< Integrates the element interpolation (exact kinetic energy of the field).
  lumped,      ///< Diagonal: half the element's mass and half its section inertia per node.
};

struct MassOptions {
  MassLumping lumping = MassLumping::consistent;
  /// Beams: include the rotary inertia of the section in bending (the torsional inertia
  /// about the axis is always included). Euler-Bernoulli textbook frequencies assume false.
  bool beam_rotary_inertia = true;
};

}  // namespace flexstress::fe
