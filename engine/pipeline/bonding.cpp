#include "engine/pipeline/bonding.h"

#include <cmath>
#include <map>
#include <tuple>
#include <utility>

#include <fmt/format.h>

#include "engine/pipeline/bond_crossings.h"
#include "engine/pipeline/pairs.h"

namespace fibrenet::pipeline {

std::string BondingSettings::Validate() const {
  if (!(transverse_modulus > 0.0 && transverse_modulus <= 1e12))
    return fmt::format("transverse_modulus = {} Pa: must lie in (0, 1e12]", transverse_modulus);
  if (!(transverse_shear_modulus > 0.0 && transverse_shear_modulus <= 1e12))
    return fmt::format("transverse_shear_modulus = {} Pa: must lie in (0, 1e12]",
                       transverse_shear_modulus);
  if (!(bond_radius_fraction > 0.0 && bond_radius_fraction <= 1.0))
    return fmt::format("bond_radius_fraction = {}: must lie in (0, 1]", bond_radius_fraction);
  if (!(F_r0 > 0.0 && std::isfinite(F_r0)))
    return fmt::format("F_r0 = {} N: must be finite and > 0", F_r0);
  if (!(F_s0 > 0.0 && std::isfinite(F_s0)))
    return fmt::format("F_s0 = {} N: must be finite and > 0", F_s0);
  if (!(gap_tolerance >= -0.5 && gap_tolerance <= 0.5))
    return fmt::format("gap_tolerance = {}: must lie in [-0.5, 0.5]", gap_tolerance);
  return {};
}

namespace {

// The bond of one crossing (or one particle pair) between particles of radii r_a <= r_b,
// shared among `share` particle bonds.
BeamBondParams SharedBondParams(const BondingSettings& s, double r_a, double r_b, int share) {
  BeamBondParams p = BeamBondParams::FromBeam(s.transverse_modulus, s.transverse_shear_modulus,
                                              s.bond_radius_fraction * r_a, r_a + r_b);
  const double part = 1.0 / share;
  p.k_n *= part, p.k_s *= part, p.k_b *= part, p.k_t *= part;
  p.failure = BondFailure::kHill;
  p.F_r0 = s.F_r0 * part;
  p.F_s0 = s.F_s0 * part;
  p.HillDefaults();
  return p;
}

}  // namespace

std::size_t FormFibreFibreBonds(Network& net, const BondingSettings& s) {
  World& w = net.world;
  Particles& p = w.particles;
  // (R_i, R_j) sorted and the share -> type
  std::map<std::tuple<double, double, int>, std::int32_t> types;
  auto type_for = [&](std::int32_t i, std::int32_t j, int share) {
    const auto [r_a, r_b] = std::minmax(p.radius[i], p.radius[j]);
    const auto key = std::make_tuple(r_a, r_b, share);
    const auto it = types.find(key);
    if (it != types.end()) return it->second;
    const std::int32_t t = w.bonds.AddType(SharedBondParams(s, r_a, r_b, share));
    types.emplace(key, t);
    return t;
  };
  std::size_t made = 0;
  for (const auto& [i, j] : TouchingPairs(w, s.gap_tolerance)) {
    const Vec3 d = w.cell.Delta(p.x[i], p.x[j]);
    const double rest = s.rest_length == RestLength::kContact ? p.radius[i] + p.radius[j] : 0.0;
    // Per crossing, the type waits for the crossing's size (below): no unused type is made.
    const std::int32_t type = s.share == BondShare::kParticle ? type_for(i, j, 1) : 0;
    w.bonds.Add(i, j, type, BondKind::kFibreFibre, MakeBondState(d, p.q[i], p.q[j], rest));
    ++made;
  }
  if (s.share == BondShare::kCrossing) {
    const BondCrossings crossings = GroupBondsByCrossing(net);
    for (std::size_t k = 0; k < crossings.bonds.size(); ++k) {
      const std::int32_t b = crossings.bonds[k];
      w.bonds.type[b] =
          type_for(w.bonds.i[b], w.bonds.j[b], crossings.size[crossings.crossing[k]]);
    }
  }
  w.neighbours.Invalidate();  // bonded pairs leave the contact list
  return made;
}

void SetFibreShape(Network& net) {
  World& w = net.world;
  Particles& p = w.particles;
  for (const FibreRecord& f : net.fibres)
    for (std::int32_t b = f.first_bond; b < f.first_bond + f.bond_count; ++b) {
      if (w.bonds.broken[b]) continue;
      const std::int32_t i = w.bonds.i[b], j = w.bonds.j[b];
      w.bonds.state[b] = MakeBondState(w.cell.Delta(p.x[i], p.x[j]), p.q[i], p.q[j]);
    }
}

}  // namespace fibrenet::pipeline
