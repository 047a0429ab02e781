// Softness: the top-surface height map and its spectrum on surfaces of known shape, the
// composite index, and the whole virtual-test stage (tensile MD and CD, compression,
// softness) on the tiny pressed sheet of tiny_spec.h, which must report every metric, and the
// ZD compression's slow toe on that sheet.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/pipeline/pipeline.h"
#include "engine/pipeline/softness.h"
#include "engine/pipeline/virtual_tests.h"
#include "tests/engine/pipeline/tiny_spec.h"

namespace fibrenet::pipeline {
namespace {

// A carpet of touching spheres (radius R, pitch 2R) on a periodic cell whose heights follow
// z = A sin(2 pi x / lambda).
World WavyCarpet(double A, double lambda) {
  World w;
  const double R = 10e-6, L = 0.8e-3;
  w.cell.lo = Vec3(0.0, 0.0, -1e-3);
  w.cell.hi = Vec3(L, L, 1e-3);
  const int n = static_cast<int>(L / (2 * R));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = (i + 0.5) * 2 * R, y = (j + 0.5) * 2 * R;
      w.particles.Add(Vec3(x, y, A * std::sin(2 * kPi * x / lambda)), R, 1e-12, -1);
    }
  return w;
}

TEST(Softness, FlatCarpetIsSmoothAndAWavyOneShowsItsWavelength) {
  const Roughness flat = MeasureRoughness(TopSurface(WavyCarpet(0.0, 0.2e-3), 5e-6, 0.0));
  EXPECT_LT(flat.sq, 3e-6);  // only the bumps of the spheres themselves
  const double A = 20e-6, lambda = 0.2e-3;
  const Roughness wavy = MeasureRoughness(TopSurface(WavyCarpet(A, lambda), 5e-6, 0.0));
  EXPECT_NEAR(wavy.sq, A / std::sqrt(2.0), 0.15 * A);
  EXPECT_NEAR(wavy.dominant_wavelength, lambda, 0.01 * lambda);
  // Along x the harmonic at lambda holds the wave's amplitude A / sqrt(2) (RMS).
  double best = 0.0;
  for (double a : wavy.md.amplitude) best = std::max(best, a);
  EXPECT_NEAR(best, A / std::sqrt(2.0), 0.1 * A);
  // A larger probe bridges the valleys between spheres: smoother, never rougher.
  const Roughness probed = MeasureRoughness(TopSurface(WavyCarpet(A, lambda), 5e-6, 50e-6));
  EXPECT_LE(probed.sq, wavy.sq * 1.01);
  std::printf("Sq flat %.3f um, wavy %.3f um (A/sqrt2 %.3f um), dominant %.1f um, md peak %.3f "
              "um, probe 50 um %.3f um\n", flat.sq * 1e6, wavy.sq * 1e6, A / std::sqrt(2.0) * 1e6,
              wavy.dominant_wavelength * 1e6, best * 1e6, probed.sq * 1e6);
}

TEST(Softness, IndexIsOneHundredAtTheReferenceAndRisesAsTheSheetSoftens) {
  const SoftnessIndexSettings s;
  const double ref = SoftnessIndex(s.bulk_ref_um_per_kPa, s.roughness_ref_um, s.bending_ref_mN_mm, s);
  EXPECT_NEAR(ref, 100.0, 1e-9);
  EXPECT_GT(SoftnessIndex(2 * s.bulk_ref_um_per_kPa, s.roughness_ref_um, s.bending_ref_mN_mm, s), ref);
  EXPECT_LT(SoftnessIndex(s.bulk_ref_um_per_kPa, 2 * s.roughness_ref_um, s.bending_ref_mN_mm, s), ref);
  EXPECT_LT(SoftnessIndex(s.bulk_ref_um_per_kPa, s.roughness_ref_um, 2 * s.bending_ref_mN_mm, s), ref);
  EXPECT_NEAR(SoftnessIndex(2 * s.bulk_ref_um_per_kPa, s.roughness_ref_um, s.bending_ref_mN_mm, s),
              100.0 * std::pow(2.0, s.w_bulk), 1e-9);
  EXPECT_TRUE(std::isnan(SoftnessIndex(0.0, 1.0, 1.0, s)));
}

// With the masses scaled for the loading, a sheet moving at the platen's full speed holds far
// more kinetic energy than the platen puts in during the toe (kinetic / platen work 8.7
// here); the slow toe keeps the guard (0.006). The faster approach below the modulus window
// saves steps and changes neither the guard's verdict nor the modulus beyond 5%. The
// feedback above the window saves steps too and leaves the window's modulus as it was.
TEST(ZdCompression, TheSlowToeKeepsAPressedSheetQuasiStatic) {
  const PipelineReport sheet = RunPipeline(testing::TinySpec(7), Progress{});
  CompressionSettings c;
  c.quasi_static.loading_steps = 20000;  // at 10000 the guard read 0.013
  c.samples = 100;
  const CompressionResult slow_toe = RunCompressionTest(sheet.network, c);
  c.approach_speed_fraction = 0.05;
  const CompressionResult approach = RunCompressionTest(sheet.network, c);
  c.approach_speed_fraction = 0.0;
  c.feedback_above_window = true;
  const CompressionResult feedback = RunCompressionTest(sheet.network, c);
  c.feedback_above_window = false;
  c.min_speed_fraction = 1.0;
  const CompressionResult constant = RunCompressionTest(sheet.network, c);
  std::printf("kinetic / platen work: approach %.4g, slow toe %.4g, constant speed %.4g; steps "
              "%ld, %ld, %ld; zd_modulus %.4g, %.4g kPa\n",
              approach.Value("zd_kinetic_work_ratio"), slow_toe.Value("zd_kinetic_work_ratio"),
              constant.Value("zd_kinetic_work_ratio"), static_cast<long>(approach.steps),
              static_cast<long>(slow_toe.steps), static_cast<long>(constant.steps),
              approach.Value("zd_modulus_kPa"), slow_toe.Value("zd_modulus_kPa"));
  EXPECT_TRUE(slow_toe.quasi_static) << slow_toe.warnings.back();
  EXPECT_TRUE(approach.quasi_static) << approach.warnings.back();
  EXPECT_FALSE(constant.quasi_static);
  EXPECT_EQ(slow_toe.Value("zd_drag_load_ratio"), 0.0);  // local damping, no drag
  EXPECT_GT(slow_toe.steps, approach.steps);
  EXPECT_GT(approach.steps, constant.steps);
  EXPECT_NEAR(approach.Value("zd_modulus_kPa"), slow_toe.Value("zd_modulus_kPa"),
              0.05 * slow_toe.Value("zd_modulus_kPa"));
  std::printf("feedback above the window: %ld steps, kinetic / platen work %.4g, zd_modulus "
              "%.6g kPa, hysteresis %.4g (slow toe %.4g), peak %.4g kPa (%.4g)\n",
              static_cast<long>(feedback.steps), feedback.Value("zd_kinetic_work_ratio"),
              feedback.Value("zd_modulus_kPa"), feedback.Value("zd_hysteresis_fraction"),
              slow_toe.Value("zd_hysteresis_fraction"), feedback.Value("zd_peak_pressure_kPa"),
              slow_toe.Value("zd_peak_pressure_kPa"));
  EXPECT_TRUE(feedback.quasi_static) << feedback.warnings.back();
  EXPECT_LT(feedback.steps, slow_toe.steps);
  EXPECT_NEAR(feedback.Value("zd_modulus_kPa"), slow_toe.Value("zd_modulus_kPa"),
              1e-3 * slow_toe.Value("zd_modulus_kPa"));
  EXPECT_NEAR(feedback.Value("zd_hysteresis_fraction"), slow_toe.Value("zd_hysteresis_fraction"),
              0.05 * slow_toe.Value("zd_hysteresis_fraction"));
  // The van Wyk fit of the loading branch is reported, within the fit's range.
  std::printf("van Wyk: n = %.3g, r2 = %.4g\n", slow_toe.Value("zd_van_wyk_exponent"),
              slow_toe.Value("zd_van_wyk_r2"));
  EXPECT_GE(slow_toe.Value("zd_van_wyk_exponent"), 1.0);
  EXPECT_LE(slow_toe.Value("zd_van_wyk_exponent"), 30.0);
  EXPECT_GE(slow_toe.Value("zd_van_wyk_r2"), 0.0);
  EXPECT_LE(slow_toe.Value("zd_van_wyk_r2"), 1.0);
}

// The tapered approach: the platen starts at the full speed and slows as the pressure rises,
// never below the constant approach's speed and never speeding up, and reaches the window in
// fewer steps with the guard holding and the modulus as the constant approach reads it.
TEST(ZdCompression, TheTaperedApproachSlowsAsThePressureRises) {
  const PipelineReport sheet = RunPipeline(testing::TinySpec(7), Progress{});
  CompressionSettings c;
  c.quasi_static.loading_steps = 20000;
  c.samples = 400;  // a sample every 50 steps: the speed's course through the approach
  c.max_pressure = 5000.0;  // past the modulus window, which is what the approach leads to
  c.approach_speed_fraction = 0.05;
  const CompressionResult constant = RunCompressionTest(sheet.network, c);
  c.approach_taper = true;
  const CompressionResult taper = RunCompressionTest(sheet.network, c);
  std::printf("tapered approach: %ld steps (constant %ld), kinetic / platen work %.4g, zd_modulus "
              "%.6g kPa (constant %.6g)\n", static_cast<long>(taper.steps),
              static_cast<long>(constant.steps), taper.Value("zd_kinetic_work_ratio"),
              taper.Value("zd_modulus_kPa"), constant.Value("zd_modulus_kPa"));
  EXPECT_TRUE(taper.quasi_static) << taper.warnings.back();
  EXPECT_LT(taper.steps, constant.steps);
  EXPECT_NEAR(taper.Value("zd_modulus_kPa"), constant.Value("zd_modulus_kPa"),
              0.05 * constant.Value("zd_modulus_kPa"));

  // The platen's travel per sample while the pressure is below the approach's end.
  const double approach_end = c.approach_pressure_fraction * c.modulus_pressure_lo;
  auto approach_moves = [&](const CompressionResult& r) {
    const Curve& curve = r.curves.front();
    const std::vector<double> gap = curve.Values("gap_m");
    const std::vector<double> pressure = curve.Values("pressure_Pa");
    std::vector<double> moves;
    for (std::size_t k = 1; k < gap.size() && pressure[k] < approach_end; ++k)
      moves.push_back(gap[k - 1] - gap[k]);
    return moves;
  };
  const double constant_move = approach_moves(constant).at(1);
  // The samples read the pressure between steps: the approach may have ended (the slow toe's
  // moves are shorter) before a sample reads its end. Up to then the moves never lengthen.
  std::vector<double> tapered = approach_moves(taper);
  const auto toe = std::find_if(tapered.begin(), tapered.end(),
                                [&](double move) { return move < constant_move * (1.0 - 1e-6); });
  tapered.erase(toe, tapered.end());
  ASSERT_GE(tapered.size(), 3u);
  EXPECT_GT(tapered.front(), 2.0 * constant_move);  // fast where the pressure is low
  for (std::size_t k = 1; k < tapered.size(); ++k)
    EXPECT_LE(tapered[k], tapered[k - 1] * (1.0 + 1e-9)) << "sample " << k;
}

// The feedback from the window's start: the platen leaves the floor speed inside the modulus
// window (the feedback above the window keeps it there), the loop takes fewer steps, the
// guard holds, and the modulus stays near the one read at half the floor.
TEST(ZdCompression, FeedbackFromTheWindowStartSpeedsTheWindowUp) {
  const PipelineReport sheet = RunPipeline(testing::TinySpec(7), Progress{});
  CompressionSettings c;
  c.quasi_static.loading_steps = 20000;
  c.samples = 400;
  c.max_pressure = 5000.0;  // past the window
  c.feedback_above_window = true;
  const CompressionResult above = RunCompressionTest(sheet.network, c);
  c.feedback_in_window = true;
  const CompressionResult in_window = RunCompressionTest(sheet.network, c);
  c.feedback_in_window = false;
  c.min_speed_fraction *= 0.5;
  const CompressionResult half_floor = RunCompressionTest(sheet.network, c);
  std::printf("feedback from the window's start: %ld steps (from its top %ld, half the floor "
              "%ld), kinetic / platen work %.4g, zd_modulus %.6g kPa (%.6g, %.6g)\n",
              static_cast<long>(in_window.steps), static_cast<long>(above.steps),
              static_cast<long>(half_floor.steps), in_window.Value("zd_kinetic_work_ratio"),
              in_window.Value("zd_modulus_kPa"), above.Value("zd_modulus_kPa"),
              half_floor.Value("zd_modulus_kPa"));
  EXPECT_TRUE(in_window.quasi_static) << in_window.warnings.back();
  EXPECT_LT(in_window.steps, above.steps);
  EXPECT_NEAR(in_window.Value("zd_modulus_kPa"), half_floor.Value("zd_modulus_kPa"),
              0.05 * half_floor.Value("zd_modulus_kPa"));

  // The platen's longest move between samples inside the window, against the floor's move.
  auto longest_window_move = [&](const CompressionResult& r) {
    const Curve& curve = r.curves.front();
    const std::vector<double> gap = curve.Values("gap_m");
    const std::vector<double> pressure = curve.Values("pressure_Pa");
    const std::vector<double> branch = curve.Values("branch");
    double longest = 0.0;
    for (std::size_t k = 1; k < gap.size() && branch[k] == 0.0; ++k)
      if (pressure[k - 1] >= c.modulus_pressure_lo && pressure[k] <= c.modulus_pressure_hi)
        longest = std::max(longest, gap[k - 1] - gap[k]);
    return longest;
  };
  const double floor_move = longest_window_move(above);
  ASSERT_GT(floor_move, 0.0);
  EXPECT_GT(longest_window_move(in_window), 1.5 * floor_move);
}

// A loop stopped at a low pressure, in the slow toe: the platen must go back up at the speed
// it came down with. Jumping to the full speed threw the sheet's scaled mass at it: the
// generic tissue's loop to 4.9 kPa returned 18% more work than it took (hysteresis -0.18),
// and here the unloading's kinetic energy broke the guard, which covers the unloading.
TEST(ZdCompression, ALoopStoppedAtALowPressureReturnsNoMoreWorkThanItTook) {
  const PipelineReport sheet = RunPipeline(testing::TinySpec(7), Progress{});
  CompressionSettings c;
  c.quasi_static.loading_steps = 20000;
  c.samples = 100;
  c.max_pressure = 2000.0;
  const CompressionResult r = RunCompressionTest(sheet.network, c);
  std::printf("peak %.4g kPa at strain %.4g, hysteresis %.4g, residual strain %.4g, kinetic / "
              "platen work %.4g, %ld steps\n", r.Value("zd_peak_pressure_kPa"),
              r.Value("zd_max_strain"), r.Value("zd_hysteresis_fraction"),
              r.Value("zd_residual_strain"), r.Value("zd_kinetic_work_ratio"),
              static_cast<long>(r.steps));
  EXPECT_NEAR(r.Value("zd_peak_pressure_kPa"), 2.0, 0.2);
  EXPECT_GE(r.Value("zd_hysteresis_fraction"), 0.0);
  EXPECT_LE(r.Value("zd_hysteresis_fraction"), 1.0);
  EXPECT_TRUE(r.quasi_static) << r.warnings.back();
}

TEST(VirtualTests, TinySheetReportsEveryMetric) {
  PipelineSpec spec = testing::TinySpec(7);
  const PipelineReport sheet = RunPipeline(spec, Progress{});
  VirtualTestsSpec tests;
  tests.tensile = TensileStage{};
  tests.tensile->settings.quasi_static.loading_steps = 3000;
  tests.tensile->settings.samples = 100;
  tests.compression = CompressionSettings{};
  tests.compression->quasi_static.loading_steps = 3000;
  tests.compression->samples = 100;
  tests.softness = SoftnessSettings{};
  tests.softness->bending_test.relax_steps = 1000;
  const VirtualTestsReport r = RunVirtualTests(sheet.network, tests);
  for (const std::string name :
       {"tensile_strength_N_per_m", "tensile_modulus_N_per_m", "strain_at_break", "tea_J_per_m2",
        "strain_energy_per_fibre_nJ", "energy_share_normal", "energy_share_shear",
        "energy_share_bending", "energy_share_twist", "strain_energy_top10_share",
        "strain_energy_gini", "cd_tensile_strength_N_per_m", "gmt_tensile_strength_N_per_m",
        "zd_modulus_kPa", "zd_hysteresis_fraction", "zd_residual_strain", "bulk_softness_um_per_kPa",
        "surface_roughness_um", "bending_stiffness", "softness_index"}) {
    const Metric* m = FindMetric(r.metrics, name);
    ASSERT_NE(m, nullptr) << name;
    EXPECT_TRUE(std::isfinite(m->value)) << name;
  }
  const double shares = FindMetric(r.metrics, "energy_share_normal")->value +
                        FindMetric(r.metrics, "energy_share_shear")->value +
                        FindMetric(r.metrics, "energy_share_bending")->value +
                        FindMetric(r.metrics, "energy_share_twist")->value;
  EXPECT_NEAR(shares, 1.0, 1e-9);
  EXPECT_GT(FindMetric(r.metrics, "tensile_strength_N_per_m")->value, 0.0);
  EXPECT_GT(FindMetric(r.metrics, "bending_stiffness")->value, 0.0);
  EXPECT_EQ(r.fibre_energy_at_peak.size(), sheet.network.fibres.size());
  EXPECT_GE(r.curves.size(), 6u);  // tensile md, cd, compression, spectra, profile, bending
  EXPECT_GT(r.steps, 0);

  // Softness alone runs its own compression and bending test; the stage counts their steps.
  VirtualTestsSpec softness_only;
  softness_only.softness = tests.softness;
  softness_only.softness->compression.quasi_static.loading_steps = 3000;
  softness_only.softness->compression.samples = 100;
  const VirtualTestsReport alone = RunVirtualTests(sheet.network, softness_only);
  ASSERT_NE(FindMetric(alone.metrics, "bulk_softness_um_per_kPa"), nullptr);
  EXPECT_GT(alone.steps, 1000);  // a bending level alone relaxes for up to 1000 steps
}

}  // namespace
}  // namespace fibrenet::pipeline
