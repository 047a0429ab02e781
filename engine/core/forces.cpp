#include "engine/core/forces.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <vector>

#include "engine/core/parallel.h"
#include "engine/core/prefetch.h"
#include "engine/interactions/beam_bond_lanes.h"
#include "engine/interactions/contact_lanes.h"

namespace fibrenet {

namespace {

// Gathers the four bonds ids[0..3] into the lanes' input: what SetLane puts in each lane.
// The motions (relative velocity, spins) only where a type damps: the law reads them for the
// damping alone.
void GatherBondLanes(const World& w, const std::vector<BondLanesType>& types,
                     const std::int32_t* ids, BondLanesInput& in) {
  const Particles& p = w.particles;
  const Bonds& bonds = w.bonds;
  std::int32_t i[kBondLanes], j[kBondLanes], type[kBondLanes];
  const BondState* state[kBondLanes];
  for (int l = 0; l < kBondLanes; ++l) {
    i[l] = bonds.i[ids[l]], j[l] = bonds.j[ids[l]], type[l] = bonds.type[ids[l]];
    state[l] = &bonds.state[ids[l]];
  }
  if (type[0] == type[1] && type[0] == type[2] && type[0] == type[3]) {
    SetAllLanesType(in, types[type[0]]);
  } else {
    in.damped = in.viscous = false;
    for (int l = 0; l < kBondLanes; ++l) SetLaneType(in, l, types[type[l]]);
  }
  Vec3 d[kBondLanes];
  for (int l = 0; l < kBondLanes; ++l) d[l] = w.cell.Delta(p.x[i[l]], p.x[j[l]]);
  GatherVec3Lanes(d, in.d);
  GatherQuatLanes({&p.q[i[0]], &p.q[i[1]], &p.q[i[2]], &p.q[i[3]]}, in.q_i);
  GatherQuatLanes({&p.q[j[0]], &p.q[j[1]], &p.q[j[2]], &p.q[j[3]]}, in.q_j);
  GatherQuatLanes({&state[0]->b_i, &state[1]->b_i, &state[2]->b_i, &state[3]->b_i}, in.b_i);
  GatherQuatLanes({&state[0]->b_j, &state[1]->b_j, &state[2]->b_j, &state[3]->b_j}, in.b_j);
  in.L0 = Across([&](int l) { return state[l]->L0; });
  in.dashpot = Across([&](int l) { return state[l]->dashpot; });
  in.plastic_y = Across([&](int l) { return state[l]->plastic_y; });
  in.plastic_z = Across([&](int l) { return state[l]->plastic_z; });
  if (!in.damped) return;
  if (!bonds.damping_factors.empty()) {
    // Each bond's own damping, as EvaluateBond forms it: the type's times the bond's factors.
    const BondDampingFactors* f = bonds.damping_factors.data();
    const Lanes translation = Across([&](int l) { return double(f[ids[l]].translation); });
    const Lanes rotation = Across([&](int l) { return double(f[ids[l]].rotation); });
    in.damping_n = in.damping_n * translation, in.damping_s = in.damping_s * translation;
    in.damping_rot = in.damping_rot * rotation;
  }
  Vec3 v_rel[kBondLanes], omega_i[kBondLanes], omega_j[kBondLanes];
  for (int l = 0; l < kBondLanes; ++l) {
    v_rel[l] = p.v[j[l]] - p.v[i[l]];
    omega_i[l] = p.omega[i[l]];
    omega_j[l] = p.omega[j[l]];
  }
  GatherVec3Lanes(v_rel, in.v_rel);
  GatherVec3Lanes(omega_i, in.omega_i);
  GatherVec3Lanes(omega_j, in.omega_j);
}

// Gathers the neighbour-list entries k[0..3] into the contact lanes' input: the geometry
// the scalar loop builds for EvaluateContact, and each pair's history.
void GatherContactLanes(World& w, const std::size_t (&k)[kLanes], ContactLanesInput& in) {
  const Particles& p = w.particles;
  NeighbourList& nl = w.neighbours;
  std::int32_t i[kLanes], j[kLanes];
  Vec3 d[kLanes], v_rel[kLanes], omega_i[kLanes], omega_j[kLanes], xi[kLanes];
  for (int l = 0; l < kLanes; ++l) {
    i[l] = nl.Owner(k[l]), j[l] = nl.Partner(k[l]);
    d[l] = w.cell.Delta(p.x[i[l]], p.x[j[l]]);
    v_rel[l] = p.v[j[l]] - p.v[i[l]];
    omega_i[l] = p.omega[i[l]], omega_j[l] = p.omega[j[l]];
    xi[l] = nl.History(k[l]);
  }
  GatherVec3Lanes(d, in.d);
  in.dist = lanes::Sqrt(lanes::Dot(in.d, in.d));
  in.r_i = Across([&](int l) { return p.radius[i[l]]; });
  in.r_j = Across([&](int l) { return p.radius[j[l]]; });
  const Lanes m_i = Across([&](int l) { return p.mass[i[l]]; });
  const Lanes m_j = Across([&](int l) { return p.mass[j[l]]; });
  in.m_eff = m_i * m_j / (m_i + m_j);
  GatherVec3Lanes(v_rel, in.v_rel);
  GatherVec3Lanes(omega_i, in.omega_i);
  GatherVec3Lanes(omega_j, in.omega_j);
  GatherVec3Lanes(xi, in.xi);
}

// The normal law's energy of particles i and j, d = x_j - x_i apart; 0 when apart. Their
// friction history starts empty, so the tangential spring holds nothing.
double OverlapEnergy(const World& w, std::int32_t i, std::int32_t j, const Vec3& d) {
  const double sum_radii = w.particles.radius[i] + w.particles.radius[j];
  const double dist = d.norm();
  return dist < sum_radii ? EvaluateVanWyk(dist, sum_radii, w.contact.normal).energy : 0.0;
}

// How far ahead the bond walk asks for memory, in bonds: a bond's partner's data
// kBondPrefetchDistance bonds ahead, the bond's own record (whose partner index that needs)
// twice as far. The contact loop asks for a pair's partner kContactPrefetchDistance pairs
// ahead. Chosen on the 10 mm sheet's ZD compression (docs/performance.md, "Prefetching the
// partners"): 4 to 32 bonds did about equally well, 32 pairs better than 8 or 16.
constexpr std::int64_t kBondPrefetchDistance = 8;
constexpr std::size_t kContactPrefetchDistance = 32;

// Bond b's own data, which the walk reads before its particles'.
// Forced inline, as in prefetch.h: a call to a function that only prefetches is dropped.
[[gnu::always_inline]] inline void PrefetchBondRecord(const Bonds& bonds, std::int32_t b) {
  PrefetchForRead(&bonds.i[b]);
  PrefetchForRead(&bonds.j[b]);
  PrefetchForRead(&bonds.type[b]);
  PrefetchForRead(&bonds.broken[b]);
  PrefetchObjectForRead(&bonds.state[b]);
  if (!bonds.damping_factors.empty()) PrefetchForRead(&bonds.damping_factors[b]);
}

// What the walk reads and writes of particle j, a bond's partner. The first particle i needs
// nothing: the walk takes the first particles block by block (ForceBuffers::BondOrder), so
// theirs is in the cache (asking for it too gained nothing).
[[gnu::always_inline]] inline void PrefetchPartner(const Particles& p, std::int32_t j) {
  PrefetchForRead(&p.x[j]);
  PrefetchObjectForRead(&p.q[j]);
  PrefetchForRead(&p.v[j]);
  PrefetchForRead(&p.omega[j]);
  PrefetchForWrite(&p.force[j]);
  PrefetchForWrite(&p.torque[j]);
}

}  // namespace

void AccumulateBondForces(World& w, ForceBuffers& buffers, StepLosses& losses) {
  Particles& p = w.particles;
  Bonds& bonds = w.bonds;
  const double dt = w.settings.dt;
  // The bond types as the lanes read them (beam_bond_lanes.h); a bond of a type they do not
  // take goes alone.
  std::vector<BondLanesType> lanes_types(bonds.types.size());
  for (std::size_t t = 0; t < bonds.types.size(); ++t)
    lanes_types[t] = LanesTypeOf(bonds.types[t], dt);
  double inelastic = 0.0, released = 0.0, regained = 0.0;
  int broke = 0;
#pragma omp parallel reduction(+ : inelastic, released, regained) reduction(| : broke)
  for (int range = ThreadId(); range < buffers.Ranges(); range += TeamSize()) {
    ForceBuffers::Writer out = buffers.WriterFor(range);
    // Plain names, not a structured binding: the lambda below captures them. The range's
    // bonds are order[first..last).
    const std::int32_t* order = buffers.BondOrder();
    const std::int64_t first = buffers.BondRange(range).first;
    const std::int64_t last = buffers.BondRange(range).second;
    // Four bonds side by side where they can go so; each bond's forces are those of
    // EvaluateBond bit for bit, so the grouping changes no result.
    const auto lanes_fit = [&](std::int64_t k) {
      if (last - k < kBondLanes) return false;
      for (int l = 0; l < kBondLanes; ++l) {
        const std::int32_t b = order[k + l];
        if (bonds.broken[b] || !lanes_types[bonds.type[b]].taken) return false;
      }
      return true;
    };
    // The forces go out bond by bond in order either way, so the sums keep their order.
    BondLanesInput input;
    BondLanesResult group;
    std::uint32_t from_lanes = 0;  // bit l: bond (group start + l) has its result in group
    for (std::int64_t k = first; k < last; ++k) {
      const std::int32_t b = order[k];
      const int lane = static_cast<int>((k - first) % kBondLanes);
      if (lane == 0) {
        for (int l = 0; l < kBondLanes; ++l) {
          if (k + kBondPrefetchDistance + l < last)
            PrefetchPartner(p, bonds.j[order[k + kBondPrefetchDistance + l]]);
          if (k + 2 * kBondPrefetchDistance + l < last)
            PrefetchBondRecord(bonds, order[k + 2 * kBondPrefetchDistance + l]);
        }
        from_lanes = 0;
        if (lanes_fit(k)) {
          GatherBondLanes(w, lanes_types, order + k, input);
          EvaluateBondLanes(input, dt, group);
          for (int l = 0; l < kBondLanes; ++l)
            if (LaneHolds(group, l)) from_lanes |= 1u << l;
        }
      }
      if (from_lanes >> lane & 1u) {
        const std::int32_t i = bonds.i[b], j = bonds.j[b];
        const Vec3 f(group.force_i.x[lane], group.force_i.y[lane], group.force_i.z[lane]);
        out.Add(i, f, Vec3(group.torque_i.x[lane], group.torque_i.y[lane], group.torque_i.z[lane]));
        out.AddReaction(
            j, f, Vec3(group.torque_j.x[lane], group.torque_j.y[lane], group.torque_j.z[lane]));
        inelastic += group.dissipated[lane];
        if (input.viscous) bonds.state[b].dashpot = group.dashpot[lane];
        continue;
      }
      if (bonds.broken[b]) continue;
      const std::int32_t i = bonds.i[b], j = bonds.j[b];
      const BondGeometry g{
          w.cell.Delta(p.x[i], p.x[j]), p.q[i], p.q[j], p.v[j] - p.v[i], p.omega[i], p.omega[j]};
      const BondResult r =
          EvaluateBond(g, bonds.types[bonds.type[b]], bonds.state[b], dt, bonds.DampingFactors(b));
      inelastic += r.dissipated;
      if (r.broken) {
        bonds.broken[b] = 1;
        released += r.Energy();
        // The pair meets as a contact once the list is built again, at the end of this step
        // (it leaves out bonded pairs only): an overlap the bond held comes back as energy.
        if (w.physics.contacts) regained += OverlapEnergy(w, i, j, g.d);
        broke = 1;
        BondBreakEvent e;
        e.step = w.step;
        e.bond = b;
        e.position = p.x[i] + 0.5 * g.d;
        e.f_r = r.f_r;
        e.f_s = r.f_s;
        e.tau_b = r.tau_b;
        e.tau_t = r.tau_t;
        e.energy = r.Energy();
#pragma omp critical(fibrenet_bond_events)
        bonds.events.push_back(e);
        continue;
      }
      out.Add(i, r.force_i, r.torque_i);
      out.AddReaction(j, r.force_i, r.torque_j);
    }
  }
  if (broke) {
    // Threads append in any order; sort this step's events so runs are reproducible.
    auto first = std::find_if(bonds.events.begin(), bonds.events.end(),
                              [&](const BondBreakEvent& e) { return e.step == w.step; });
    std::sort(first, bonds.events.end(),
              [](const BondBreakEvent& a, const BondBreakEvent& b) { return a.bond < b.bond; });
  }
  losses.bond_inelastic += inelastic;
  losses.released += released;
  losses.overlap_regained += regained;
  losses.bonds_broke = losses.bonds_broke || broke;
}

void AccumulateContactForces(World& w, ForceBuffers& buffers, StepLosses& losses) {
  Particles& p = w.particles;
  NeighbourList& nl = w.neighbours;
  const double dt = w.settings.dt;
  const bool friction = w.physics.friction;
  // Pairs go in blocks: a first pass finds which of them touch, without a branch on it (about
  // half the pairs of a packing touch, in no order the processor could predict), and clears
  // the history of a pair that has come apart; a second pass evaluates the touching pairs in
  // their order, so every force is added as a loop over all pairs would add it.
  constexpr std::size_t kBlock = 256;
  double damping = 0.0, slip = 0.0, min_ratio = 1.0;
#pragma omp parallel reduction(+ : damping, slip) reduction(min : min_ratio)
  for (int range = ThreadId(); range < buffers.Ranges(); range += TeamSize()) {
    // Rows of this range: the owner i is always in it, the partner j anywhere.
    ForceBuffers::Writer out = buffers.WriterFor(range);
    const auto [first, last] = buffers.ParticleRange(range);
    const std::size_t pairs_end = nl.RowBegin(last);
    std::uint32_t touching[kBlock];
    for (std::size_t block = nl.RowBegin(first); block < pairs_end; block += kBlock) {
      const std::size_t block_end = std::min(block + kBlock, pairs_end);
      std::size_t count = 0;
      for (std::size_t k = block; k < block_end; ++k) {
        // The partner's position and radius, for the pair this many ahead (the owner's are
        // near: a row's pairs share it).
        if (k + kContactPrefetchDistance < pairs_end) {
          const std::int32_t ahead = nl.Partner(k + kContactPrefetchDistance);
          PrefetchForRead(&p.x[ahead]);
          PrefetchForRead(&p.radius[ahead]);
        }
        const std::int32_t i = nl.Owner(k), j = nl.Partner(k);
        const double sum_radii = p.radius[i] + p.radius[j];
        // Written as "not apart" so that a non-finite distance counts as touching, and its
        // forces carry it on to the non-finite check.
        const bool touch = !(w.cell.Delta(p.x[i], p.x[j]).squaredNorm() >= sum_radii * sum_radii);
        touching[count] = static_cast<std::uint32_t>(k - block);
        count += touch ? 1 : 0;
        // Apart: the next touch starts afresh. Writing only when needed keeps the cache
        // lines of the many pairs already clear clean.
        Vec3& xi = nl.History(k);
        const int held = static_cast<int>(xi.x() != 0.0) | static_cast<int>(xi.y() != 0.0) |
                         static_cast<int>(xi.z() != 0.0);
        if (static_cast<int>(!touch) & held) xi.setZero();
      }
      // Four touching pairs at a time through the lanes, the rest one by one; each pair's
      // results equal EvaluateContact's bit for bit and go out in the same order.
      std::size_t c = 0;
      for (; c + kLanes <= count; c += kLanes) {
        // The next group's partners: their motion, mass, force and torque.
        for (std::size_t a = c + kLanes; a < std::min(count, c + 2 * kLanes); ++a) {
          const std::int32_t ahead = nl.Partner(block + touching[a]);
          PrefetchForRead(&p.v[ahead]);
          PrefetchForRead(&p.omega[ahead]);
          PrefetchForRead(&p.mass[ahead]);
          PrefetchForWrite(&p.force[ahead]);
          PrefetchForWrite(&p.torque[ahead]);
        }
        std::size_t k[kLanes];
        for (int l = 0; l < kLanes; ++l) k[l] = block + touching[c + l];
        ContactLanesInput in;
        GatherContactLanes(w, k, in);
        ContactLanesResult r;
        EvaluateContactLanes(in, w.contact, dt, friction, r);
        for (int l = 0; l < kLanes; ++l) {
          const Vec3 force_j(r.force_j.x[l], r.force_j.y[l], r.force_j.z[l]);
          out.AddReaction(nl.Owner(k[l]), force_j,
                          Vec3(r.torque_i.x[l], r.torque_i.y[l], r.torque_i.z[l]));
          out.Add(nl.Partner(k[l]), force_j,
                  Vec3(r.torque_j.x[l], r.torque_j.y[l], r.torque_j.z[l]));
          nl.History(k[l]) = Vec3(r.xi.x[l], r.xi.y[l], r.xi.z[l]);
          damping += r.damping_power[l] * dt;
          slip += r.slip_loss[l];
          min_ratio = std::min(min_ratio, in.dist[l] / (in.r_i[l] + in.r_j[l]));
        }
      }
      for (; c < count; ++c) {
        const std::size_t k = block + touching[c];
        const std::int32_t i = nl.Owner(k), j = nl.Partner(k);
        const Vec3 d = w.cell.Delta(p.x[i], p.x[j]);
        const double sum_radii = p.radius[i] + p.radius[j];
        const double dist = std::sqrt(d.squaredNorm());
        const double m_sum = p.mass[i] + p.mass[j];
        const ContactGeometry g{d,
                                dist,
                                p.radius[i],
                                p.radius[j],
                                p.mass[i] * p.mass[j] / m_sum,
                                p.v[j] - p.v[i],
                                p.omega[i],
                                p.omega[j]};
        const ContactResult r = EvaluateContact(g, w.contact, nl.History(k), dt, friction);
        out.AddReaction(i, r.force_j, r.torque_i);
        out.Add(j, r.force_j, r.torque_j);
        damping += r.damping_power * dt;
        slip += r.slip_loss;
        min_ratio = std::min(min_ratio, dist / sum_radii);
      }
    }
  }
  losses.damping += damping;
  losses.friction += slip;
  losses.min_contact_ratio = std::min(losses.min_contact_ratio, min_ratio);
}

namespace {

// Contact of particle i with a rigid surface at centre distance `gap`, `normal` pointing from
// the surface into the particle, the surface moving with `surface_velocity`: the surface acts
// as the particle's mirror image (centre distance 2 gap, radii R and R, the image's mass
// infinite), plus the surface's optional hard core below hard_gap radii. Returns the force on
// the surface (on the particle it is the opposite) and the particle's torque.
struct SurfaceResult {
  Vec3 on_surface;
  Vec3 torque;
  double damping_power, slip_loss;
};
SurfaceResult SurfaceContact(const World& w, const ContactParams& law, std::int64_t i,
                             const Vec3& normal, double gap, const Vec3& surface_velocity,
                             Vec3& history, bool friction, double hard_stiffness, double hard_gap) {
  const Particles& p = w.particles;
  const double dist = std::max(2.0 * gap, 1e-3 * p.radius[i]);
  const ContactGeometry g{-dist * normal, dist,        p.radius[i],
                          p.radius[i],    p.mass[i],   surface_velocity - p.v[i],
                          p.omega[i],     Vec3::Zero()};
  const ContactResult r = EvaluateContact(g, law, history, w.settings.dt, friction);
  SurfaceResult out{r.force_j, r.torque_i, r.damping_power, r.slip_loss};
  const double core = hard_gap * p.radius[i] - gap;
  if (core > 0.0 && hard_stiffness > 0.0) out.on_surface -= hard_stiffness * core * normal;
  return out;
}

void ClearHistory(Vec3& xi) {
  if (xi.x() != 0.0 || xi.y() != 0.0 || xi.z() != 0.0) xi.setZero();
}

// One rigid surface against the free particles: touch(i) gives the particle's centre-to-
// surface gap and the normal pointing into it. Checks every particle, or only those of
// `reach` (ascending; every other particle is known to be apart, its history clear). Each
// thread takes its static share of all the particles either way, so the reductions are summed
// in the same order. Adds the forces and torques, returns the force the particles exert on
// the surface, and books the losses.
template <class TouchOf>
Vec3 AccumulateSurface(World& w, const ContactParams& law, TouchOf touch,
                       const Vec3& surface_velocity, std::vector<Vec3>& history, bool friction,
                       double hard_stiffness, double hard_gap,
                       const std::vector<std::int32_t>* reach, StepLosses& losses) {
  Particles& p = w.particles;
  const std::int64_t n = static_cast<std::int64_t>(p.size());
  const double dt = w.settings.dt;
  if (history.size() != p.size()) history.assign(p.size(), Vec3::Zero());
  const std::int32_t* members = reach ? reach->data() : nullptr;
  const std::int32_t* members_end = reach ? members + reach->size() : nullptr;
  double fx = 0.0, fy = 0.0, fz = 0.0, damping = 0.0, slip = 0.0, min_ratio = 1.0;
#pragma omp parallel reduction(+ : fx, fy, fz, damping, slip) reduction(min : min_ratio)
  {
    std::int64_t first, end;
    std::tie(first, end) = StaticShare(n, ThreadId(), TeamSize());
    if (members) {
      const std::int32_t* from = std::lower_bound(members, members_end, first);
      const std::int32_t* to = std::lower_bound(from, members_end, end);
      first = from - members;
      end = to - members;
    }
    for (std::int64_t k = first; k < end; ++k) {
      const std::int64_t i = members ? members[k] : k;
      const Blade::Touch t = touch(i);
      // A fixed particle's motion is prescribed: surfaces act on free particles only.
      if (t.gap >= p.radius[i] || p.inv_mass[i] == 0.0) {
        ClearHistory(history[i]);
        continue;
      }
      const SurfaceResult r = SurfaceContact(w, law, i, t.normal, t.gap, surface_velocity,
                                             history[i], friction, hard_stiffness, hard_gap);
      p.force[i] -= r.on_surface;
      p.torque[i] += r.torque;
      fx += r.on_surface.x();
      fy += r.on_surface.y();
      fz += r.on_surface.z();
      damping += r.damping_power * dt;
      slip += r.slip_loss;
      min_ratio = std::min(min_ratio, std::max(t.gap, 5e-4 * p.radius[i]) / p.radius[i]);
    }
  }
  losses.damping += damping;
  losses.friction += slip;
  losses.min_contact_ratio = std::min(losses.min_contact_ratio, min_ratio);
  return Vec3(fx, fy, fz);
}

// The particles a wall can touch before the neighbour list is built again or the wall has
// moved by half the skin, whichever comes first; null (check them all) without a built list.
// Since the list's build every particle has moved by at most half the skin, so by at most a
// skin from where it is now: one further than 1.5 skins from the surface's nearest point (the
// relief's highest) cannot reach it while the wall moves by less than half a skin. The others'
// histories are cleared, as a check that found them apart would.
const std::vector<std::int32_t>* WallReachOf(World& w, Wall& wall) {
  const Particles& p = w.particles;
  const NeighbourList& nl = w.neighbours;
  if (!w.physics.contacts || nl.Stale(p.size())) return nullptr;
  WallReach& reach = wall.reach;
  const double skin = nl.skin();
  if (reach.list_build == nl.build_id() && reach.side == wall.side &&
      reach.relief == wall.relief && std::abs(wall.z - reach.z) <= 0.5 * skin)
    return &reach.particles;
  if (wall.history.size() != p.size()) wall.history.assign(p.size(), Vec3::Zero());
  const double nearest = wall.z + wall.side * (wall.relief ? wall.relief->Max() : 0.0);
  reach.particles.clear();
  for (std::size_t i = 0; i < p.size(); ++i) {
    if ((p.x[i].z() - nearest) * wall.side < p.radius[i] + 1.5 * skin)
      reach.particles.push_back(static_cast<std::int32_t>(i));
    else
      ClearHistory(wall.history[i]);
  }
  reach.list_build = nl.build_id();
  reach.z = wall.z;
  reach.side = wall.side;
  reach.relief = wall.relief;
  return &reach.particles;
}

}  // namespace

void AccumulateWallForces(World& w, StepLosses& losses) {
  const Particles& p = w.particles;
  const ContactParams law = w.contact.ForSurface();
  for (Wall& wall : w.walls) {
    const Vec3 normal(0.0, 0.0, static_cast<double>(wall.side));  // points into the particles
    const Relief* relief = wall.relief.get();
    auto touch = [&](std::int64_t i) {
      const double surface =
          relief ? wall.z + wall.side * relief->At(p.x[i].x(), p.x[i].y()) : wall.z;
      return Blade::Touch{normal, (p.x[i].z() - surface) * wall.side};  // centre to wall
    };
    wall.reaction = AccumulateSurface(w, law, touch, Vec3(0.0, 0.0, wall.vz), wall.history,
                                      w.physics.friction && wall.friction, wall.hard_stiffness,
                                      wall.hard_gap, WallReachOf(w, wall), losses);
    // Energy the moving wall feeds in: force on the particles times the wall's travel.
    wall.work += -wall.reaction.z() * wall.vz * w.settings.dt;
  }
}

void AccumulateBladeForces(World& w, StepLosses& losses) {
  const Particles& p = w.particles;
  const ContactParams surface_law = w.contact.ForSurface();
  for (Blade& blade : w.blades) {
    ContactParams law = surface_law;
    if (blade.mu) law.mu = *blade.mu;
    auto touch = [&](std::int64_t i) { return blade.Nearest(p.x[i]); };
    blade.reaction = AccumulateSurface(w, law, touch, blade.velocity, blade.history,
                                       w.physics.friction && blade.friction, blade.hard_stiffness,
                                       blade.hard_gap, nullptr, losses);
    blade.work += -blade.reaction.dot(blade.velocity) * w.settings.dt;
  }
}

void StartForces(World& w) {
  Particles& p = w.particles;
  const Physics& ph = w.physics;
  const std::int64_t n = static_cast<std::int64_t>(p.size());
  // One pass that both clears and loads: the particle arrays are the largest stream here.
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    Vec3 f = Vec3::Zero();
    if (ph.gravity) f += p.mass[i] * ph.g;
    if (ph.drag) f -= ph.drag_coefficient * (p.v[i] - ph.air_velocity);
    if (ph.applied_loads) {
      f += w.applied_force[i];
      p.torque[i] = w.applied_torque[i];
    } else {
      p.torque[i].setZero();
    }
    p.force[i] = f;
  }
}

}  // namespace fibrenet
