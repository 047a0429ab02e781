// The "fibre bed" benchmark scene of SPEC section 6: straight fibres of bonded spheres
// (radius 16 um, spacing one diameter, six-mode beam bonds from E and G), random in-plane
// orientations, stacked loosely in layers in a cell periodic in x and y, falling onto a
// floor wall with friction so that non-bonded van Wyk contacts with friction history form.
//
// Acceleration, stated because the benchmark must reach the contact regime within tens of
// steps instead of the ~1e6 steps a bed takes to settle under real gravity at dt ~ 1 ns:
//  - the layers start a small gap apart (`gap`, default 0.1 um, 0.3% of a diameter),
//  - layer k (from the bottom, k = 0, 1, ...) starts with a downward velocity
//    (k + 1) * approach_speed, so every gap, the floor's included, closes at the same
//    moment, gap / approach_speed (about 45 steps with the defaults) — a gentle impact
//    (1.5 m/s relative) next to the 30 m/s hard validation case,
//  - gravity is scaled (default 1e4 g) so that the bed stays pressed once it has landed.
// The fibre ordering is spatial: fibres are sorted by the Morton index of the tile holding
// their centre, so fibres that touch sit close in memory.
#pragma once

#include <cstdint>
#include <string>

#include "engine/core/world.h"

namespace fibrenet::bench {

// Stokes drag of a bed particle in air, 6 pi mu_air R [N s/m], and a Maxwell relaxation time
// of the order measured for wet paper [s]: the values `fibrenet bench --drag --viscoelastic`
// switches on.
inline constexpr double kStokesDragOfBedParticle = 6.0 * 3.141592653589793 * 1.8e-5 * 16e-6;
inline constexpr double kBenchMaxwellTau = 1e-3;

struct FibreBedSpec {
  // Particles requested; the bed holds the largest whole number of fibres not above it.
  std::int64_t particles = 50000;
  int particles_per_fibre = 20;
  double radius = 16e-6;       // particle and bond cross-section radius [m]
  double E = 10e9;             // fibre Young's modulus [Pa]
  double G = 3e9;              // fibre shear modulus [Pa]
  double coarseness = 2.5e-7;  // fibre mass per length [kg/m]; one particle = 2R of fibre
  int layers = 8;              // layers the fibres are dealt into
  double coverage = 0.25;      // projected area fraction of one layer, in (0, 0.4]
  double gap = 0.1e-6;         // initial clearance between layers and above the floor [m]
  double approach_speed = 3.0; // closing speed of every gap at the start [m/s]
  double gravity = 9.81e4;     // scaled gravity [m/s^2], acting along -z
  double mu = 0.3;             // Coulomb friction, fibre-fibre and fibre-floor [-]
  double restitution = 0.5;    // contact restitution coefficient, in (0, 1]
  double safety = 0.5;         // time step = safety * critical time step
  bool contacts = true;        // non-bonded fibre-fibre contacts (van Wyk)
  bool friction = true;        // friction on contacts and on the floor
  bool use_gravity = true;
  // Physics the bed does not need, switchable to show what they cost: linear air drag per
  // particle [N s/m] (0 = off) and the fibre bonds' axial Maxwell relaxation time [s] (0 =
  // elastic).
  double drag_coefficient = 0.0;
  double maxwell_tau = 0.0;
  // true: fibres sorted by the Morton index of their centre's tile; false: in random order
  // (as a scene's forming box places them), to show what memory locality is worth.
  bool spatial_order = true;
  // true: each fibre is lowered onto the fibres placed before it (it rests on its highest
  // support, `gap` above it); false: layer k sits at height R + gap + k (2R + gap).
  bool deposit = true;
  std::uint64_t seed = 1;

  // Empty when valid; otherwise names the field and its accepted range.
  std::string Validate() const;
};

// What the builder made, for reports.
struct FibreBedInfo {
  std::int64_t particles = 0;
  std::int64_t bonds = 0;
  int fibres = 0;
  int layers = 0;         // layers used (more than spec.layers if a layer was full)
  double cell_side = 0.0; // periodic cell edge in x and y [m]
};

// Fills an empty world with the fibre bed: particles, bonds, floor wall, physics switches
// and step settings (the time step itself is chosen by Simulation::Prepare).
// Throws InputError when the spec is invalid.
FibreBedInfo BuildFibreBed(const FibreBedSpec& spec, World& w);

// Non-bonded particle pairs in contact now (centre distance below the sum of radii),
// counted from the neighbour list; 0 when contacts are off.
std::int64_t CountTouchingPairs(const World& w);

}  // namespace fibrenet::bench
