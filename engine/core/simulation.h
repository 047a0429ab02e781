// Advances a World in time with symplectic Euler: kick (v, omega from forces at x_n), then
// drift (x, q with the new velocities). With forces from x_n this conserves linear and
// angular momentum exactly when no external load acts, and energy without drift.
// A step computes only the physics the world switches on.
#pragma once

#include <functional>
#include <string>

#include "engine/core/force_buffers.h"
#include "engine/core/forces.h"
#include "engine/core/world.h"

namespace fibrenet {

class Simulation {
 public:
  explicit Simulation(World& world) : w_(world) {}

  // Chooses the time step (returns a warning when it had to reduce it), sizes buffers and
  // builds the neighbour list. Call after setting up the world and after adding bonds.
  std::string Prepare();
  // One time step. Throws RunError naming step, particle and interaction on instability.
  void Step();
  // `steps` steps; `every` > 0 calls `observe` after each `every` steps.
  void Run(std::int64_t steps, std::int64_t every = 0,
           const std::function<void()>& observe = {});

  // Forces of the current configuration without advancing (for diagnostics and tests).
  void ComputeForces();

  std::size_t MemoryBytes() const;

 private:
  // Builds the neighbour list first when asked to (Step decides in its state check).
  void ComputeForces(bool rebuild_neighbours);
  // Kick and drift; stops the run on a non-finite force or torque or a runaway particle.
  // With Physics::local_damping, first adds the damping to each free particle's force and
  // torque and books the energy it takes out.
  void Integrate();
  [[noreturn]] void FailAt(std::size_t particle, const std::string& cause);

  World& w_;
  ForceBuffers buffers_;
  StepLosses losses_;
};

}  // namespace fibrenet
