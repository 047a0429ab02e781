// The simulation cell: periodic in the sheet plane (x, y), open in z where walls and
// plates bound the sheet. Lengths in m.
#pragma once

#include <cmath>

#include "engine/core/types.h"

namespace fibrenet {

struct Cell {
  Vec3 lo = Vec3::Zero();
  Vec3 hi = Vec3::Ones();
  bool periodic_x = true;
  bool periodic_y = true;

  double Lx() const { return hi.x() - lo.x(); }
  double Ly() const { return hi.y() - lo.y(); }

  // Shortest vector from a to b under the periodic images (minimum image convention).
  Vec3 Delta(const Vec3& a, const Vec3& b) const {
    Vec3 d = b - a;
    if (periodic_x) d.x() -= Lx() * std::nearbyint(d.x() / Lx());
    if (periodic_y) d.y() -= Ly() * std::nearbyint(d.y() / Ly());
    return d;
  }

  // Maps a position back into [lo, hi) along the periodic directions.
  void Wrap(Vec3& p) const {
    if (periodic_x) p.x() -= Lx() * std::floor((p.x() - lo.x()) / Lx());
    if (periodic_y) p.y() -= Ly() * std::floor((p.y() - lo.y()) / Ly());
  }
};

}  // namespace fibrenet
