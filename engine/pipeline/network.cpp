#include "engine/pipeline/network.h"

#include <algorithm>
#include <stdexcept>

#include <fmt/format.h>

namespace fibrenet::pipeline {

std::int32_t Network::AddFibre(const FibreProperties& f, const std::vector<Vec3>& centres,
                               const FibreBondOptions& options) {
  Particles& p = world.particles;
  Bonds& b = world.bonds;
  const auto id = static_cast<std::int32_t>(fibres.size());
  const int n = static_cast<int>(centres.size());
  const double radius = 0.5 * f.diameter;
  const double spacing = f.length / n;
  FibreRecord r;
  r.first_particle = static_cast<std::int32_t>(p.size());
  r.particle_count = n;
  r.first_bond = static_cast<std::int32_t>(b.size());
  r.bond_count = n - 1;
  r.length = f.length;
  r.diameter = f.diameter;
  r.coarseness = f.coarseness;
  r.youngs_modulus = f.youngs_modulus;
  r.shear_modulus = f.shear_modulus;
  r.strength = f.strength;

  BeamBondParams params = BeamBondParams::FromBeam(f.youngs_modulus, f.shear_modulus, radius, spacing);
  params.failure = BondFailure::kModeThresholds;
  params.max_tension = f.strength;
  params.maxwell_tau = options.maxwell_tau;
  params.yield_moment = options.yield_moment;
  r.bond_type = b.AddType(params);

  const double mass = f.coarseness * spacing;  // this particle's share of the fibre length
  for (const Vec3& c : centres) {
    Vec3 x = c;
    world.cell.Wrap(x);
    p.Add(x, radius, mass, id, options.inertia_scale);
  }
  for (int k = 0; k + 1 < n; ++k) {
    const std::int32_t a = r.first_particle + k, c = a + 1;
    b.Add(a, c, r.bond_type, BondKind::kFibre,
          MakeBondState(world.cell.Delta(p.x[a], p.x[c]), p.q[a], p.q[c]));
  }
  fibres.push_back(r);
  return id;
}

double Network::TotalMass() const {
  double m = 0.0;
  for (double mi : world.particles.mass) m += mi;
  return m;
}

std::size_t Network::IntactFibreFibreBonds() const {
  const Bonds& b = world.bonds;
  std::size_t n = 0;
  for (std::size_t k = 0; k < b.size(); ++k)
    n += (b.kind[k] == BondKind::kFibreFibre && !b.broken[k]);
  return n;
}

std::string Network::CheckInvariants() const {
  const Particles& p = world.particles;
  const Bonds& b = world.bonds;
  std::size_t next_particle = 0;
  for (std::size_t f = 0; f < fibres.size(); ++f) {
    const FibreRecord& r = fibres[f];
    if (static_cast<std::size_t>(r.first_particle) != next_particle)
      return fmt::format("fibre {}: particles do not follow the previous fibre's", f);
    for (int k = 0; k < r.particle_count; ++k)
      if (p.fibre[r.first_particle + k] != static_cast<std::int32_t>(f))
        return fmt::format("fibre {}: particle {} belongs to fibre {}", f, r.first_particle + k,
                           p.fibre[r.first_particle + k]);
    for (int k = 0; k < r.bond_count; ++k) {
      const std::size_t bond = r.first_bond + k;
      if (bond >= b.size() || b.i[bond] != r.first_particle + k ||
          b.j[bond] != r.first_particle + k + 1)
        return fmt::format("fibre {}: bond {} does not join particles {} and {}", f, bond,
                           r.first_particle + k, r.first_particle + k + 1);
    }
    next_particle += r.particle_count;
  }
  if (next_particle != p.size())
    return fmt::format("{} particles but the fibres own {}", p.size(), next_particle);
  return {};
}

namespace {

template <class T>
void KeepEntries(std::vector<T>& v, const std::vector<std::uint8_t>& keep) {
  std::size_t out = 0;
  for (std::size_t i = 0; i < v.size(); ++i)
    if (keep[i]) v[out++] = v[i];
  v.resize(out);
}

}  // namespace

std::size_t KeepParticles(Network& net, const std::vector<std::uint8_t>& keep) {
  World& w = net.world;
  Particles& p = w.particles;
  Bonds& b = w.bonds;
  if (keep.size() != p.size()) throw std::invalid_argument("KeepParticles: one flag per particle");
  constexpr std::int32_t kGone = -1;
  std::vector<std::int32_t> new_index(p.size(), kGone);
  std::int32_t n_kept = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (keep[i]) new_index[i] = n_kept++;
  const std::size_t removed = p.size() - static_cast<std::size_t>(n_kept);
  if (removed == 0) return 0;

  // Histories of the kept pairs in contact, before the indices change (the list may still
  // name particles beyond p.size() that the caller dropped).
  std::vector<PairHistory> history;
  const bool had_list = w.neighbours.builds() > 0;
  if (had_list)
    for (PairHistory h : w.neighbours.ExportHistory()) {
      if (static_cast<std::size_t>(h.j) >= p.size() || !keep[h.i] || !keep[h.j]) continue;
      if (w.cell.Delta(p.x[h.i], p.x[h.j]).norm() >= p.radius[h.i] + p.radius[h.j]) continue;
      h.i = new_index[h.i];
      h.j = new_index[h.j];
      history.push_back(h);
    }

  // Fibres: one record per run of kept particles; their intra-fibre bonds first, in order.
  std::vector<FibreRecord> fibres;
  std::vector<std::uint8_t> keep_bond(b.size(), 0);
  std::vector<std::int32_t> bond_order;  // old ids of the kept bonds, in their new order
  std::vector<std::int32_t> fibre_of(p.size(), -1);
  for (const FibreRecord& f : net.fibres) {
    for (int k = 0; k < f.particle_count;) {
      if (!keep[f.first_particle + k]) {
        ++k;
        continue;
      }
      int end = k;
      while (end < f.particle_count && keep[f.first_particle + end]) ++end;
      FibreRecord run = f;
      run.first_particle = new_index[f.first_particle + k];
      run.particle_count = end - k;
      run.first_bond = static_cast<std::int32_t>(bond_order.size());
      run.bond_count = end - k - 1;
      run.length = f.length * run.particle_count / f.particle_count;
      for (int m = k; m < end; ++m) fibre_of[f.first_particle + m] = static_cast<std::int32_t>(fibres.size());
      for (int m = k; m + 1 < end; ++m) {
        bond_order.push_back(f.first_bond + m);
        keep_bond[f.first_bond + m] = 1;
      }
      fibres.push_back(run);
      k = end;
    }
  }
  // Then every other bond whose ends both stay, in the order it had.
  for (std::size_t k = 0; k < b.size(); ++k)
    if (b.kind[k] != BondKind::kFibre && keep[b.i[k]] && keep[b.j[k]]) {
      bond_order.push_back(static_cast<std::int32_t>(k));
      keep_bond[k] = 1;
    }
  std::vector<std::int32_t> new_bond(b.size(), kGone);
  for (std::size_t k = 0; k < bond_order.size(); ++k)
    new_bond[bond_order[k]] = static_cast<std::int32_t>(k);

  Bonds kept;
  kept.types = b.types;
  for (std::int32_t k : bond_order) {
    kept.Add(new_index[b.i[k]], new_index[b.j[k]], b.type[k], b.kind[k], b.state[k]);
    kept.broken.back() = b.broken[k];
  }
  if (!b.damping_factors.empty())
    for (std::int32_t k : bond_order) kept.damping_factors.push_back(b.damping_factors[k]);
  for (BondBreakEvent e : b.events) {
    if (new_bond[e.bond] == kGone) continue;
    e.bond = new_bond[e.bond];
    kept.events.push_back(e);
  }
  b = std::move(kept);

  for (std::size_t i = 0; i < p.size(); ++i)
    if (keep[i]) p.fibre[i] = fibre_of[i];
  for (auto* v : {&p.x, &p.v, &p.omega, &p.force, &p.torque}) KeepEntries(*v, keep);
  KeepEntries(p.q, keep);
  for (auto* v : {&p.radius, &p.mass, &p.inv_mass, &p.inertia, &p.inv_inertia}) KeepEntries(*v, keep);
  KeepEntries(p.fibre, keep);
  for (auto* v : {&w.applied_force, &w.applied_torque})
    if (v->size() == keep.size()) KeepEntries(*v, keep);
  for (Wall& wall : w.walls)
    if (wall.history.size() == keep.size()) KeepEntries(wall.history, keep);
  net.fibres = std::move(fibres);

  const double skin = w.neighbours.skin();
  w.neighbours = NeighbourList{};
  if (had_list) {
    w.neighbours.Build(p, w.cell, b, skin);
    w.neighbours.ImportHistory(history);
  }
  return removed;
}

SavedMasses ScaleMasses(World& w, double factor) {
  Particles& p = w.particles;
  SavedMasses saved{p.mass, p.inertia};
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.mass[i] *= factor;
    p.inertia[i] *= factor;
    // A fixed particle (inverse 0) stays fixed.
    if (p.inv_mass[i] > 0.0) p.inv_mass[i] = 1.0 / p.mass[i];
    if (p.inv_inertia[i] > 0.0) p.inv_inertia[i] = 1.0 / p.inertia[i];
  }
  return saved;
}

