#include "engine/core/energy.h"

namespace fibrenet {

double KineticEnergy(const World& w) {
  const Particles& p = w.particles;
  double e = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
    e += 0.5 * (p.mass[i] * p.v[i].squaredNorm() + p.inertia[i] * p.omega[i].squaredNorm());
  return e;
}

EnergyReport MeasureEnergy(const World& w) {
  EnergyReport r;
  const Particles& p = w.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    r.kinetic_translation += 0.5 * p.mass[i] * p.v[i].squaredNorm();
    r.kinetic_rotation += 0.5 * p.inertia[i] * p.omega[i].squaredNorm();
  }
  for (std::size_t b = 0; b < w.bonds.size(); ++b) {
    if (w.bonds.broken[b]) continue;
    const std::int32_t i = w.bonds.i[b], j = w.bonds.j[b];
    BondState copy = w.bonds.state[b];
    const BondGeometry g{w.cell.Delta(p.x[i], p.x[j]), p.q[i], p.q[j], p.v[j] - p.v[i],
                         p.omega[i], p.omega[j]};
    const BondResult br = EvaluateBond(g, w.bonds.types[w.bonds.type[b]], copy, 0.0);
    r.strain.normal += br.energy_n;
    r.strain.shear += br.energy_s;
    r.strain.bending += br.energy_b;
    r.strain.twist += br.energy_t;
  }
  if (w.physics.contacts) {
    const NeighbourList& nl = w.neighbours;
    const bool friction = w.physics.friction && w.contact.mu > 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      for (std::size_t k = nl.RowBegin(i); k < nl.RowEnd(i); ++k) {
        const std::int32_t j = nl.Partner(k);
        const Vec3 d = w.cell.Delta(p.x[i], p.x[j]);
        const double sum = p.radius[i] + p.radius[j], dist = d.norm();
        if (dist >= sum) continue;
        const NormalResult nr = EvaluateVanWyk(dist, sum, w.contact.normal);
        r.strain.contacts += nr.energy;
        if (friction) {
          const Vec3 xi = nl.History(k);
          r.strain.contacts += 0.5 * w.contact.tangential_ratio * nr.law_stiffness * xi.squaredNorm();
        }
      }
    }
  }
  // A surface pushes with F(2 gap) of the mirror-image pair, so the potential of that force
  // over the gap is half the pair's energy (which is the integral over 2 gap); its hard core
  // adds a linear spring.
  const ContactParams surface_law = w.contact.ForSurface();
  auto surface_energy = [&](std::size_t i, double gap, bool friction,
                            const std::vector<Vec3>& history, double hard_stiffness,
                            double hard_gap) {
    if (gap >= p.radius[i] || p.inv_mass[i] == 0.0) return;
    const NormalResult nr = EvaluateVanWyk(2.0 * gap, 2.0 * p.radius[i], surface_law.normal);
    r.strain.contacts += 0.5 * nr.energy;
    if (w.physics.friction && friction && i < history.size())
      r.strain.contacts += 0.5 * w.contact.tangential_ratio * nr.law_stiffness * history[i].squaredNorm();
    const double core = hard_gap * p.radius[i] - gap;
    if (core > 0.0) r.strain.contacts += 0.5 * hard_stiffness * core * core;
  };
  for (const Wall& wall : w.walls)
    for (std::size_t i = 0; i < p.size(); ++i)
      surface_energy(i, (p.x[i].z() - wall.z) * wall.side, wall.friction, wall.history,
                     wall.hard_stiffness, wall.hard_gap);
  for (const Blade& blade : w.blades)
    for (std::size_t i = 0; i < p.size(); ++i)
      surface_energy(i, blade.Nearest(p.x[i]).gap, blade.friction, blade.history,
                     blade.hard_stiffness, blade.hard_gap);
  return r;
}

Vec3 LinearMomentum(const World& w) {
  Vec3 m = Vec3::Zero();
  for (std::size_t i = 0; i < w.particles.size(); ++i) m += w.particles.mass[i] * w.particles.v[i];
  return m;
}

Vec3 AngularMomentum(const World& w) {
  const Particles& p = w.particles;
  Vec3 L = Vec3::Zero();
  for (std::size_t i = 0; i < p.size(); ++i)
    L += p.mass[i] * p.x[i].cross(p.v[i]) + p.inertia[i] * p.omega[i];
  return L;
}

}  // namespace fibrenet
