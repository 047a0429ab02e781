// The crepe read from a height profile: the waviness filter against its definition (a
// parabola kept whole, half a sine at the cutoff), and the crepe band on profiles whose folds
// are known: under a creped sheet's long shape, and absent.
#include "engine/pipeline/crepe_profile.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "engine/core/types.h"
#include "engine/pipeline/profile_filter.h"

namespace fibrenet::pipeline {
namespace {

// RMS x sqrt(2) over the profile's middle half: a sine's amplitude, away from the ends.
double MiddleAmplitude(const std::vector<double>& v) {
  const std::size_t n = v.size();
  double sum = 0.0;
  for (std::size_t j = n / 4; j < 3 * n / 4; ++j) sum += v[j] * v[j];
  return std::sqrt(2.0 * sum / double(3 * n / 4 - n / 4));
}

std::vector<double> Sine(int n, double bin, double wavelength) {
  std::vector<double> h(n);
  for (int j = 0; j < n; ++j) h[j] = std::sin(2.0 * kPi * j * bin / wavelength);
  return h;
}

TEST(ProfileFilter, KeepsAParabolaWholeToItsEnds) {
  const double bin = 10e-6;
  std::vector<double> h;
  for (int j = 0; j < 300; ++j) {
    const double u = j * bin;
    h.push_back(200e-6 + 0.3 * u - 150.0 * u * u);
  }
  const std::vector<double> waviness = GaussianRegressionWaviness(h, bin, 800e-6);
  ASSERT_EQ(waviness.size(), h.size());
  for (std::size_t j = 0; j < h.size(); ++j) EXPECT_NEAR(waviness[j], h[j], 1e-12) << j;
}

TEST(ProfileFilter, PassesHalfASineAtTheCutoffAndSeparatesTheBands) {
  const double bin = 10e-6, cutoff = 800e-6;
  // At the cutoff: half the amplitude (the definition of the cutoff).
  EXPECT_NEAR(MiddleAmplitude(GaussianRegressionWaviness(Sine(2000, bin, cutoff), bin, cutoff)),
              0.5, 0.01);
  // Half the cutoff is roughness (under 2% left in the waviness), five cutoffs waviness.
  EXPECT_LT(MiddleAmplitude(GaussianRegressionWaviness(Sine(2000, bin, 0.5 * cutoff), bin, cutoff)),
            0.02);
  EXPECT_GT(MiddleAmplitude(GaussianRegressionWaviness(Sine(2000, bin, 5.0 * cutoff), bin, cutoff)),
            0.99);
}

TEST(CrepeProfile, FindsTheFrequencyAndAmplitudeOfASineProfile) {
  const double bin = 5e-6, wavelength = 180e-6, amplitude = 20e-6;
  std::vector<double> h;
  for (int k = 0; k < 400; ++k)
    h.push_back(100e-6 + 0.02 * k * bin + amplitude * std::sin(2.0 * kPi * k * bin / wavelength));
  const CrepeSpectrum s = AnalyseCrepe(h, bin, CrepeBand{});
  EXPECT_NEAR(s.frequency, 1.0 / wavelength, 0.02 / wavelength);
  EXPECT_NEAR(s.amplitude, amplitude, 0.05 * amplitude);
}

// A creped sheet's profile as the blade leaves it, 8 mm long: the sheet's long shape (a
// slope and a 300 um hump 1 mm wide) carries folds 260 um apart, 40 um high, and the fibres'
// texture (40 um apart, 8 um high). The long shape's amplitude is ten times the folds'.
std::vector<double> CrepedSheet(double bin, double fold_amplitude) {
  std::vector<double> h;
  for (int j = 0; j < 800; ++j) {
    const double u = j * bin, hump = (u - 4.5e-3) / 1e-3;
    h.push_back(150e-6 + 0.02 * u + 300e-6 * std::exp(-hump * hump) +
                fold_amplitude * std::sin(2.0 * kPi * u / 260e-6) +
                8e-6 * std::sin(2.0 * kPi * u / 40e-6));
  }
  return h;
}

TEST(CrepeProfile, FindsTheFoldsUnderTheSheetsLongShape) {
  const double bin = 10e-6;
  const CrepeSpectrum s = AnalyseCrepe(CrepedSheet(bin, 40e-6), bin, CrepeBand{});
  EXPECT_NEAR(s.frequency, 1.0 / 260e-6, 0.02 / 260e-6);
  EXPECT_NEAR(s.amplitude, 40e-6, 0.05 * 40e-6);
  EXPECT_NEAR(s.peak_amplitude, 40e-6, 0.2 * 40e-6);  // the Hann window's scalloping
  ASSERT_EQ(s.folds.size(), 800u);
  ASSERT_EQ(s.waviness.size(), 800u);
  // The long shape is in the waviness: at the hump's top it stands 300 um up.
  EXPECT_NEAR(s.waviness[450] - (150e-6 + 0.02 * 4.5e-3), 300e-6, 15e-6);
}

TEST(CrepeProfile, ReadsNoFoldsWhereNoneStandAboveTheBar) {
  const double bin = 10e-6;
  // Folds 5 um high: under the least amplitude (16 um), no fold train.
  const CrepeSpectrum low = AnalyseCrepe(CrepedSheet(bin, 5e-6), bin, CrepeBand{});
  EXPECT_EQ(low.frequency, 0.0);
  EXPECT_NEAR(low.amplitude, 5e-6, 1e-6);
  // The long shape and the texture alone: no folds either.
  const CrepeSpectrum none = AnalyseCrepe(CrepedSheet(bin, 0.0), bin, CrepeBand{});
  EXPECT_EQ(none.frequency, 0.0);
  EXPECT_LT(none.amplitude, 2e-6);
  // The same 5 um folds count once the bar is lowered under them.
  CrepeBand fine;
  fine.min_amplitude = 3e-6;
  EXPECT_NEAR(AnalyseCrepe(CrepedSheet(bin, 5e-6), bin, fine).frequency, 1.0 / 260e-6,
              0.02 / 260e-6);
}

TEST(CrepeProfile, ASingleBuckleIsNotAFoldTrain) {
  // A 2.2 mm sheet, sloped, with one buckle: a dip 100 um deep and 150 um wide, then a
  // crest (the generic web at 33.7 J/m^2 left the blade so, docs/creping.md).
  const double bin = 10e-6;
  std::vector<double> h;
  for (int j = 0; j < 220; ++j) {
    const double t = (j * bin - 0.8e-3) / 150e-6;
    h.push_back(900e-6 + 0.1 * j * bin - 100e-6 * std::exp(-t * t) +
                50e-6 * std::exp(-(t - 1.5) * (t - 1.5)));
  }
  const CrepeSpectrum s = AnalyseCrepe(h, bin, CrepeBand{});
  // Its spectrum has a peak above a fibre radius, but the band holds one fold.
  EXPECT_GE(s.peak_amplitude, CrepeBand{}.min_amplitude);
  EXPECT_LT(s.fold_count, kFoldsInATrain);
  EXPECT_EQ(s.frequency, 0.0);
  // A train of the folds the earlier tests find counts each of them (8 mm / 260 um).
  EXPECT_NEAR(AnalyseCrepe(CrepedSheet(bin, 40e-6), bin, CrepeBand{}).fold_count, 8e-3 / 260e-6, 1.0);
}

TEST(CrepeProfile, CoversOnlyTheStretchTheSheetReaches) {
  // A one-particle-high sheet under u = 100-300 um of a 0-400 um window, with no particle
  // between 180 and 220 um; its top rises 0.1 um per um.
  std::vector<FramePoint> pts;
  for (int i = 0; i < 20; ++i) {
    const double u = 105e-6 + i * 10e-6;
    if (u > 180e-6 && u < 220e-6) continue;
    pts.push_back({Vec3(u, 25e-6, 0.1 * u), 16e-6});
  }
  const CrepeProfile p = MeasureCrepeProfile(pts, 0.0, 400e-6, 10e-6, 0.0, 50e-6, 50e-6, 1.0);
  EXPECT_NEAR(p.u0, 100e-6, 1e-12);
  ASSERT_EQ(p.height.size(), 20u);
  for (int k = 0; k < 20; ++k)
    EXPECT_NEAR(p.height[k], 0.1 * (105e-6 + k * 10e-6) + 16e-6, 1e-12) << k;
}

TEST(CrepeProfile, ContourOfASlopeAndOfFoldsAgainstTheirArcLength) {
  const double bin = 1e-6;
  std::vector<double> slope;
  for (int j = 0; j < 500; ++j) slope.push_back(0.3 * j * bin);
  EXPECT_NEAR(ContourRatio(slope, bin), std::sqrt(1.09), 1e-12);
  EXPECT_EQ(ContourRatio({}, bin), 1.0);
  // Folds 40 um high, 400 um apart, over five whole wavelengths: the arc length of
  // A sin(2 pi u / L) per wavelength is (2 / pi) sqrt(1 + k^2) E(k / sqrt(1 + k^2)) L, with
  // k = 2 pi A / L and E the complete elliptic integral of the second kind (modulus form).
  const double amplitude = 40e-6, wavelength = 400e-6;
  std::vector<double> folds = Sine(2001, bin, wavelength);
  for (double& h : folds) h *= amplitude;
  const double k = 2.0 * kPi * amplitude / wavelength;
  const double arc =
      2.0 / kPi * std::sqrt(1.0 + k * k) * std::comp_ellint_2(k / std::sqrt(1.0 + k * k));
  EXPECT_NEAR(ContourRatio(folds, bin), arc, 1e-5);
  EXPECT_GT(arc, 1.09);  // the folds take up 9% more sheet than their projection
}

TEST(CrepeProfile, CaliperOfAFlatLayerIsItsThickness) {
  std::vector<FramePoint> pts;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 10; ++j)
      for (int layer = 0; layer < 3; ++layer)
        pts.push_back({Vec3(i * 10e-6 + 5e-6, j * 50e-6 + 25e-6, 16e-6 + layer * 32e-6), 16e-6});
  const CrepeProfile p = MeasureCrepeProfile(pts, 0.0, 400e-6, 10e-6, 0.0, 500e-6, 50e-6, 1.0);
  EXPECT_NEAR(p.caliper, 96e-6, 1e-12);
  ASSERT_EQ(p.height.size(), 40u);
  for (double h : p.height) EXPECT_NEAR(h, 96e-6, 1e-12);
}

}  // namespace
}  // namespace fibrenet::pipeline
