// Spatial lookups the pipeline needs outside the time step: overlap checks while placing
// fibres, touching pairs for bond formation and for contact counts. A uniform grid, periodic
// in x and y as the cell says; cost linear in the particle count. (The engine's neighbour
// list serves the force loop; this one has no skin and no history, and stages use it at
// moments when that list may be stale.)
#pragma once

#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "engine/core/cell.h"
#include "engine/core/world.h"

namespace fibrenet::pipeline {

class ParticleGrid {
 public:
  // h: grid spacing [m], at least the largest distance that will be asked about.
  ParticleGrid(const Cell& cell, double h);

  void Insert(std::int32_t id, const Vec3& x);
  // Ids inserted in the grid cells around x (the 3 x 3 x 3 block, without repeats).
  void Near(const Vec3& x, std::vector<std::int32_t>& out) const;

 private:
  std::int64_t Key(int ix, int iy, int iz) const;
  void Index(const Vec3& x, int& ix, int& iy, int& iz) const;

  Cell cell_;
  double h_;
  int nx_, ny_;
  std::unordered_map<std::int64_t, std::vector<std::int32_t>> cells_;
};

// Pairs i < j of particles of different fibres whose centre distance is below
// (R_i + R_j) * (1 + tolerance), sorted; pairs joined by an intact bond are left out.
// tolerance > -1; negative asks for overlapping pairs only.
std::vector<std::pair<std::int32_t, std::int32_t>> TouchingPairs(const World& w, double tolerance);

}  // namespace fibrenet::pipeline