std::vector<BeamBondParams> ScaleFibreStiffness(Network& net, double factor) {
  std::vector<BeamBondParams> saved = net.world.bonds.types;
  for (const FibreRecord& f : net.fibres) {
    BeamBondParams& t = net.world.bonds.types[f.bond_type];
    t.k_n *= factor;
    t.k_s *= factor;
    t.k_b *= factor;
    t.k_t *= factor;
  }
  return saved;
}

void RestoreMasses(World& w, const SavedMasses& saved) {
  Particles& p = w.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.mass[i] = saved.mass[i];
    p.inertia[i] = saved.inertia[i];
    if (p.inv_mass[i] > 0.0) p.inv_mass[i] = 1.0 / p.mass[i];
    if (p.inv_inertia[i] > 0.0) p.inv_inertia[i] = 1.0 / p.inertia[i];
  }
}

void TransformRigidly(World& w, const Mat3& R, const Vec3& shift) {
  const Quat qR(R);
  Particles& p = w.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.x[i] = R * p.x[i] + shift;
    p.v[i] = R * p.v[i];
    p.omega[i] = R * p.omega[i];
    p.q[i] = (qR * p.q[i]).normalized();
  }
  w.neighbours.RotateHistory(R);
  for (Wall& wall : w.walls)
    for (Vec3& h : wall.history) h = R * h;
  for (Blade& blade : w.blades)
    for (Vec3& h : blade.history) h = R * h;
  for (Vec3& f : w.applied_force) f = R * f;
  for (Vec3& t : w.applied_torque) t = R * t;
  w.neighbours.Invalidate();
}

}  // namespace fibrenet::pipeline
