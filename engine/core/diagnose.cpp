#include "engine/core/diagnose.h"

#include <cmath>

#include <fmt/format.h>

namespace fibrenet {

std::string DescribeLargestInteraction(const World& w, std::size_t particle) {
  const Particles& p = w.particles;
  const auto a = static_cast<std::int32_t>(particle);
  double worst = -1.0;
  std::string what = "none (body forces only)";
  auto consider = [&](double magnitude, std::string description) {
    const double key = std::isfinite(magnitude) ? magnitude : HUGE_VAL;
    if (key > worst) {
      worst = key;
      what = std::move(description);
    }
  };
  for (std::size_t b = 0; b < w.bonds.size(); ++b) {
    if (w.bonds.broken[b] || (w.bonds.i[b] != a && w.bonds.j[b] != a)) continue;
    const std::int32_t i = w.bonds.i[b], j = w.bonds.j[b];
    BondState copy = w.bonds.state[b];
    const BondGeometry g{w.cell.Delta(p.x[i], p.x[j]), p.q[i], p.q[j], p.v[j] - p.v[i],
                         p.omega[i], p.omega[j]};
    const BondResult r =
        EvaluateBond(g, w.bonds.types[w.bonds.type[b]], copy, 0.0, w.bonds.DampingFactors(b));
    consider(r.force_i.norm(), fmt::format("bond {} ({}-{}): |F| = {:.3g} N, |T| = {:.3g} N m", b,
                                           i, j, r.force_i.norm(), r.torque_i.norm()));
  }
  if (w.physics.contacts) {
    for (std::size_t i = 0; i < p.size(); ++i) {
      for (std::size_t k = w.neighbours.RowBegin(i); k < w.neighbours.RowEnd(i); ++k) {
        const std::int32_t j = w.neighbours.Partner(k);
        if (static_cast<std::int32_t>(i) != a && j != a) continue;
        const Vec3 d = w.cell.Delta(p.x[i], p.x[j]);
        const double dist = d.norm(), sum = p.radius[i] + p.radius[j];
        if (!(dist < sum)) continue;
        const double f = EvaluateVanWyk(dist, sum, w.contact.normal).force;
        consider(f, fmt::format("contact {}-{}: d/(R_i+R_j) = {:.3g}, |F_n| = {:.3g} N", i, j,
                                dist / sum, f));
      }
    }
  }
  for (std::size_t k = 0; k < w.walls.size(); ++k) {
    const double gap = (p.x[particle].z() - w.walls[k].z) * w.walls[k].side;
    if (gap >= p.radius[particle]) continue;
    const double f =
        EvaluateVanWyk(2.0 * gap, 2.0 * p.radius[particle], w.contact.ForSurface().normal).force;
    consider(f, fmt::format("wall {} at z = {:.4g} m: gap {:.3g} m, |F_n| = {:.3g} N", k,
                            w.walls[k].z, gap, f));
  }
  return what;
}

}  // namespace fibrenet
