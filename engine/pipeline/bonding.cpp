#include "engine/pipeline/bonding.h"

#include <cmath>
#include <map>
#include <utility>

#include <fmt/format.h>

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

std::size_t FormFibreFibreBonds(Network& net, const BondingSettings& s) {
  World& w = net.world;
  Particles& p = w.particles;
  std::map<std::pair<double, double>, std::int32_t> types;  // (R_i, R_j) sorted -> type
  auto type_for = [&](double r_a, double r_b) {
    const auto key = std::minmax(r_a, r_b);
    const auto it = types.find(key);
    if (it != types.end()) return it->second;
    BeamBondParams params = BeamBondParams::FromBeam(
        s.transverse_modulus, s.transverse_shear_modulus, s.bond_radius_fraction * key.first,
        key.first + key.second);
    params.failure = BondFailure::kHill;
    params.F_r0 = s.F_r0;
    params.F_s0 = s.F_s0;
    params.HillDefaults();
    const std::int32_t t = w.bonds.AddType(params);
    types.emplace(key, t);
    return t;
  };
  std::size_t made = 0;
  for (const auto& [i, j] : TouchingPairs(w, s.gap_tolerance)) {
    const Vec3 d = w.cell.Delta(p.x[i], p.x[j]);
    const double rest = s.rest_length == RestLength::kContact ? p.radius[i] + p.radius[j] : 0.0;
    w.bonds.Add(i, j, type_for(p.radius[i], p.radius[j]), BondKind::kFibreFibre,
                MakeBondState(d, p.q[i], p.q[j], rest));
    ++made;
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
