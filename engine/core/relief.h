// A periodic height map on a wall (an embossing plate's bosses, a drying fabric's pockets):
// heights on a regular grid over one period in x and y, interpolated bilinearly. A height
// h > 0 stands out of the wall towards the particles, h < 0 recedes from them.
//
// The wall's contact normal stays along z: the relief changes where the surface is, not
// which way it pushes. That is exact on the flats and good while the slopes are gentle
// (flanks wider than about a fibre radius per relief height); patterns are built with
// smooth flanks for this reason (engine/pipeline/relief_pattern.h).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace fibrenet {

struct Relief {
  double x0 = 0.0, y0 = 0.0;        // origin of the grid [m]
  double period_x = 0.0, period_y = 0.0;  // [m]
  std::size_t nx = 0, ny = 0;       // grid points per period
  std::vector<double> height;       // nx * ny, row-major in y: height[j * nx + i] [m]

  // Height at (x, y): periodic, bilinear between grid points.
  double At(double x, double y) const {
    const double u = Wrap((x - x0) / period_x) * static_cast<double>(nx);
    const double v = Wrap((y - y0) / period_y) * static_cast<double>(ny);
    const std::size_t i0 = std::min(static_cast<std::size_t>(u), nx - 1);
    const std::size_t j0 = std::min(static_cast<std::size_t>(v), ny - 1);
    const std::size_t i1 = i0 + 1 == nx ? 0 : i0 + 1, j1 = j0 + 1 == ny ? 0 : j0 + 1;
    const double fu = u - static_cast<double>(i0), fv = v - static_cast<double>(j0);
    const double bottom = (1.0 - fu) * height[j0 * nx + i0] + fu * height[j0 * nx + i1];
    const double top = (1.0 - fu) * height[j1 * nx + i0] + fu * height[j1 * nx + i1];
    return (1.0 - fv) * bottom + fv * top;
  }

  double Max() const {
    double m = -INFINITY;
    for (double h : height) m = std::max(m, h);
    return m;
  }
  double Min() const {
    double m = INFINITY;
    for (double h : height) m = std::min(m, h);
    return m;
  }

 private:
  static double Wrap(double t) { return t - std::floor(t); }
};

}  // namespace fibrenet
