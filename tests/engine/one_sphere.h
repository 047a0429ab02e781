// One sphere in a cell open along x (the tests of a single particle against a wall or blade).
#pragma once

#include "engine/core/world.h"

namespace fibrenet {

// A sphere of radius R and mass m at rest at x, with contacts of restitution e, in the cell
// [-half, half] along x and z (open along x) and [0, width] along y.
inline World OneSphere(const Vec3& x, double R, double m, double e, double half, double width) {
  World w;
  w.cell.lo = Vec3(-half, 0.0, -half);
  w.cell.hi = Vec3(half, width, half);
  w.cell.periodic_x = false;
  w.physics.contacts = true;
  w.contact.restitution = e;
  w.contact.Derive();
  w.particles.Add(x, R, m, 0);
  return w;
}

}  // namespace fibrenet
