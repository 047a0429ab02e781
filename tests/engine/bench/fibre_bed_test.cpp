#include "engine/bench/fibre_bed.h"

#include <cmath>
#include <set>
#include <tuple>
#include <utility>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/core/simulation.h"

namespace fibrenet::bench {
namespace {

FibreBedSpec SmallBed() {
  FibreBedSpec s;
  s.particles = 2000;  // 100 fibres
  s.layers = 4;
  return s;
}

TEST(FibreBed, HasTheRequestedParticlesAndFibreBonds) {
  World w;
  const FibreBedInfo info = BuildFibreBed(SmallBed(), w);
  EXPECT_EQ(info.particles, 2000);
  EXPECT_EQ(w.particles.size(), 2000u);
  EXPECT_EQ(info.fibres, 100);
  EXPECT_GE(info.layers, 4);
  // 19 bonds per fibre, each between consecutive particles of one fibre, rest length 2R.
  ASSERT_EQ(info.bonds, 100 * 19);
  ASSERT_EQ(w.bonds.size(), 1900u);
  for (std::size_t b = 0; b < w.bonds.size(); ++b) {
    const std::int32_t i = w.bonds.i[b], j = w.bonds.j[b];
    EXPECT_EQ(j, i + 1);
    EXPECT_EQ(w.particles.fibre[i], w.particles.fibre[j]);
    EXPECT_DOUBLE_EQ(w.bonds.state[b].L0, 32e-6);
    EXPECT_NEAR(w.cell.Delta(w.particles.x[i], w.particles.x[j]).norm(), 32e-6, 1e-12);
    EXPECT_EQ(w.bonds.kind[b], BondKind::kFibre);
  }
  // Full six-mode beam bonds from E = 10 GPa, G = 3 GPa, R = 16 um, L = 32 um.
  const BeamBondParams expected = BeamBondParams::FromBeam(10e9, 3e9, 16e-6, 32e-6);
  ASSERT_EQ(w.bonds.types.size(), 1u);
  EXPECT_DOUBLE_EQ(w.bonds.types[0].k_n, expected.k_n);
  EXPECT_DOUBLE_EQ(w.bonds.types[0].k_s, expected.k_s);
  EXPECT_DOUBLE_EQ(w.bonds.types[0].k_b, expected.k_b);
  EXPECT_DOUBLE_EQ(w.bonds.types[0].k_t, expected.k_t);
  // Particle mass from the coarseness: 2.5e-7 kg/m times one diameter of fibre.
  EXPECT_DOUBLE_EQ(w.particles.mass[0], 2.5e-7 * 32e-6);
  // Physics of the scene: contacts, friction, gravity and a frictional floor.
  EXPECT_TRUE(w.physics.contacts);
  EXPECT_TRUE(w.physics.friction);
  EXPECT_TRUE(w.physics.gravity);
  EXPECT_DOUBLE_EQ(w.contact.mu, 0.3);
  ASSERT_EQ(w.walls.size(), 1u);
  EXPECT_TRUE(w.walls[0].friction);
}

TEST(FibreBed, StartsWithoutOverlapsInsideThePeriodicCell) {
  World w;
  BuildFibreBed(SmallBed(), w);
  const Particles& p = w.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_GE(p.x[i].x(), w.cell.lo.x());
    EXPECT_LT(p.x[i].x(), w.cell.hi.x());
    EXPECT_GE(p.x[i].y(), w.cell.lo.y());
    EXPECT_LT(p.x[i].y(), w.cell.hi.y());
    EXPECT_GT(p.x[i].z() - w.walls[0].z, p.radius[i]);  // clear of the floor
  }
  // Brute force over all pairs: nothing closer than one diameter, bonded pairs included
  // (they sit exactly one diameter apart, touching but not overlapping).
  int overlaps = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j)
      if (w.cell.Delta(p.x[i], p.x[j]).norm() < (p.radius[i] + p.radius[j]) * (1.0 - 1e-12))
        ++overlaps;
  EXPECT_EQ(overlaps, 0);
}

TEST(FibreBed, IsDeterministicForASeed) {
  World a, b;
  BuildFibreBed(SmallBed(), a);
  BuildFibreBed(SmallBed(), b);
  for (std::size_t i = 0; i < a.particles.size(); ++i) ASSERT_EQ(a.particles.x[i], b.particles.x[i]);
}

// --shuffled: the same fibres at the same places, only their order in memory differs.
TEST(FibreBed, AShuffledBedHoldsTheSameFibresInAnotherOrder) {
  FibreBedSpec shuffled = SmallBed();
  shuffled.spatial_order = false;
  World a, b;
  BuildFibreBed(SmallBed(), a);
  BuildFibreBed(shuffled, b);
  ASSERT_EQ(a.particles.size(), b.particles.size());
  auto places = [](const World& w) {
    std::multiset<std::tuple<double, double, double>> out;
    for (const Vec3& x : w.particles.x) out.emplace(x.x(), x.y(), x.z());
    return out;
  };
  EXPECT_EQ(places(a), places(b));
  std::size_t moved = 0;
  for (std::size_t i = 0; i < a.particles.size(); ++i) moved += a.particles.x[i] != b.particles.x[i];
  EXPECT_GT(moved, a.particles.size() / 2);
}

TEST(FibreBed, ContactsFormAfterTheLayersLand) {
  World w;
  BuildFibreBed(SmallBed(), w);
  Simulation sim(w);
  sim.Prepare();
  EXPECT_EQ(CountTouchingPairs(w), 0);
  sim.Run(150);
  const std::int64_t touching = CountTouchingPairs(w);
  EXPECT_GT(touching, 0);
  // Crossing fibres in neighbouring layers touch at a few points per fibre.
  const double per_particle = 2.0 * static_cast<double>(touching) / w.particles.size();
  EXPECT_GT(per_particle, 0.05);
  EXPECT_LT(per_particle, 6.0);
  EXPECT_GT(w.min_contact_ratio, 0.5);  // a gentle landing, far from the stiff branch
}

TEST(FibreBed, RefusesBadSpecsNamingTheField) {
  World w;
  FibreBedSpec s = SmallBed();
  s.particles = 10;
  try {
    BuildFibreBed(s, w);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("particles"), std::string::npos);
  }
  s = SmallBed();
  s.coverage = 0.9;
  EXPECT_THROW(BuildFibreBed(s, w), InputError);
}

}  // namespace
}  // namespace fibrenet::bench
