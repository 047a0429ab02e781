#include "engine/pipeline/metrics.h"

#include <cmath>

#include <gtest/gtest.h>

#include "engine/pipeline/bonding.h"
#include "tests/engine/pipeline/test_fibre.h"

namespace fibrenet::pipeline {
namespace {

// A straight fibre from a to b with particles one diameter apart.
void AddStraight(Network& net, const Vec3& a, const Vec3& b) {
  const FibreProperties f = TestFibre((b - a).norm());
  net.AddFibre(f, PointsAlong({a, b}, ParticlesPerFibre(f.length, f.diameter)), {});
}

Network EmptyNetwork(double side) {
  Network net;
  net.world.cell.lo = Vec3::Zero();
  net.world.cell.hi = Vec3(side, side, 1.0);
  return net;
}

TEST(Metrics, FlatLayerIsOneDiameterThickWithNoTilt) {
  Network net = EmptyNetwork(1e-3);
  const double r = 16e-6;
  for (int k = 0; k < 5; ++k)
    AddStraight(net, Vec3(0.1e-3, (0.1 + 0.15 * k) * 1e-3, r), Vec3(0.9e-3, (0.1 + 0.15 * k) * 1e-3, r));
  const NetworkMetrics m = Measure(net, MetricsSettings{});
  EXPECT_NEAR(m.thickness_um, 32.0, 1e-9);
  EXPECT_NEAR(m.out_of_plane_angle_deg_mean, 0.0, 1e-12);
  EXPECT_NEAR(m.orientation_anisotropy, 1.0, 1e-12);  // all along x
  EXPECT_EQ(m.fibre_count, 5.0);
  EXPECT_EQ(m.crossings_per_fibre, 0.0);
  EXPECT_EQ(m.contacts_per_fibre, 0.0);
  EXPECT_NEAR(m.basis_weight_gsm, 5 * 0.8e-3 * 2.5e-7 / 1e-6 * 1e3, 1e-9);
  EXPECT_NEAR(m.density_kg_per_m3, m.basis_weight_gsm * 1e-3 / 32e-6, 1e-6);
  EXPECT_NEAR(m.porosity, 1.0 - m.density_kg_per_m3 / 1500.0, 1e-12);
}

TEST(Metrics, DensityProfileHoldsTheBasisWeight) {
  Network net = EmptyNetwork(1e-3);
  AddStraight(net, Vec3(0.1e-3, 0.2e-3, 16e-6), Vec3(0.9e-3, 0.3e-3, 16e-6));
  AddStraight(net, Vec3(0.5e-3, 0.1e-3, 47e-6), Vec3(0.4e-3, 0.9e-3, 60e-6));
  const DensityProfile prof = MeasureDensityProfile(net.world, 5e-6);
  double mass_per_area = 0.0;
  for (double d : prof.density) mass_per_area += d * prof.bin;
  EXPECT_NEAR(mass_per_area, net.TotalMass() / net.Area(), 1e-12 * mass_per_area);
}

TEST(Metrics, CrossingFibresCountOnceEachAlsoAcrossThePeriodicFace) {
  Network net = EmptyNetwork(1e-3);
  AddStraight(net, Vec3(0.1e-3, 0.5e-3, 16e-6), Vec3(0.9e-3, 0.5e-3, 16e-6));
  AddStraight(net, Vec3(0.5e-3, 0.1e-3, 48e-6), Vec3(0.5e-3, 0.9e-3, 48e-6));
  // Fibre 4 crosses fibre 3 through the periodic face y = 0 (at y = 1.02 mm = 0.02 mm).
  AddStraight(net, Vec3(0.3e-3, 0.02e-3, 80e-6), Vec3(0.7e-3, 0.02e-3, 80e-6));
  AddStraight(net, Vec3(0.4e-3, 0.9e-3, 112e-6), Vec3(0.4e-3, 1.1e-3, 112e-6));
  double kc = 0.0;
  EXPECT_NEAR(CrossingsPerFibre(net, &kc), 2.0 * 2.0 / 4.0, 1e-12);
  EXPECT_GT(kc, 0.0);
}

TEST(Metrics, TouchingFibresGiveContactsAndThenBonds) {
  Network net = EmptyNetwork(1e-3);
  const double r = 16e-6;
  AddStraight(net, Vec3(0.1e-3, 0.5e-3, r), Vec3(0.9e-3, 0.5e-3, r));
  // Directly on top, slightly pressed into the first (overlap 1 um).
  AddStraight(net, Vec3(0.5e-3, 0.1e-3, 3 * r - 1e-6), Vec3(0.5e-3, 0.9e-3, 3 * r - 1e-6));
  NetworkMetrics m = Measure(net, MetricsSettings{});
  EXPECT_GT(m.contacts_per_fibre, 0.0);
  EXPECT_EQ(m.bonds_per_fibre, 0.0);
  const double contacts = m.contacts_per_fibre;
  const std::size_t made = FormFibreFibreBonds(net, BondingSettings{});
  EXPECT_EQ(static_cast<double>(made), contacts);  // 2 fibres: per fibre = 2 x pairs / 2
  m = Measure(net, MetricsSettings{});
  EXPECT_EQ(m.bonds_per_fibre, contacts);
  EXPECT_EQ(m.contacts_per_fibre, 0.0);  // bonded pairs are no longer contacts
  const BeamBondParams& t = net.world.bonds.types.back();
  EXPECT_EQ(t.failure, BondFailure::kHill);
  EXPECT_DOUBLE_EQ(t.F_r0, 25e-3);
  EXPECT_DOUBLE_EQ(t.F_s0, 5e-3);
  EXPECT_DOUBLE_EQ(t.G_b0, 25e-3 * std::sqrt(t.k_b / t.k_n));
}

TEST(Metrics, RestLengthPolicyKeepsOrRemovesTheOverlap) {
  for (RestLength policy : {RestLength::kCurrent, RestLength::kContact}) {
    Network net = EmptyNetwork(1e-3);
    const double r = 16e-6;
    AddStraight(net, Vec3(0.1e-3, 0.5e-3, r), Vec3(0.9e-3, 0.5e-3, r));
    AddStraight(net, Vec3(0.5e-3, 0.1e-3, 3 * r - 1e-6), Vec3(0.5e-3, 0.9e-3, 3 * r - 1e-6));
    BondingSettings s;
    s.rest_length = policy;
    ASSERT_GT(FormFibreFibreBonds(net, s), 0u);
    const Bonds& b = net.world.bonds;
    const std::size_t last = b.size() - 1;
    const double d = net.world.cell.Delta(net.world.particles.x[b.i[last]],
                                          net.world.particles.x[b.j[last]]).norm();
    if (policy == RestLength::kCurrent) EXPECT_DOUBLE_EQ(b.state[last].L0, d);
    else EXPECT_DOUBLE_EQ(b.state[last].L0, 2 * r);
  }
}

}  // namespace
}  // namespace fibrenet::pipeline
