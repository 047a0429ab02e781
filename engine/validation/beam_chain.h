// A straight fibre of bonded spheres for the validation cases: n particles along x,
// spacing L, beam-theory bonds from E, G and the particle radius.
#pragma once

#include "engine/core/world.h"

namespace fibrenet::validation {

struct ChainSpec {
  int particles = 11;
  double length = 1e-3;           // end-to-end centre distance [m]
  double radius = 16e-6;          // [m]; also the bond cross-section radius
  double E = 10e9, G = 3e9;       // [Pa]
  double mass_per_length = 2.5e-7;  // [kg/m] (25 mg/100 m)
  bool half_mass_ends = true;     // lump half a segment's mass on each end particle
  Vec3 origin = Vec3::Zero();
  double inertia_scale = 1.0;
};

// Adds the chain to w (particles and bonds with one new bond type); returns the index of
// the first particle.
std::size_t AddChain(World& w, const ChainSpec& spec);

// A cell large enough to hold the chain without periodic images interfering.
Cell IsolatedCell(const ChainSpec& spec);

}  // namespace fibrenet::validation
