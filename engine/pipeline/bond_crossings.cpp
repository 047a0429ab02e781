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
  // pair_bonds is in bond id order; `by_pair` visits it fibre pair by fibre pair.
  std::vector<std::int32_t> by_pair(pair_bonds.size());
  std::iota(by_pair.begin(), by_pair.end(), 0);
  std::stable_sort(by_pair.begin(), by_pair.end(), [&](std::int32_t l, std::int32_t r) {
    return std::tie(pair_bonds[l].fibre_a, pair_bonds[l].fibre_b) <
           std::tie(pair_bonds[r].fibre_a, pair_bonds[r].fibre_b);
  });

  // Union-find within each fibre pair's run of bonds (a handful, so all pairs are compared).
  std::vector<std::int32_t> parent(pair_bonds.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (std::size_t begin = 0; begin < by_pair.size();) {
    const PairBond& first = pair_bonds[by_pair[begin]];
    std::size_t end = begin + 1;
    while (end < by_pair.size() && pair_bonds[by_pair[end]].fibre_a == first.fibre_a &&
           pair_bonds[by_pair[end]].fibre_b == first.fibre_b)
      ++end;
    const std::int32_t reach = std::max(CrossingReach(net.fibres[first.fibre_a]),
                                        CrossingReach(net.fibres[first.fibre_b]));
    for (std::size_t m = begin; m < end; ++m)
      for (std::size_t n = m + 1; n < end; ++n) {
        const PairBond& u = pair_bonds[by_pair[m]];
        const PairBond& v = pair_bonds[by_pair[n]];
        if (std::abs(u.place_a - v.place_a) <= reach && std::abs(u.place_b - v.place_b) <= reach)
          parent[Root(parent, by_pair[n])] = Root(parent, by_pair[m]);
      }
    begin = end;
  }

  // Number the crossings in the order of their first bond; report bonds in id order.
  BondCrossings out;
  std::vector<std::int32_t> id_of_root(pair_bonds.size(), -1);
  for (std::size_t k = 0; k < pair_bonds.size(); ++k) {
    std::int32_t& id = id_of_root[Root(parent, static_cast<std::int32_t>(k))];
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
