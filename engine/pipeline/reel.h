// The reel's draw on the creped sheet (creping.h). The reel runs slower than the Yankee by the
// crepe ratio and pulls the sheet away along the blade face: a particle the blade has passed
// (its place on the Yankee lies behind the tip) and that has climbed beyond the takeaway
// height along the face is dragged towards the reel's velocity. Sheet the blade has not yet
// reached is left alone, even where it has lifted off the Yankee ahead of the blade: the reel
// pulls on the creped sheet, not on the glued one through it.
#pragma once

#include <cstddef>
#include <vector>

#include "engine/core/particles.h"
#include "engine/core/types.h"

namespace fibrenet::pipeline {

struct Reel {
  Vec3 velocity = Vec3::Zero();  // the reel's velocity in the Yankee frame [m/s]
  Vec3 face_up = Vec3::UnitZ();  // along the blade face away from the tip
  double takeaway = 0.0;         // [m] along the face from the tip
  double rate = 0.0;             // 1 / the drag's relaxation time [1/s]
  std::vector<double> x_on_yankee;  // x of each sheet particle before the blade met it [m]

  // The drag on particle i with the blade tip at `tip`; zero for particles beyond the sheet
  // (anchors), those the blade has not passed and those below the takeaway height.
  Vec3 Force(const Particles& p, std::size_t i, const Vec3& tip) const {
    if (i >= x_on_yankee.size() || x_on_yankee[i] < tip.x()) return Vec3::Zero();
    const double along = (p.x[i].x() - tip.x()) * face_up.x() + (p.x[i].z() - tip.z()) * face_up.z();
    if (along <= takeaway) return Vec3::Zero();
    return -p.mass[i] * rate * (p.v[i] - velocity);
  }
};

}  // namespace fibrenet::pipeline
