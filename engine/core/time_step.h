// Critical time step of the explicit integrator. Symplectic Euler is stable for
// dt < 2 / omega_max; omega_max^2 is bounded (Gershgorin) by the largest row sum of the
// mass-normalised stiffness matrix built from every intact bond (translation, rotation and
// their shear coupling), a bounded number of contacts at the stiff-branch stiffness, and
// linear drag (dt < 2 m / c).
// Bond dashpots lower that limit: a mode of frequency omega damped at zeta of critical, its
// dashpot acting on the step's starting velocity, is stable under symplectic Euler for
// omega dt < 2 (sqrt(1 + zeta^2) - zeta). Each dashpot mode of each bond (stretch, shear on
// the pair's reduced mass; twist, bending on its reduced inertia) gives its zeta, and the
// largest scales dt_crit by that factor.
#pragma once

#include <string>

#include "engine/core/world.h"

namespace fibrenet {

struct TimeStepInfo {
  double dt_crit = 0.0;  // [s], without the bond dashpots
  std::string limited_by;  // the interaction that sets dt_crit, for messages
  // [s] the limit with the bond dashpots, dt_crit x (sqrt(1 + zeta^2) - zeta) at the largest
  // zeta (dt_crit without dashpots). The time step is safety x dt_crit, and never above this.
  double dt_damped = 0.0;
  std::string damped_limited_by;
};

TimeStepInfo CriticalTimeStep(const World& w);

// Applies the policy of w.settings to the user's dt (0 = automatic). Returns a warning
// message when the step was reduced; throws RunError when the policy is to refuse.
std::string ChooseTimeStep(World& w);

}  // namespace fibrenet
