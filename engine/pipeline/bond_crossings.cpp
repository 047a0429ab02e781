#include "engine/pipeline/bond_crossings.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numeric>
#include <tuple>

namespace fibrenet::pipeline {
namespace {

// One particle bond seen from its fibre pair: fibres a < b and the particles' places along
// each.
struct PairBond {
  std::int32_t fibre_a, fibre_b, place_a, place_b, bond;
};

std::int32_t Root(std::vector<std::int32_t>& parent, std::int32_t k) {
  while (parent[k] != k) k = parent[k] = parent[parent[k]];
  return k;
}

}  // namespace

std::int32_t CrossingReach(const FibreRecord& f) {
  if (f.particle_count <= 0 || f.length <= 0.0) return 1;
  const double spacing = f.length / f.particle_count;
  return static_cast<std::int32_t>(std::ceil(f.diameter / spacing - 1e-9)) + 1;
}

BondCrossings GroupBondsByCrossing(const Network& net) {
  const Bonds& b = net.world.bonds;
  const std::vector<std::int32_t>& fibre_of = net.world.particles.fibre;
  std::vector<PairBond> pair_bonds;
  for (std::size_t k = 0; k < b.size(); ++k) {
    if (b.kind[k] != BondKind::kFibreFibre || b.broken[k]) continue;
    std::int32_t i = b.i[k], j = b.j[k];
    if (fibre_of[i] > fibre_of[j]) std::swap(i, j);
    const std::int32_t fa = fibre_of[i], fb = fibre_of[j];
    pair_bonds.push_back({fa, fb, i - net.fibres[fa].first_particle,
                          j - net.fibres[fb].first_particle, static_cast<std::int32_t>(k)});
  }
  std::sort(pair_bonds.begin(), pair_bonds.end(), [](const PairBond& l, const PairBond& r) {
    return std::tie(l.fibre_a, l.fibre_b, l.bond) < std::tie(r.fibre_a, r.fibre_b, r.bond);
  });

  // Union-find within each fibre pair's run of bonds (a handful, so all pairs are compared).
  std::vector<std::int32_t> parent(pair_bonds.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (std::size_t begin = 0; begin < pair_bonds.size();) {
    std::size_t end = begin + 1;
    while (end < pair_bonds.size() && pair_bonds[end].fibre_a == pair_bonds[begin].fibre_a &&
           pair_bonds[end].fibre_b == pair_bonds[begin].fibre_b)
      ++end;
    const std::int32_t reach = std::max(CrossingReach(net.fibres[pair_bonds[begin].fibre_a]),
                                        CrossingReach(net.fibres[pair_bonds[begin].fibre_b]));
    for (std::size_t m = begin; m < end; ++m)
      for (std::size_t n = m + 1; n < end; ++n)
        if (std::abs(pair_bonds[m].place_a - pair_bonds[n].place_a) <= reach &&
            std::abs(pair_bonds[m].place_b - pair_bonds[n].place_b) <= reach)
          parent[Root(parent, static_cast<std::int32_t>(n))] =
              Root(parent, static_cast<std::int32_t>(m));
    begin = end;
  }

  // Number the crossings in the order of their first bond; report bonds in id order.
  std::vector<std::int32_t> order(pair_bonds.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](std::int32_t l, std::int32_t r) { return pair_bonds[l].bond < pair_bonds[r].bond; });
  BondCrossings out;
  std::vector<std::int32_t> id_of_root(pair_bonds.size(), -1);
  for (std::int32_t k : order) {
    std::int32_t& id = id_of_root[Root(parent, k)];
    if (id < 0) {
      id = static_cast<std::int32_t>(out.size.size());
      out.size.push_back(0);
    }
    out.bonds.push_back(pair_bonds[k].bond);
    out.crossing.push_back(id);
    ++out.size[id];
  }
  return out;
}

}  // namespace fibrenet::pipeline
