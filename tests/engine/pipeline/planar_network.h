// Test networks built directly with Network::AddFibre: a nearly 2D random network of
// straight fibres lying flat in `layers` planes (fibre k in the plane z = (k mod layers) d),
// bonded at every crossing of fibres in neighbouring planes by one fibre-fibre bond between
// the two particles nearest the crossing. Contacts are off (fibres in one plane may overlap;
// the network is held together by bonds alone). Used for the Cox affine-limit check and the
// bond-level checks of the virtual tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "engine/pipeline/distribution.h"
#include "engine/pipeline/fibre.h"
#include "engine/pipeline/network.h"

namespace fibrenet::pipeline::testing {

struct PlanarSpec {
  int fibres = 100;
  double length = 0.6e-3;     // [m]
  double diameter = 20e-6;    // [m]; particles are spaced one diameter apart
  double coarseness = 1e-7;   // [kg/m]
  double E = 10e9, G = 3e9;   // fibre moduli [Pa]
  double Lx = 1.8e-3, Ly = 0.9e-3;
  int layers = 2;
  // Fibre-fibre bonds: beam of radius bond_radius_fraction * R and length d with moduli
  // bond_E, bond_G; Hill failure with F_r0, F_s0 (failure off when F_r0 <= 0).
  double bond_E = 10e9, bond_G = 3e9, bond_radius_fraction = 1.0;
  double F_r0 = 0.0, F_s0 = 0.0;
  // Keep each crossing bond with this probability (bonds per fibre below the crossings).
  double bond_probability = 1.0;
  std::uint64_t seed = 1;
};

struct PlanarNetwork {
  Network net;
  int crossings = 0;  // bonded crossings
};

inline PlanarNetwork MakePlanarNetwork(const PlanarSpec& s) {
  PlanarNetwork out;
  Network& net = out.net;
  World& w = net.world;
  w.cell.lo = Vec3(0.0, 0.0, -1e-3);
  w.cell.hi = Vec3(s.Lx, s.Ly, 1e-3);
  std::mt19937_64 rng(s.seed);
  const int n = std::max(2, static_cast<int>(std::lround(s.length / s.diameter)));
  const double spacing = s.length / n;
  FibreProperties f;
  f.length = s.length;
  f.diameter = s.diameter;
  f.coarseness = s.coarseness;
  f.youngs_modulus = s.E;
  f.shear_modulus = s.G;
  f.strength = 1e9;
  struct Line {
    Vec3 a, t;  // first particle centre and unit direction (in-plane)
    int layer;
  };
  std::vector<Line> lines;
  std::vector<int> order(s.fibres);
  for (int k = 0; k < s.fibres; ++k) order[k] = k;
  std::shuffle(order.begin(), order.end(), rng);
  for (int k = 0; k < s.fibres; ++k) {
    // Stratified angles: fibre k gets one angle from the k-th of `fibres` equal slices of
    // [0, pi), so the orientation distribution is uniform up to 1/fibres (Cox assumes it).
    const double phi = kPi * (order[k] + UniformUnit(rng)) / s.fibres;
    const Vec3 t(std::cos(phi), std::sin(phi), 0.0);
    const int layer = k % s.layers;
    const Vec3 c(s.Lx * UniformUnit(rng), s.Ly * UniformUnit(rng), layer * s.diameter);
    const Vec3 a = c - 0.5 * (n - 1) * spacing * t;
    std::vector<Vec3> x;
    for (int m = 0; m < n; ++m) x.push_back(a + m * spacing * t);
    net.AddFibre(f, x, FibreBondOptions{});
    lines.push_back({a, t, layer});
  }
  BeamBondParams bp = BeamBondParams::FromBeam(s.bond_E, s.bond_G,
                                               s.bond_radius_fraction * 0.5 * s.diameter, s.diameter);
  if (s.F_r0 > 0.0) {
    bp.failure = BondFailure::kHill;
    bp.F_r0 = s.F_r0;
    bp.F_s0 = s.F_s0;
    bp.HillDefaults();
  }
  const std::int32_t type = w.bonds.AddType(bp);
  const double span = (n - 1) * spacing;
  Particles& p = w.particles;
  // Crossings of the centrelines (as unwrapped segments) over the periodic images.
  for (int i = 0; i < s.fibres; ++i) {
    for (int j = i + 1; j < s.fibres; ++j) {
      if (std::abs(lines[i].layer - lines[j].layer) != 1) continue;
      for (int ix = -1; ix <= 1; ++ix) {
        for (int iy = -1; iy <= 1; ++iy) {
          const Vec3 shift(ix * s.Lx, iy * s.Ly, 0.0);
          const Vec3 a = lines[i].a, b = lines[j].a + shift;
          const Vec3 u = lines[i].t, v = lines[j].t;
          const double det = u.x() * (-v.y()) - u.y() * (-v.x());
          if (std::abs(det) < 1e-12) continue;
          const Vec3 r = b - a;
          // a + s_i u = b + s_j v
          const double si = (r.x() * (-v.y()) - r.y() * (-v.x())) / det;
          const double sj = (u.x() * r.y() - u.y() * r.x()) / det;
          if (si < 0.0 || si > span || sj < 0.0 || sj > span) continue;
          if (UniformUnit(rng) >= s.bond_probability) continue;
          const auto pi = static_cast<std::int32_t>(net.fibres[i].first_particle +
                                                    std::lround(si / spacing));
          const auto pj = static_cast<std::int32_t>(net.fibres[j].first_particle +
                                                    std::lround(sj / spacing));
          w.bonds.Add(pi, pj, type, BondKind::kFibreFibre,
                      MakeBondState(w.cell.Delta(p.x[pi], p.x[pj]), p.q[pi], p.q[pj]));
          ++out.crossings;
        }
      }
    }
  }
  w.physics = Physics{};  // bonds only
  return out;
}

}  // namespace fibrenet::pipeline::testing
