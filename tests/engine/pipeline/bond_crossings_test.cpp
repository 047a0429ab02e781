#include "engine/pipeline/bond_crossings.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "engine/pipeline/bonding.h"
#include "tests/engine/pipeline/test_fibre.h"

namespace fibrenet::pipeline {
namespace {

constexpr double kRadius = 16e-6;

double Length(const std::vector<Vec3>& polyline) {
  double length = 0.0;
  for (std::size_t k = 1; k < polyline.size(); ++k) length += (polyline[k] - polyline[k - 1]).norm();
  return length;
}

// A fibre along the polyline with particles `spacing` diameters apart.
void AddFibre(Network& net, const std::vector<Vec3>& polyline, double spacing) {
  const FibreProperties f = TestFibre(Length(polyline));
  net.AddFibre(f, PointsAlong(polyline, ParticlesPerFibre(f.length, spacing * f.diameter)), {});
}

// Fibre 0 along x on the wire; fibre 1 along y on top of it, its centreline 0.85 of a
// diameter above fibre 0's: a pressed crossing, as the consolidation leaves them.
Network Crossing(double spacing) {
  Network net;
  net.world.cell.lo = Vec3::Zero();
  net.world.cell.hi = Vec3(1e-3, 1e-3, 1.0);
  const double top = kRadius + 0.85 * 2 * kRadius;
  AddFibre(net, {Vec3(0.1e-3, 0.5e-3, kRadius), Vec3(0.9e-3, 0.5e-3, kRadius)}, spacing);
  AddFibre(net, {Vec3(0.5e-3, 0.1e-3, top), Vec3(0.5e-3, 0.9e-3, top)}, spacing);
  return net;
}

BondingSettings Share(BondShare share) {
  BondingSettings s;
  s.share = share;
  return s;
}

// The crossing's bonds under a rigid lift of the top fibre, linearised: per metre of lift,
// the force each bond puts on the lifted fibre (z) and the rise of its failure index.
struct BondUnderLift {
  double force_z = 0.0, index = 0.0;
};

std::vector<BondUnderLift> LiftTopFibre(const Network& net) {
  const World& w = net.world;
  const Particles& p = w.particles;
  const double dz = 1e-10;  // far inside the linear range of the bond law
  std::vector<BondUnderLift> out;
  for (std::size_t b = 0; b < w.bonds.size(); ++b) {
    if (w.bonds.kind[b] != BondKind::kFibreFibre) continue;
    const std::int32_t i = w.bonds.i[b], j = w.bonds.j[b];
    const double sign = p.fibre[j] == 1 ? 1.0 : -1.0;  // +1: j is on the lifted fibre
    BondGeometry g;
    g.d = w.cell.Delta(p.x[i], p.x[j]) + Vec3(0, 0, sign * dz);
    g.q_i = p.q[i], g.q_j = p.q[j];
    g.v_rel = g.omega_i = g.omega_j = Vec3::Zero();
    BondState state = w.bonds.state[b];
    const BondResult r = EvaluateBond(g, w.bonds.types[w.bonds.type[b]], state, 0.0);
    out.push_back({sign * -r.force_i.z() / dz, r.failure_index / dz});
  }
  return out;
}

// The crossing as a whole under a rigid, quasi-static lift: its stiffness, and its pull-off
// force as its bonds fail one after the other (each at its own lift; the peak of the force
// the survivors carry).
struct CrossingResponse {
  std::size_t bonds = 0;
  double stiffness = 0.0, pull_off = 0.0;
};

CrossingResponse Respond(double spacing, BondShare share) {
  Network net = Crossing(spacing);
  CrossingResponse r;
  r.bonds = FormFibreFibreBonds(net, Share(share));
  std::vector<BondUnderLift> bonds = LiftTopFibre(net);
  std::sort(bonds.begin(), bonds.end(), [](const BondUnderLift& l, const BondUnderLift& m) {
    return l.index > m.index;  // the first to fail first
  });
  double carrying = 0.0;  // downward stiffness of the bonds still intact
  for (const BondUnderLift& b : bonds) carrying -= b.force_z;
  r.stiffness = carrying;
  for (const BondUnderLift& b : bonds) {
    r.pull_off = std::max(r.pull_off, carrying / b.index);  // at the lift that breaks b
    carrying += b.force_z;
  }
  return r;
}

TEST(BondCrossings, ReachIsTheParticlesInOneDiameterPlusOne) {
  FibreRecord f;
  f.diameter = 32e-6;
  f.length = 32e-6 * 40;
  f.particle_count = 40;  // one diameter apart
  EXPECT_EQ(CrossingReach(f), 2);
  f.particle_count = 80;  // half a diameter
  EXPECT_EQ(CrossingReach(f), 3);
  f.particle_count = 20;  // two diameters
  EXPECT_EQ(CrossingReach(f), 2);
}

TEST(BondCrossings, OneCrossingHoldsAllItsParticleBondsAtEverySpacing) {
  for (double spacing : {1.0, 0.5, 0.25}) {
    Network net = Crossing(spacing);
    const std::size_t made = FormFibreFibreBonds(net, BondingSettings{});
    ASSERT_GT(made, 0u) << spacing;
    const BondCrossings c = GroupBondsByCrossing(net);
    EXPECT_EQ(c.bonds.size(), made) << spacing;
    ASSERT_EQ(c.size.size(), 1u) << spacing;
    EXPECT_EQ(static_cast<std::size_t>(c.size[0]), made) << spacing;
  }
}

TEST(BondCrossings, AFibreMeetingAnotherTwiceMakesTwoCrossings) {
  Network net;
  net.world.cell.lo = Vec3::Zero();
  net.world.cell.hi = Vec3(1e-3, 1e-3, 1.0);
  const double top = kRadius + 0.85 * 2 * kRadius;
  AddFibre(net, {Vec3(0.1e-3, 0.5e-3, kRadius), Vec3(0.9e-3, 0.5e-3, kRadius)}, 0.5);
  // A kinked fibre crossing fibre 0 at x = 0.4 mm and x = 0.6 mm.
  AddFibre(net, {Vec3(0.3e-3, 0.3e-3, top), Vec3(0.5e-3, 0.7e-3, top), Vec3(0.7e-3, 0.3e-3, top)},
           0.5);
  const std::size_t made = FormFibreFibreBonds(net, BondingSettings{});
  const BondCrossings c = GroupBondsByCrossing(net);
  ASSERT_EQ(c.size.size(), 2u);
  EXPECT_EQ(static_cast<std::size_t>(c.size[0] + c.size[1]), made);
  EXPECT_GT(c.size[0], 0);
  EXPECT_GT(c.size[1], 0);
}

TEST(BondCrossings, BrokenBondsLeaveTheirCrossing) {
  Network net = Crossing(0.5);
  const std::size_t made = FormFibreFibreBonds(net, BondingSettings{});
  ASSERT_GE(made, 2u);
  net.world.bonds.broken.back() = 1;
  const BondCrossings c = GroupBondsByCrossing(net);
  ASSERT_EQ(c.size.size(), 1u);
  EXPECT_EQ(static_cast<std::size_t>(c.size[0]), made - 1);
}

TEST(BondCrossings, PerCrossingTheParticleBondsShareOneBondsPropertiesExactly) {
  const BondingSettings s;
  const BeamBondParams one = BeamBondParams::FromBeam(
      s.transverse_modulus, s.transverse_shear_modulus, s.bond_radius_fraction * kRadius,
      2 * kRadius);
  for (double spacing : {1.0, 0.5, 0.25}) {
    Network net = Crossing(spacing);
    const std::size_t made = FormFibreFibreBonds(net, Share(BondShare::kCrossing));
    double k_n = 0, k_s = 0, k_b = 0, k_t = 0, F_r0 = 0, F_s0 = 0;
    const Bonds& b = net.world.bonds;
    for (std::size_t k = 0; k < b.size(); ++k) {
      if (b.kind[k] != BondKind::kFibreFibre) continue;
      const BeamBondParams& t = b.types[b.type[k]];
      k_n += t.k_n, k_s += t.k_s, k_b += t.k_b, k_t += t.k_t, F_r0 += t.F_r0, F_s0 += t.F_s0;
      EXPECT_DOUBLE_EQ(t.G_b0, t.F_r0 * std::sqrt(t.k_b / t.k_n));
      EXPECT_EQ(t.failure, BondFailure::kHill);
    }
    SCOPED_TRACE(::testing::Message() << "spacing " << spacing << ", " << made << " bonds");
    EXPECT_NEAR(k_n, one.k_n, 1e-12 * one.k_n);
    EXPECT_NEAR(k_s, one.k_s, 1e-12 * one.k_s);
    EXPECT_NEAR(k_b, one.k_b, 1e-12 * one.k_b);
    EXPECT_NEAR(k_t, one.k_t, 1e-12 * one.k_t);
    EXPECT_NEAR(F_r0, s.F_r0, 1e-12 * s.F_r0);
    EXPECT_NEAR(F_s0, s.F_s0, 1e-12 * s.F_s0);
  }
}

// The physical check: a crossing lifted apart. Per particle its stiffness and pull-off grow
// with the bonds the spacing puts in it (1 at one diameter here, 4 at a half, 12 at a
// quarter). Per crossing they stay within 20% and 40% of the one-bond crossing: what is
// left comes from the bonds at the crossing's edge, inclined to the lift, which take shear
// (F_s0 = F_r0 / 5) and fail first.
TEST(BondCrossings, PerCrossingALiftedCrossingKeepsItsStiffnessAndStrengthAtAnySpacing) {
  const CrossingResponse coarse = Respond(1.0, BondShare::kCrossing);
  const CrossingResponse coarse_p = Respond(1.0, BondShare::kParticle);
  ASSERT_EQ(coarse.bonds, coarse_p.bonds);
  for (double spacing : {0.5, 0.25}) {
    const CrossingResponse fine = Respond(spacing, BondShare::kCrossing);
    const CrossingResponse fine_p = Respond(spacing, BondShare::kParticle);
    ASSERT_EQ(fine.bonds, fine_p.bonds);
    ASSERT_GE(fine.bonds, 4 * coarse.bonds);  // the spacing changes the bond count
    std::printf("spacing 1 / %g: bonds %zu / %zu; per crossing: stiffness %.4g / %.4g N/m, "
                "pull-off %.4g / %.4g mN; per particle: %.4g / %.4g N/m, %.4g / %.4g mN\n",
                spacing, coarse.bonds, fine.bonds, coarse.stiffness, fine.stiffness,
                1e3 * coarse.pull_off, 1e3 * fine.pull_off, coarse_p.stiffness,
                fine_p.stiffness, 1e3 * coarse_p.pull_off, 1e3 * fine_p.pull_off);
    EXPECT_NEAR(fine.stiffness / coarse.stiffness, 1.0, 0.2) << spacing;
    EXPECT_NEAR(fine.pull_off / coarse.pull_off, 1.0, 0.4) << spacing;
    EXPECT_NEAR(coarse.pull_off, Share(BondShare::kCrossing).F_r0, 1e-6);  // one aligned bond
    EXPECT_GT(fine_p.stiffness / coarse_p.stiffness, 3.0) << spacing;
    EXPECT_GT(fine_p.pull_off / coarse_p.pull_off, 2.5) << spacing;
  }
}

}  // namespace
}  // namespace fibrenet::pipeline
