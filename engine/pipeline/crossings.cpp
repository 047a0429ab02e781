// Projected fibre crossings (Kallmes-Corte statistics), declared in metrics.h.
//
// Each fibre's centreline is the polyline through its particle centres, unwrapped across
// the periodic faces and projected on the x-y plane. Two segments of different fibres are
// tested for intersection after shifting one by the periodic image that brings its
// midpoint nearest to the other's (segments are far shorter than the cell). The 2D random
// expectation (Crofton's formula, any curve shape): fibres of projected lengths l_i, l_j in
// area A cross on average 2 l_i l_j / (pi A) times.
#include <cmath>
#include <algorithm>
#include <vector>

#include "engine/pipeline/metrics.h"

namespace fibrenet::pipeline {

namespace {

struct Segment {
  double ax, ay, bx, by;
  std::int32_t fibre;
};

double Cross(double ux, double uy, double vx, double vy) { return ux * vy - uy * vx; }

bool Intersect(const Segment& s, const Segment& t, double shift_x, double shift_y) {
  const double tax = t.ax + shift_x, tay = t.ay + shift_y;
  const double tbx = t.bx + shift_x, tby = t.by + shift_y;
  const double rx = s.bx - s.ax, ry = s.by - s.ay;
  const double qx = tbx - tax, qy = tby - tay;
  const double denom = Cross(rx, ry, qx, qy);
  if (denom == 0.0) return false;  // parallel: measure zero for random fibres
  const double wx = tax - s.ax, wy = tay - s.ay;
  const double u = Cross(wx, wy, qx, qy) / denom;  // along s
  const double v = Cross(wx, wy, rx, ry) / denom;  // along t
  return u >= 0.0 && u < 1.0 && v >= 0.0 && v < 1.0;
}

}  // namespace

double CrossingsPerFibre(const Network& net, double* kallmes_corte) {
  const World& w = net.world;
  const Particles& p = w.particles;
  const double Lx = w.cell.Lx(), Ly = w.cell.Ly();
  std::vector<Segment> segs;
  std::vector<double> lengths(net.fibres.size(), 0.0);
  double longest = 0.0;
  for (std::size_t f = 0; f < net.fibres.size(); ++f) {
    const FibreRecord& r = net.fibres[f];
    Vec3 a = p.x[r.first_particle];
    for (int k = 1; k < r.particle_count; ++k) {
      const Vec3 b = a + w.cell.Delta(a, p.x[r.first_particle + k]);
      segs.push_back({a.x(), a.y(), b.x(), b.y(), static_cast<std::int32_t>(f)});
      const double l = std::hypot(b.x() - a.x(), b.y() - a.y());
      lengths[f] += l;
      longest = std::max(longest, l);
      a = b;
    }
  }
  const double n = static_cast<double>(net.fibres.size());
  if (kallmes_corte) {
    double sum = 0.0, sum2 = 0.0;
    for (double l : lengths) {
      sum += l;
      sum2 += l * l;
    }
    *kallmes_corte = n > 0.0 ? 2.0 * (sum * sum - sum2) / (kPi * Lx * Ly * n) : 0.0;
  }
  if (segs.empty() || longest <= 0.0) return 0.0;

  // Grid over segment midpoints (wrapped); a cell side of at least the longest segment
  // guarantees that crossing segments sit in neighbouring cells.
  const int nx = std::max(1, static_cast<int>(Lx / longest));
  const int ny = std::max(1, static_cast<int>(Ly / longest));
  auto cell_of = [&](const Segment& s, int& cx, int& cy) {
    double mx = 0.5 * (s.ax + s.bx), my = 0.5 * (s.ay + s.by);
    mx -= Lx * std::floor((mx - w.cell.lo.x()) / Lx);
    my -= Ly * std::floor((my - w.cell.lo.y()) / Ly);
    cx = std::min(nx - 1, static_cast<int>((mx - w.cell.lo.x()) / Lx * nx));
    cy = std::min(ny - 1, static_cast<int>((my - w.cell.lo.y()) / Ly * ny));
  };
  std::vector<std::vector<std::int32_t>> grid(static_cast<std::size_t>(nx) * ny);
  for (std::size_t k = 0; k < segs.size(); ++k) {
    int cx, cy;
    cell_of(segs[k], cx, cy);
    grid[static_cast<std::size_t>(cy) * nx + cx].push_back(static_cast<std::int32_t>(k));
  }
  std::size_t crossings = 0;
  std::vector<int> seen_cells;
  for (std::size_t k = 0; k < segs.size(); ++k) {
    const Segment& s = segs[k];
    int cx, cy;
    cell_of(s, cx, cy);
    seen_cells.clear();
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int c = ((cy + dy + ny) % ny) * nx + (cx + dx + nx) % nx;
        if (std::find(seen_cells.begin(), seen_cells.end(), c) != seen_cells.end()) continue;
        seen_cells.push_back(c);
        for (const std::int32_t m : grid[c]) {
          if (static_cast<std::size_t>(m) <= k || segs[m].fibre == s.fibre) continue;
          const Segment& t = segs[m];
          const double ddx = 0.5 * (t.ax + t.bx - s.ax - s.bx), ddy = 0.5 * (t.ay + t.by - s.ay - s.by);
          const double shift_x = -Lx * std::nearbyint(ddx / Lx);
          const double shift_y = -Ly * std::nearbyint(ddy / Ly);
          crossings += Intersect(s, t, shift_x, shift_y);
        }
      }
  }
  return n > 0.0 ? 2.0 * static_cast<double>(crossings) / n : 0.0;
}

}  // namespace fibrenet::pipeline
