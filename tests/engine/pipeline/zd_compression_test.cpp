// ZD compression with unloading: the van Wyk fit gives back the exponent of a curve of its
// form, and the loading stops at a target pressure. A floating mat (fibres placed at random
// in a box, no gravity, no bonds) is the cheap specimen of the stop; the van Wyk check on a
// mat settled under its weight is tests/campaigns/loose_mat_test.cpp.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "engine/pipeline/compression_test.h"
#include "engine/pipeline/forming.h"

namespace fibrenet::pipeline {
namespace {

// 100 straight 0.5 mm fibres of 20 um, oriented at random in 3D, in a 1 mm x 1 mm x 1 mm box
// (10 g/m^2 at 1% consistency): fibre volume fraction ~1.6%.
Network FloatingMat() {
  SheetSpec sheet;
  sheet.Lx = sheet.Ly = 1e-3;
  sheet.basis_weight = 0.010;
  sheet.fibres.length = Distribution::Fixed(0.5e-3);
  sheet.fibres.diameter = Distribution::Fixed(20e-6);
  sheet.fibres.coarseness = Distribution::Fixed(2e-7);
  sheet.contact.restitution = 0.5;
  sheet.contact.Derive();
  FormingSettings forming;
  forming.consistency = 0.01;
  std::mt19937_64 rng(11);
  Network net = PlaceFibres(sheet, forming, rng);
  net.world.physics.contacts = true;
  net.world.physics.friction = true;
  return net;
}

CompressionSettings MatCompression() {
  CompressionSettings s;
  s.max_strain = 0.9;
  s.quasi_static.loading_steps = 8000;
  // Constant speed: the slow toe follows the platen work, which stays tiny while the platen
  // sweeps up the floating fibres (about 100x the steps).
  s.min_speed_fraction = 1.0;
  s.samples = 200;
  return s;
}

// A loading curve of exactly the van Wyk form gives back its exponent, and its r2 is 1.
TEST(ZdCompression, VanWykFitRecoversAKnownExponent) {
  for (double n : {2.0, 3.0, 5.5}) {
    const double phi_h0 = 0.05, k = 2e6;
    Curve c;
    c.columns = {"strain", "pressure_Pa", "branch"};
    for (int i = 0; i <= 100; ++i) {
      const double strain = 0.8 * i / 100.0;
      const double phi = phi_h0 / (1.0 - strain);
      c.Add({strain, k * (std::pow(phi, n) - std::pow(phi_h0, n)), 0.0});
    }
    c.Add({0.7, 1.0, 1.0});  // the unloading branch is left out
    const VanWykFit fit = FitVanWyk(c, phi_h0);
    EXPECT_NEAR(fit.n, n, 0.011);
    EXPECT_NEAR(fit.k, k, 0.05 * k);
    EXPECT_NEAR(fit.phi0, phi_h0, 0.02 * phi_h0);
    EXPECT_GT(fit.r2, 0.9999);
  }
}

TEST(ZdCompression, StopsAtTheTargetPressure) {
  const CompressionResult full = RunCompressionTest(FloatingMat(), MatCompression());
  CompressionSettings s = MatCompression();
  s.max_pressure = 0.2 * full.Value("zd_peak_pressure_kPa") * 1e3;
  const CompressionResult r = RunCompressionTest(FloatingMat(), s);
  EXPECT_NEAR(r.Value("zd_peak_pressure_kPa") * 1e3 / s.max_pressure, 1.0, 0.15);
  EXPECT_LT(r.Value("zd_max_strain"), 0.9);
}

}  // namespace
}  // namespace fibrenet::pipeline
