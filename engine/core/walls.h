// Planes normal to z that bound the sheet: the forming wire, pressing plates, compression
// platens. A wall moves with a prescribed velocity; particles touch it through the same
// van Wyk law as a fibre-fibre contact, with the wall acting as the mirror image of the
// particle (distance 2 h between a particle and its image, radii R and R).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "engine/core/relief.h"
#include "engine/core/types.h"

namespace fibrenet {

// The particles a wall can touch until the neighbour list's next build or the wall's next half
// skin of travel, whichever comes first (forces.cpp): a step checks these instead of every
// particle. Found with the list of that build id (0: never found), for the wall's side and
// relief at the time.
struct WallReach {
  std::vector<std::int32_t> particles;  // ascending
  std::uint64_t list_build = 0;
  double z = 0.0;  // the wall's position when they were found [m]
  int side = 0;
  std::shared_ptr<const Relief> relief;
};

struct Wall {
  double z = 0.0;        // position [m]
  double vz = 0.0;       // prescribed velocity [m/s]
  int side = +1;         // +1: particles live above (a floor); -1: below (a top plate)
  bool friction = true;  // Coulomb friction with the contact's mu
  // Hard core of a steel surface (blade.h): a linear spring of hard_stiffness [N/m] below a
  // centre distance of hard_gap radii. 0 = off.
  double hard_stiffness = 0.0;
  double hard_gap = 0.5;
  // Optional height map (relief.h): the surface is at z + side * relief(x, y). Shared, so
  // that copying a World does not copy the grid. Not stored in snapshots: the stages that
  // use a patterned wall remove it before they end.
  std::shared_ptr<const Relief> relief;
  // Reaction of the particles on the wall during the last step [N] (z component is the
  // pressing force) and the work the wall has done on the particles since the start [J].
  Vec3 reaction = Vec3::Zero();
  double work = 0.0;
  // Tangential history of each particle against this wall (sized on first use).
  std::vector<Vec3> history;
  WallReach reach;
};

}  // namespace fibrenet
