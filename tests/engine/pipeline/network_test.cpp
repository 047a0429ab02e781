#include "engine/pipeline/network.h"

#include <gtest/gtest.h>

#include "engine/pipeline/fibre.h"
#include "tests/engine/pipeline/test_fibre.h"

namespace fibrenet::pipeline {
namespace {

constexpr double kRadius = 16e-6, kSpacing = 32e-6;

FibreProperties Straight(int particles) { return TestFibre(particles * kSpacing); }

// A fibre of `particles` along x starting at (x0, y, z).
void AddStraightFibre(Network& net, int particles, double x0, double y, double z) {
  std::vector<Vec3> centres;
  for (int k = 0; k < particles; ++k) centres.push_back(Vec3(x0 + k * kSpacing, y, z));
  net.AddFibre(Straight(particles), centres, {});
}

Network EmptyNetwork() {
  Network net;
  net.world.cell.hi = Vec3(2e-3, 2e-3, 1e-3);
  return net;
}

void AddFibreFibreBond(Network& net, std::int32_t a, std::int32_t b) {
  World& w = net.world;
  const std::int32_t type = w.bonds.AddType(w.bonds.types[0]);
  w.bonds.Add(a, b, type, BondKind::kFibreFibre,
              MakeBondState(w.cell.Delta(w.particles.x[a], w.particles.x[b]), w.particles.q[a],
                            w.particles.q[b]));
}

TEST(KeepParticles, SplitsFibresAndKeepsTheBondsWhoseEndsStay) {
  Network net = EmptyNetwork();
  AddStraightFibre(net, 6, 1e-4, 1e-4, 1e-4);  // particles 0..5
  AddStraightFibre(net, 6, 1e-4, 3e-4, 1e-4);  // 6..11
  AddStraightFibre(net, 6, 1e-4, 5e-4, 1e-4);  // 12..17
  AddFibreFibreBond(net, 2, 9);                // fibre 0 to the kept half of fibre 1
  AddFibreFibreBond(net, 6, 17);               // the dropped half of fibre 1 to fibre 2
  World& w = net.world;
  w.bonds.broken[7] = 1;  // fibre 1 broke between its particles 2 and 3 (ids 8 and 9)
  w.bonds.events.push_back({.step = 5, .bond = 7});
  w.bonds.events.push_back({.step = 6, .bond = 15});  // the bond 2-9, which stays
  w.bonds.events.push_back({.step = 7, .bond = 16});  // the bond 6-17, which goes
  // Each bond's damping factors name it, to follow it to its new id.
  for (std::size_t b = 0; b < w.bonds.size(); ++b)
    w.bonds.damping_factors.push_back({float(b), float(b) + 0.5f});
  std::vector<std::uint8_t> keep(18, 1);
  for (int i : {6, 7, 8}) keep[i] = 0;
  for (int i = 12; i < 18; ++i) keep[i] = 0;
  const Vec3 x9 = w.particles.x[9];

  EXPECT_EQ(KeepParticles(net, keep), 9u);
  EXPECT_EQ(net.CheckInvariants(), "");
  ASSERT_EQ(w.particles.size(), 9u);
  ASSERT_EQ(net.fibres.size(), 2u);
  EXPECT_EQ(net.fibres[1].first_particle, 6);
  EXPECT_EQ(net.fibres[1].particle_count, 3);
  EXPECT_EQ(net.fibres[1].bond_count, 2);
  EXPECT_DOUBLE_EQ(net.fibres[1].length, 3 * kSpacing);
  EXPECT_EQ(w.particles.x[6], x9);
  EXPECT_EQ(w.particles.fibre[6], 1);
  // 5 + 2 intra-fibre bonds, then the one fibre-fibre bond whose ends both stay.
  ASSERT_EQ(w.bonds.size(), 8u);
  EXPECT_EQ(w.bonds.kind[7], BondKind::kFibreFibre);
  EXPECT_EQ(w.bonds.i[7], 2);
  EXPECT_EQ(w.bonds.j[7], 6);
  // The broken bond lay between a dropped and a kept particle: it goes, with its event; the
  // event of the kept bond names its new id.
  EXPECT_EQ(w.bonds.CountIntact(), 8u);
  ASSERT_EQ(w.bonds.events.size(), 1u);
  EXPECT_EQ(w.bonds.events[0].step, 6);
  EXPECT_EQ(w.bonds.events[0].bond, 7);
  // The kept bonds' damping factors: fibre 0's five, fibre 1's kept pair (bonds 8 and 9),
  // then the fibre-fibre bond 15.
  ASSERT_EQ(w.bonds.damping_factors.size(), 8u);
  const float was[8] = {0, 1, 2, 3, 4, 8, 9, 15};
  for (int b = 0; b < 8; ++b) {
    EXPECT_EQ(w.bonds.damping_factors[b].translation, was[b]) << "bond " << b;
    EXPECT_EQ(w.bonds.damping_factors[b].rotation, was[b] + 0.5f) << "bond " << b;
  }
}

TEST(KeepParticles, ARemovedMiddleParticleLeavesTwoFibresAndABrokenBondCarriesOver) {
  Network net = EmptyNetwork();
  AddStraightFibre(net, 7, 1e-4, 1e-4, 1e-4);
  World& w = net.world;
  w.bonds.broken[0] = 1;
  w.bonds.events.push_back({.step = 3, .bond = 0});
  std::vector<std::uint8_t> keep(7, 1);
  keep[3] = 0;
  EXPECT_EQ(KeepParticles(net, keep), 1u);
  EXPECT_EQ(net.CheckInvariants(), "");
  ASSERT_EQ(net.fibres.size(), 2u);
  EXPECT_EQ(net.fibres[0].particle_count, 3);
  EXPECT_EQ(net.fibres[1].particle_count, 3);
  EXPECT_EQ(net.fibres[1].first_bond, 2);
  ASSERT_EQ(w.bonds.size(), 4u);
  EXPECT_EQ(w.bonds.broken[0], 1);  // a broken bond inside a kept run stays broken
  ASSERT_EQ(w.bonds.events.size(), 1u);
  EXPECT_EQ(w.bonds.events[0].bond, 0);
  EXPECT_NEAR(net.TotalMass(), 6.0 / 7.0 * Straight(7).Mass(), 1e-12 * Straight(7).Mass());
}

TEST(KeepParticles, ContactHistoriesFollowTheirPairs) {
  Network net = EmptyNetwork();
  AddStraightFibre(net, 4, 1e-4, 1e-4, 1e-4);              // 0..3
  AddStraightFibre(net, 4, 1e-4, 1e-4, 1e-4 + 1.9 * kRadius);  // 4..7, touching fibre 0
  World& w = net.world;
  w.neighbours.Build(w.particles, w.cell, w.bonds, 0.5 * kRadius);
  const Vec3 marked(1e-9, 2e-9, 0.0);
  bool found = false;
  for (std::size_t k = w.neighbours.RowBegin(2); k < w.neighbours.RowEnd(2); ++k)
    if (w.neighbours.Partner(k) == 6) {
      w.neighbours.History(k) = marked;
      found = true;
    }
  ASSERT_TRUE(found);
  std::vector<std::uint8_t> keep(8, 1);
  keep[0] = 0;  // indices shift down by one
  KeepParticles(net, keep);
  const std::vector<PairHistory> h = w.neighbours.ExportHistory();
  ASSERT_EQ(h.size(), 1u);
  EXPECT_EQ(h[0].i, 1);
  EXPECT_EQ(h[0].j, 5);
  EXPECT_EQ(h[0].xi, marked);
}

}  // namespace
}  // namespace fibrenet::pipeline
