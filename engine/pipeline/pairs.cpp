#include "engine/pipeline/pairs.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>

namespace fibrenet::pipeline {

ParticleGrid::ParticleGrid(const Cell& cell, double h) : cell_(cell), h_(h) {
  nx_ = std::max(1, static_cast<int>(std::floor(cell.Lx() / h)));
  ny_ = std::max(1, static_cast<int>(std::floor(cell.Ly() / h)));
}

void ParticleGrid::Index(const Vec3& x, int& ix, int& iy, int& iz) const {
  Vec3 p = x;
  cell_.Wrap(p);
  ix = std::clamp(static_cast<int>(std::floor((p.x() - cell_.lo.x()) / cell_.Lx() * nx_)), 0, nx_ - 1);
  iy = std::clamp(static_cast<int>(std::floor((p.y() - cell_.lo.y()) / cell_.Ly() * ny_)), 0, ny_ - 1);
  iz = static_cast<int>(std::floor(p.z() / h_));
}

std::int64_t ParticleGrid::Key(int ix, int iy, int iz) const {
  return ((static_cast<std::int64_t>(iz) + (1LL << 30)) << 32) |
         (static_cast<std::int64_t>(iy) << 16) | static_cast<std::int64_t>(ix);
}

void ParticleGrid::Insert(std::int32_t id, const Vec3& x) {
  int ix, iy, iz;
  Index(x, ix, iy, iz);
  cells_[Key(ix, iy, iz)].push_back(id);
}

void ParticleGrid::Near(const Vec3& x, std::vector<std::int32_t>& out) const {
  out.clear();
  int ix, iy, iz;
  Index(x, ix, iy, iz);
  std::int64_t keys[27];
  int count = 0;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        int cx = ix + dx, cy = iy + dy;
        if (cx < 0 || cx >= nx_) {
          if (!cell_.periodic_x) continue;
          cx = (cx + nx_) % nx_;
        }
        if (cy < 0 || cy >= ny_) {
          if (!cell_.periodic_y) continue;
          cy = (cy + ny_) % ny_;
        }
        keys[count++] = Key(cx, cy, iz + dz);
      }
  std::sort(keys, keys + count);
  count = static_cast<int>(std::unique(keys, keys + count) - keys);
  for (int k = 0; k < count; ++k) {
    const auto it = cells_.find(keys[k]);
    if (it != cells_.end()) out.insert(out.end(), it->second.begin(), it->second.end());
  }
}

std::vector<std::pair<std::int32_t, std::int32_t>> TouchingPairs(const World& w, double tolerance) {
  const Particles& p = w.particles;
  std::vector<std::pair<std::int32_t, std::int32_t>> pairs;
  if (p.size() == 0) return pairs;
  const double r_max = *std::max_element(p.radius.begin(), p.radius.end());
  ParticleGrid grid(w.cell, 2.0 * r_max * std::max(1.0, 1.0 + tolerance));
  for (std::size_t i = 0; i < p.size(); ++i) grid.Insert(static_cast<std::int32_t>(i), p.x[i]);

  std::unordered_set<std::uint64_t> bonded;
  for (std::size_t b = 0; b < w.bonds.size(); ++b) {
    if (w.bonds.broken[b]) continue;
    const auto lo = static_cast<std::uint64_t>(std::min(w.bonds.i[b], w.bonds.j[b]));
    const auto hi = static_cast<std::uint64_t>(std::max(w.bonds.i[b], w.bonds.j[b]));
    bonded.insert((lo << 32) | hi);
  }
  std::vector<std::int32_t> near;
  for (std::size_t i = 0; i < p.size(); ++i) {
    grid.Near(p.x[i], near);
    for (const std::int32_t j : near) {
      if (j <= static_cast<std::int32_t>(i) || p.fibre[j] == p.fibre[i]) continue;
      const double reach = (p.radius[i] + p.radius[j]) * (1.0 + tolerance);
      if (w.cell.Delta(p.x[i], p.x[j]).squaredNorm() >= reach * reach) continue;
      if (bonded.count((static_cast<std::uint64_t>(i) << 32) | static_cast<std::uint64_t>(j)))
        continue;
      pairs.emplace_back(static_cast<std::int32_t>(i), j);
    }
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace fibrenet::pipeline
