#include "engine/pipeline/strain_energy.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

namespace fibrenet::pipeline {

ModeEnergy& ModeEnergy::operator+=(const ModeEnergy& o) {
  normal += o.normal;
  shear += o.shear;
  bending += o.bending;
  twist += o.twist;
  return *this;
}

ModeEnergy ModeEnergy::operator-(const ModeEnergy& o) const {
  return {normal - o.normal, shear - o.shear, bending - o.bending, twist - o.twist};
}

std::vector<ModeEnergy> FibreEnergies(const Network& net) {
  const World& w = net.world;
  const Particles& p = w.particles;
  const Bonds& bonds = w.bonds;
  std::vector<ModeEnergy> out(net.fibres.size());
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    if (bonds.broken[b]) continue;
    const std::int32_t i = bonds.i[b], j = bonds.j[b];
    BondState copy = bonds.state[b];
    const BondGeometry g{w.cell.Delta(p.x[i], p.x[j]), p.q[i], p.q[j], p.v[j] - p.v[i],
                         p.omega[i], p.omega[j]};
    const BondResult r = EvaluateBond(g, bonds.types[bonds.type[b]], copy, 0.0);
    const ModeEnergy e{r.energy_n, r.energy_s, r.energy_b, r.energy_t};
    const std::int32_t fi = p.fibre[i], fj = p.fibre[j];
    if (bonds.kind[b] == BondKind::kFibre || fi == fj) {
      if (fi >= 0) out[fi] += e;
      continue;
    }
    const ModeEnergy half{0.5 * e.normal, 0.5 * e.shear, 0.5 * e.bending, 0.5 * e.twist};
    if (fi >= 0) out[fi] += half;
    if (fj >= 0) out[fj] += half;
  }
  return out;
}

ModeEnergy TotalEnergy(const std::vector<ModeEnergy>& fibres) {
  ModeEnergy t;
  for (const ModeEnergy& e : fibres) t += e;
  return t;
}

double Gini(std::vector<double> values) {
  for (double& v : values) v = std::max(v, 0.0);
  const double sum = std::accumulate(values.begin(), values.end(), 0.0);
  const auto n = static_cast<double>(values.size());
  if (values.empty() || !(sum > 0.0)) return 0.0;
  std::sort(values.begin(), values.end());
  double weighted = 0.0;
  for (std::size_t k = 0; k < values.size(); ++k) weighted += static_cast<double>(k + 1) * values[k];
  return 2.0 * weighted / (n * sum) - (n + 1.0) / n;
}

double TopShare(std::vector<double> values, double fraction) {
  for (double& v : values) v = std::max(v, 0.0);
  const double sum = std::accumulate(values.begin(), values.end(), 0.0);
  if (values.empty() || !(sum > 0.0)) return 0.0;
  const auto top = std::min(values.size(), static_cast<std::size_t>(std::ceil(
                                               fraction * static_cast<double>(values.size()))));
  std::partial_sort(values.begin(), values.begin() + top, values.end(), std::greater<double>());
  return std::accumulate(values.begin(), values.begin() + top, 0.0) / sum;
}

EnergyDistribution DistributionOfIncrement(const std::vector<ModeEnergy>& before,
                                           const std::vector<ModeEnergy>& now) {
  EnergyDistribution d;
  d.per_fibre.resize(now.size());
  for (std::size_t f = 0; f < now.size(); ++f) {
    const ModeEnergy inc = f < before.size() ? now[f] - before[f] : now[f];
    d.total += inc;
    d.per_fibre[f] = inc.Total();
  }
  if (!now.empty()) d.per_fibre_mean = d.total.Total() / static_cast<double>(now.size());
  d.top10_share = TopShare(d.per_fibre, 0.1);
  d.gini = Gini(d.per_fibre);
  return d;
}

}  // namespace fibrenet::pipeline
