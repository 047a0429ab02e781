#include "engine/pipeline/fibre.h"

#include <cmath>

#include <gtest/gtest.h>

#include "engine/pipeline/network.h"

namespace fibrenet::pipeline {
namespace {

double PolylineLength(const std::vector<Vec3>& p) {
  double l = 0.0;
  for (std::size_t k = 1; k < p.size(); ++k) l += (p[k] - p[k - 1]).norm();
  return l;
}

TEST(Fibre, CentrelineHasTheFibreLength) {
  FibreSpec spec;
  spec.segments = 10;
  spec.bend_angle = Distribution::Normal(0.0, 0.3);
  spec.twist_angle = Distribution::Uniform(-kPi, kPi);
  std::mt19937_64 rng(1);
  const FibreProperties f = SampleFibre(spec, rng);
  const std::vector<Vec3> c = Centreline(f);
  ASSERT_EQ(c.size(), 11u);
  EXPECT_NEAR(PolylineLength(c), f.length, 1e-12);
}

TEST(Fibre, ConstantBendWithoutTwistIsAPlanarArc) {
  FibreProperties f;
  f.length = 1e-3;
  const int segments = 12;
  f.bend.assign(segments - 1, kPi / segments);  // a constant bend between segments
  f.twist.assign(segments - 1, 0.0);
  const std::vector<Vec3> c = Centreline(f);
  for (const Vec3& p : c) EXPECT_NEAR(p.z(), 0.0, 1e-15);  // stays in the x-y plane
  // All vertices lie on one circle: equal distances from the circumcentre of three of them.
  const Vec3 a = c[0], b = c[6], d = c[12];
  const Vec3 ab = b - a, ad = d - a;
  const Vec3 n = ab.cross(ad);
  const Vec3 centre =
      a + (ab.squaredNorm() * ad.cross(n) + ad.squaredNorm() * n.cross(ab)) / (2 * n.squaredNorm());
  const double r = (a - centre).norm();
  for (const Vec3& p : c) EXPECT_NEAR((p - centre).norm(), r, 1e-12);
}

TEST(Fibre, TwistTakesTheFibreOutOfPlane) {
  FibreProperties f;
  f.length = 1e-3;
  f.bend.assign(9, 0.3);
  f.twist.assign(9, 0.5);
  double z = 0.0;
  for (const Vec3& p : Centreline(f)) z = std::max(z, std::abs(p.z()));
  EXPECT_GT(z, 1e-5);
}

TEST(Fibre, ParticlesAreSpacedEvenlyAlongTheCentreline) {
  EXPECT_EQ(ParticlesPerFibre(1.92e-3, 32e-6), 60);
  EXPECT_EQ(ParticlesPerFibre(10e-6, 32e-6), 2);
  const std::vector<Vec3> line = {Vec3::Zero(), Vec3(1e-3, 0, 0)};
  const std::vector<Vec3> p = PointsAlong(line, 4);
  ASSERT_EQ(p.size(), 4u);
  EXPECT_NEAR(p[0].x(), 0.125e-3, 1e-15);
  EXPECT_NEAR(p[3].x(), 0.875e-3, 1e-15);
}

TEST(Fibre, MassIsExactAtAnyFidelity) {
  FibreProperties f;
  f.length = 1.92e-3;
  f.diameter = 32e-6;
  f.coarseness = 2.5e-7;
  f.youngs_modulus = 10e9;
  f.shear_modulus = 3e9;
  f.strength = 0.1;
  for (double spacing : {0.5, 1.0, 1.5, 3.0}) {
    Network net;
    net.world.cell.hi = Vec3(5e-3, 5e-3, 1.0);
    const int n = ParticlesPerFibre(f.length, spacing * f.diameter);
    net.AddFibre(f, PointsAlong({Vec3(1e-3, 1e-3, 1e-4), Vec3(2.92e-3, 1e-3, 1e-4)}, n), {});
    EXPECT_NEAR(net.TotalMass(), f.Mass(), 1e-13 * f.Mass()) << "spacing " << spacing;
    EXPECT_EQ(net.world.bonds.size(), static_cast<std::size_t>(n - 1));
    EXPECT_EQ(net.CheckInvariants(), "");
    const BeamBondParams& t = net.world.bonds.types[net.fibres[0].bond_type];
    EXPECT_EQ(t.failure, BondFailure::kModeThresholds);
    EXPECT_DOUBLE_EQ(t.max_tension, 0.1);
    EXPECT_NEAR(t.k_n, 10e9 * kPi * 16e-6 * 16e-6 / (f.length / n), 1e-6 * t.k_n);
  }
}

TEST(Fibre, SpecValidateRejectsNonPhysicalValues) {
  FibreSpec spec;
  EXPECT_EQ(spec.Validate(), "");
  spec.diameter = Distribution::Fixed(3e-3);  // thicker than long
  EXPECT_NE(spec.Validate(), "");
  spec = FibreSpec{};
  spec.segments = 0;
  EXPECT_NE(spec.Validate(), "");
}

}  // namespace
}  // namespace fibrenet::pipeline
