// The force loops of one step. Each loop is written once and calls the pure evaluator of
// its law (engine/interactions); energy lost during the step is returned for the ledger.
#pragma once

#include "engine/core/force_buffers.h"
#include "engine/core/world.h"

namespace fibrenet {

struct StepLosses {
  double damping = 0.0;         // [J]
  double friction = 0.0;        // [J]
  double bond_inelastic = 0.0;  // [J]
  double released = 0.0;        // [J]
  double overlap_regained = 0.0;  // [J]
  double min_contact_ratio = 1.0;
  bool bonds_broke = false;
};

// Intact bonds: forces, torques, history, failure. Broken bonds are marked and recorded.
void AccumulateBondForces(World& w, ForceBuffers& buffers, StepLosses& losses);
// Non-bonded contacts found in the neighbour list (physics.contacts).
void AccumulateContactForces(World& w, ForceBuffers& buffers, StepLosses& losses);
// Particle-wall contacts; fills each wall's reaction.
void AccumulateWallForces(World& w, StepLosses& losses);
// Particle-blade contacts; fills each blade's reaction and work.
void AccumulateBladeForces(World& w, StepLosses& losses);
// Starts a force evaluation: sets every force and torque to the body loads switched on
// (gravity, drag, applied loads), zero otherwise.
void StartForces(World& w);

}  // namespace fibrenet
