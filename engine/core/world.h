// Everything a DEM run evolves: particles, bonds, contacts, walls, body forces, and the
// settings that say which physics the scene uses. A scene switches on only what it needs;
// the step computes nothing else.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "engine/core/affine_field.h"
#include "engine/core/blade.h"
#include "engine/core/bonds.h"
#include "engine/core/cell.h"
#include "engine/core/neighbour_list.h"
#include "engine/core/particles.h"
#include "engine/core/walls.h"
#include "engine/interactions/contact.h"

namespace fibrenet {

// The physics a scene declares. Off means not computed at all.
struct Physics {
  bool gravity = false;
  Vec3 g = Vec3(0.0, 0.0, -9.81);  // [m/s^2]
  bool drag = false;
  double drag_coefficient = 0.0;    // linear drag per particle [N s/m]
  Vec3 air_velocity = Vec3::Zero();  // [m/s]
  bool contacts = false;             // non-bonded van Wyk contacts
  bool friction = false;             // Coulomb friction on contacts and walls
  bool applied_loads = false;        // per-particle applied forces and torques
  // Local non-viscous damping (Cundall 1987), in [0, 1): each force and torque component
  // on a free particle is reduced by local_damping x its magnitude when it drives the motion
  // and raised as much when it opposes it. It vanishes in equilibrium, at any velocity, so
  // it relaxes quasi-static loading without resisting the steady motion a viscous drag
  // would; 0 = off. "The motion" is the velocity relative to World::damping_reference.
  double local_damping = 0.0;
};

// What to do with a user time step above safety * dt_crit.
enum class TimeStepPolicy { kReduce, kRefuse };

struct StepSettings {
  double dt = 0.0;           // [s]; 0 = choose safety * dt_crit
  double safety = 0.5;       // fraction of the critical time step, in (0, 1]
  TimeStepPolicy policy = TimeStepPolicy::kReduce;
  double skin = 0.0;         // neighbour skin [m]; 0 = skin_radii x the smallest radius
  // A speed setting only: the forces, and so the results, are the same bit for bit at any
  // skin (pairs beyond contact add nothing). A larger skin means fewer list builds but
  // more pairs to check each step.
  double skin_radii = 0.5;
  int contacts_per_particle_bound = 6;  // assumed contacts per particle for dt_crit
  // A particle moving more than this fraction of its radius in one step is taken as a
  // blow-up and stops the run.
  double max_step_displacement = 0.25;
};

// Energy bookkeeping since the start of the run [J]. Balance:
//   kinetic + strain + dissipated + released = initial + work.
struct EnergyLedger {
  double damping = 0.0;         // viscous contact damping and local damping
  double friction = 0.0;        // Coulomb slip (contacts and walls)
  double bond_inelastic = 0.0;  // bond dashpots, Maxwell flow, plastic bending
  double released = 0.0;        // strain energy of bonds at the step they broke
  // Contact energy of the overlap a broken bond held: a bond formed on a pressed pair keeps
  // its particles overlapping, and once it breaks they meet as a contact again, whose
  // compression pushes them apart with energy the bond stored when it formed.
  double overlap_regained = 0.0;
  double work_gravity = 0.0;
  double work_drag = 0.0;       // negative when drag takes energy out
  double work_walls = 0.0;
  double work_applied = 0.0;

  double Dissipated() const { return damping + friction + bond_inelastic; }
  double Work() const { return work_gravity + work_drag + work_walls + work_applied; }
};

struct World {
  Cell cell;
  Particles particles;
  Bonds bonds;
  ContactParams contact;
  Physics physics;
  std::vector<Wall> walls;
  std::vector<Blade> blades;
  // Per-particle applied loads (used when physics.applied_loads) [N], [N m].
  std::vector<Vec3> applied_force, applied_torque;
  // The velocity field local damping measures each particle's motion against; the default is
  // rest. The damping is not Galilean invariant: measured against rest it resists a
  // deformation a test rig imposes on the whole sheet, so the rig sets this to that
  // deformation before each step. A field, not a velocity per particle: the integrator
  // evaluates it where it reads the particle anyway, instead of a pass of its own.
  AffineField damping_reference;
  StepSettings settings;

  NeighbourList neighbours;
  EnergyLedger energy;
  double time = 0.0;
  std::int64_t step = 0;
  double min_contact_ratio = 1.0;  // smallest d / (R_i + R_j) reached in a contact
};

// A copy of the world to keep aside (a stage's network, an impact frame) with its neighbour
// list parked: the copy costs the particles and bonds, not the list's rows, which its next
// build makes again. The world itself is left as it was.
inline World KeptCopy(World& w) {
  NeighbourList rows = std::exchange(w.neighbours, w.neighbours.Parked());
  World copy = w;
  w.neighbours = std::move(rows);
  return copy;
}

}  // namespace fibrenet
