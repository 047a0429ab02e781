// Mean crossings per fibre in a thin, nearly 2D random network of straight fibres against
// Kallmes-Corte: 2 l_i l_j / (pi A) crossings per fibre pair (SPEC section 5, "Networks").
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "engine/pipeline/forming.h"
#include "engine/pipeline/metrics.h"

namespace fibrenet::pipeline {
namespace {

// 1000 straight fibres of 0.5 mm and 50 ng on 4 mm^2, placed flat.
SheetSpec ThinSheet() {
  SheetSpec sheet;
  sheet.Lx = sheet.Ly = 2e-3;
  sheet.fibres.length = Distribution::Fixed(0.5e-3);
  sheet.fibres.diameter = Distribution::Fixed(20e-6);
  sheet.fibres.coarseness = Distribution::Fixed(1e-7);
  sheet.basis_weight = 0.0125;
  return sheet;
}

FormingSettings FlatPlacement() {
  FormingSettings forming;
  forming.orientation = Orientation::kPlanar;
  forming.consistency = 0.005;
  return forming;
}

TEST(KallmesCorte, RandomPlanarNetworkMatchesWithinFivePercent) {
  const SheetSpec sheet = ThinSheet();
  const FormingSettings forming = FlatPlacement();
  double sum = 0.0, expected = 0.0;
  const int seeds = 3;
  for (int seed = 1; seed <= seeds; ++seed) {
    std::mt19937_64 rng(seed);
    const Network net = PlaceFibres(sheet, forming, rng);
    ASSERT_EQ(net.fibres.size(), 1000u);
    double kc = 0.0;
    sum += CrossingsPerFibre(net, &kc);
    expected += kc;
  }
  const double mean = sum / seeds, kc = expected / seeds;
  // About 30 crossings per fibre, 45000 crossings in all: the sampling error is below 1%.
  EXPECT_GT(kc, 20.0);
  EXPECT_NEAR(mean / kc, 1.0, 0.05) << "crossings " << mean << " Kallmes-Corte " << kc;
}

TEST(KallmesCorte, ExpectationScalesWithFibreLengthSquared) {
  Network net;
  net.world.cell.hi = Vec3(1e-3, 1e-3, 1.0);
  FibreProperties f;
  f.length = 0.5e-3;
  f.diameter = 20e-6;
  f.coarseness = 1e-7;
  f.youngs_modulus = 1e10;
  f.shear_modulus = 3e9;
  f.strength = 0.1;
  for (int k = 0; k < 3; ++k)
    net.AddFibre(f, PointsAlong({Vec3(0.1e-3, 0.1e-3 + k * 0.2e-3, 1e-4),
                                 Vec3(0.6e-3, 0.1e-3 + k * 0.2e-3, 1e-4)}, 10), {});
  double kc = 0.0;
  CrossingsPerFibre(net, &kc);
  const double l = 0.45e-3;  // chain of 10 particles: 9 of 10 spacings
  EXPECT_NEAR(kc, 2.0 * (9 * l * l - 3 * l * l) / (kPi * 1e-6 * 3), 1e-9);
}

// The placed fibres lie in memory in the order of their place in the plane, so that fibres
// that meet are near each other in memory too. Measured over the pairs of fibres whose centres
// lie within half a fibre length: the median of their index distance, as a fraction of the
// fibre count, is 1 - 1/sqrt(2) = 0.29 for fibres in random order. (The median, since the
// order cannot follow the periodic cell across its edges.)
TEST(Placement, FibresThatMeetLieNearEachOtherInMemory) {
  std::mt19937_64 rng(1);
  const Network net = PlaceFibres(ThinSheet(), FlatPlacement(), rng);
  ASSERT_EQ(net.CheckInvariants(), "");
  const Particles& p = net.world.particles;
  std::vector<Vec3> centre;
  for (const FibreRecord& f : net.fibres) {
    // The middle particle: a centroid would fall between the halves of a wrapped fibre.
    centre.push_back(p.x[f.first_particle + f.particle_count / 2]);
  }
  const double n = static_cast<double>(centre.size());
  std::vector<double> distance;
  for (std::size_t a = 0; a < centre.size(); ++a)
    for (std::size_t b = a + 1; b < centre.size(); ++b) {
      const Vec3 d = net.world.cell.Delta(centre[a], centre[b]);
      if (std::hypot(d.x(), d.y()) <= 0.25e-3) distance.push_back(static_cast<double>(b - a) / n);
    }
  ASSERT_GT(distance.size(), 1000u);
  std::nth_element(distance.begin(), distance.begin() + distance.size() / 2, distance.end());
  EXPECT_LT(distance[distance.size() / 2], 0.1) << "median index distance of neighbouring fibres";
}

}  // namespace
}  // namespace fibrenet::pipeline
