#include "engine/core/force_buffers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <tuple>
#include <vector>

#include "engine/core/forces.h"
#include "engine/core/parallel.h"
#include "engine/core/quaternion.h"
#include "engine/core/world.h"

namespace fibrenet {
namespace {

constexpr double kR = 16e-6, kL = 32e-6, kMass = 1e-10;

// Chains of particles along x (each fibre's own bonds first), then fibre-fibre bonds
// between random particles, appended after them with the lower index first, as the bonding
// stage does.
World ChainsWithCrossBonds(int fibres, int per_fibre, int cross, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  World w;
  w.cell.lo = Vec3(-1.0, -1.0, -1.0);
  w.cell.hi = Vec3(1.0, 1.0, 1.0);
  const std::int32_t type = w.bonds.AddType(BeamBondParams::FromBeam(10e9, 3e9, kR, kL));
  for (int f = 0; f < fibres; ++f)
    for (int k = 0; k < per_fibre; ++k)
      w.particles.Add(Vec3(k * kL, f * 3 * kR, 0.0), kR, kMass, f);
  const auto add = [&](std::int32_t i, std::int32_t j) {
    Particles& p = w.particles;
    w.bonds.Add(i, j, type, BondKind::kFibreFibre,
                MakeBondState(w.cell.Delta(p.x[i], p.x[j]), p.q[i], p.q[j]));
  };
  for (int f = 0; f < fibres; ++f)
    for (int k = 0; k + 1 < per_fibre; ++k) add(f * per_fibre + k, f * per_fibre + k + 1);
  std::uniform_int_distribution<std::int32_t> any(0, fibres * per_fibre - 1);
  for (int c = 0; c < cross; ++c) {
    const std::int32_t i = any(rng), j = any(rng);
    if (i != j) add(std::min(i, j), std::max(i, j));
  }
  // Strain every bond a little: move and turn each particle.
  for (std::size_t i = 0; i < w.particles.size(); ++i) {
    w.particles.x[i] += 1e-3 * kR * Vec3(u(rng), u(rng), u(rng));
    w.particles.q[i] = QuatFromRotationVector(1e-3 * Vec3(u(rng), u(rng), u(rng)));
  }
  w.settings.dt = 1e-9;
  return w;
}

// One thread walks the bond list in id order; with two, the bonds in their first particle's
// order, cut into two equal shares, each walked by blocks of first particles and within a
// block by second particle (then first particle, then id). Owned by their first particle
// instead, the low range would take most of the fibre-fibre bonds: each has its lower index
// first.
TEST(ForceBuffers, TheRangesTakeEqualSharesOfTheBondsInTheirFirstParticlesOrder) {
  World w = ChainsWithCrossBonds(6, 10, 120, 3);
  const auto nb = static_cast<std::int64_t>(w.bonds.size());
  {
    ScopedThreadCount one(1);
    ForceBuffers buffers;
    buffers.Prepare(w.particles, w.bonds);
    ASSERT_EQ(buffers.Ranges(), 1);
    EXPECT_EQ(buffers.BondRange(0).first, 0);
    EXPECT_EQ(buffers.BondRange(0).second, nb);
    for (std::int64_t k = 0; k < nb; ++k) EXPECT_EQ(buffers.BondOrder()[k], k);
  }
  ScopedThreadCount two(2);
  ForceBuffers buffers;
  buffers.Prepare(w.particles, w.bonds);
  ASSERT_EQ(buffers.Ranges(), 2);
  // The split by first particle is lopsided in this network.
  const std::int64_t low_owned = std::count_if(w.bonds.i.begin(), w.bonds.i.end(), [&](auto i) {
    return i < buffers.ParticleRange(0).second;
  });
  ASSERT_GT(low_owned, nb / 2 + nb / 10);
  EXPECT_EQ(buffers.BondRange(0).first, 0);
  EXPECT_EQ(buffers.BondRange(0).second, buffers.BondRange(1).first);
  EXPECT_EQ(buffers.BondRange(1).second, nb);
  EXPECT_LE(std::abs(2 * buffers.BondRange(0).second - nb), 1);
  // The cut lies in the first particles' order.
  std::int32_t low_max = -1, high_min = std::numeric_limits<std::int32_t>::max();
  for (std::int64_t k = 0; k < nb; ++k) {
    const std::int32_t i = w.bonds.i[buffers.BondOrder()[k]];
    if (k < buffers.BondRange(0).second)
      low_max = std::max(low_max, i);
    else
      high_min = std::min(high_min, i);
  }
  EXPECT_LE(low_max, high_min);
  const auto walk_key = [&](std::int32_t b) {
    return std::make_tuple(w.bonds.i[b] / ForceBuffers::kFirstParticleBlock, w.bonds.j[b],
                           w.bonds.i[b], b);
  };
  std::vector<int> seen(nb, 0);
  for (std::int64_t k = 0; k < nb; ++k) {
    const std::int32_t b = buffers.BondOrder()[k];
    ++seen[b];
    if (k > 0 && k != buffers.BondRange(1).first) {
      const std::int32_t a = buffers.BondOrder()[k - 1];
      EXPECT_LT(walk_key(a), walk_key(b)) << "bonds " << a << ", " << b;
    }
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), nb);  // each bond exactly once
}

// Two threads give every particle the bond forces and torques of one thread, up to the
// rounding of a different order of the additions.
TEST(ForceBuffers, TwoThreadsGiveTheBondForcesOfOne) {
  const World start = ChainsWithCrossBonds(40, 30, 400, 9);
  const auto forces_with = [&](int threads) {
    ScopedThreadCount t(threads);
    World w = start;
    ForceBuffers buffers;
    buffers.Prepare(w.particles, w.bonds);
    StepLosses losses;
    AccumulateBondForces(w, buffers, losses);
    buffers.Reduce();
    return w.particles;
  };
  const Particles one = forces_with(1), two = forces_with(2);
  double force_scale = 0.0, torque_scale = 0.0;
  for (std::size_t i = 0; i < one.size(); ++i) {
    force_scale = std::max(force_scale, one.force[i].norm());
    torque_scale = std::max(torque_scale, one.torque[i].norm());
  }
  ASSERT_GT(force_scale, 0.0);
  ASSERT_GT(torque_scale, 0.0);
  for (std::size_t i = 0; i < one.size(); ++i) {
    EXPECT_LE((two.force[i] - one.force[i]).norm(), 1e-12 * force_scale) << "particle " << i;
    EXPECT_LE((two.torque[i] - one.torque[i]).norm(), 1e-12 * torque_scale) << "particle " << i;
  }
}

}  // namespace
}  // namespace fibrenet
