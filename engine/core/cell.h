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
  // Hot: runs for every pair every step. |d| <= L/2 (almost every pair) skips the division
  // and the rounding, which would leave d unchanged there anyway, so results are identical.
  // The components are built as scalars and put together once: a vector whose halves were
  // written one at a time and then read whole stalls on the store forwarding (36% of the
  // state check's samples).
  Vec3 Delta(const Vec3& a, const Vec3& b) const {
    double dx = b.x() - a.x(), dy = b.y() - a.y();
    const double dz = b.z() - a.z();
    if (periodic_x) dx = MinimumImage(dx, Lx());
    if (periodic_y) dy = MinimumImage(dy, Ly());
    return Vec3(dx, dy, dz);
  }

  // Maps a position back into [lo, hi) along the periodic directions. A position already
  // inside (t in [0, 1)) is left as it is, which is what the floor would give.
  void Wrap(Vec3& p) const {
    if (periodic_x) p.x() = WrapInto(p.x(), lo.x(), Lx());
    if (periodic_y) p.y() = WrapInto(p.y(), lo.y(), Ly());
  }

 private:
  static double MinimumImage(double d, double L) {
    if (std::abs(d) <= 0.5 * L) return d;
    return d - L * std::nearbyint(d / L);
  }
  // a = x - lo in [0, L) exactly when the rounded a / L lies in [0, 1) (a < L gives a / L <=
  // 1 - 2^-53 after rounding), so the division is left to the rare position outside.
  static double WrapInto(double x, double lo, double L) {
    const double a = x - lo;
    if (a >= 0.0 && a < L) return x;
    return x - L * std::floor(a / L);
  }
};

}  // namespace fibrenet
