// Critical time step of the explicit integrator. Symplectic Euler is stable for
// dt < 2 / omega_max; omega_max^2 is bounded (Gershgorin) by the largest row sum of the
// mass-normalised stiffness matrix built from every intact bond (translation, rotation and
// their shear coupling), a bounded number of contacts at the stiff-branch stiffness, and
// linear drag (dt < 2 m / c).
#pragma once

#include <string>

#include "engine/core/world.h"

namespace fibrenet {

struct TimeStepInfo {
  double dt_crit = 0.0;  // [s]
  std::string limited_by;  // the interaction that sets dt_crit, for messages
};

TimeStepInfo CriticalTimeStep(const World& w);

// Applies the policy of w.settings to the user's dt (0 = automatic). Returns a warning
// message when the step was reduced; throws RunError when the policy is to refuse.
std::string ChooseTimeStep(World& w);

}  // namespace fibrenet
