// The pipeline on the tiny scene: basis weight, settling, determinism, the pressing approach,
// pressing to a target thickness with springback, bonds formed.
#include "engine/pipeline/pipeline.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "tests/engine/pipeline/tiny_spec.h"

namespace fibrenet::pipeline {
namespace {

using testing::TinySpec;

// One run of the tiny scene per seed, shared by the tests below (each run takes seconds).
const PipelineReport& RunTiny(std::uint64_t seed, bool press) {
  static std::map<std::pair<std::uint64_t, bool>, PipelineReport> cache;
  auto key = std::make_pair(seed, press);
  auto it = cache.find(key);
  if (it == cache.end()) {
    PipelineSpec spec = TinySpec(seed);
    if (!press) spec.pressing.reset();
    it = cache.emplace(key, RunPipeline(spec, Progress{})).first;
  }
  return it->second;
}

TEST(Pipeline, BasisWeightWithinOnePercentOfTarget) {
  const PipelineReport& r = RunTiny(7, false);
  EXPECT_NEAR(r.Final().basis_weight_gsm, 20.0, 0.2);
  EXPECT_GT(r.Final().fibre_count, 50.0);
}

TEST(Pipeline, FormingSettlesOnTheWire) {
  const PipelineReport& r = RunTiny(7, false);
  const StageReport& forming = r.stages.at(0);
  EXPECT_EQ(forming.name, "forming");
  bool settled = false;
  for (const auto& [name, value] : forming.details)
    if (name == "settled") settled = value == 1.0;
  EXPECT_TRUE(settled);
  // Every particle has come down from the 2 mm box onto a web far thinner than the box.
  double top = 0.0;
  for (const Vec3& x : r.network.world.particles.x) top = std::max(top, x.z());
  EXPECT_LT(top, 1.0e-3);
  EXPECT_GT(forming.metrics.contacts_per_fibre, 1.0);
  EXPECT_EQ(r.network.CheckInvariants(), "");
}

TEST(Pipeline, SameSeedGivesTheSameNetworkAndOtherSeedsDiffer) {
  const PipelineReport& a = RunTiny(7, false);
  PipelineSpec spec = TinySpec(7);
  spec.pressing.reset();
  const PipelineReport b = RunPipeline(spec, Progress{});
  ASSERT_EQ(a.network.world.particles.size(), b.network.world.particles.size());
  for (std::size_t i = 0; i < a.network.world.particles.size(); ++i)
    ASSERT_EQ(a.network.world.particles.x[i], b.network.world.particles.x[i]) << "particle " << i;
  const PipelineReport& c = RunTiny(8, false);
  EXPECT_NE(a.Final().thickness_um, c.Final().thickness_um);
  EXPECT_NE(a.network.world.particles.x[0], c.network.world.particles.x[0]);
}

TEST(Pipeline, PressingReachesTheTargetThicknessAfterSpringback) {
  const PipelineReport& r = RunTiny(7, true);
  ASSERT_EQ(r.stages.size(), 2u);
  const StageReport& pressing = r.stages[1];
  EXPECT_EQ(pressing.name, "pressing");
  for (const std::string& w : pressing.warnings) ADD_FAILURE() << "warning: " << w;
  EXPECT_NEAR(pressing.metrics.thickness_um, 150.0, 0.05 * 150.0);
  EXPECT_GT(pressing.metrics.bonds_per_fibre, 0.5);
  EXPECT_NEAR(pressing.metrics.basis_weight_gsm, r.stages[0].metrics.basis_weight_gsm, 1e-9);
  EXPECT_LT(pressing.metrics.thickness_um, r.stages[0].metrics.thickness_um);
}

TEST(Pipeline, ParticleSpacingAboveOneDiameterIsWarnedAbout) {
  // Gaps between a fibre's particles let crossing fibres through: forming says so.
  const auto spacing_warnings = [](const StageReport& forming) {
    int n = 0;
    for (const std::string& w : forming.warnings)
      n += w.find("particle spacing") != std::string::npos ? 1 : 0;
    return n;
  };
  EXPECT_EQ(spacing_warnings(RunTiny(7, false).stages.at(0)), 0);
  PipelineSpec spec = TinySpec(7);
  spec.pressing.reset();
  spec.sheet.particle_spacing = 2.0;
  spec.forming.max_steps = 100;  // the warning is about the setting, not the outcome
  const PipelineReport coarse = RunPipeline(spec, Progress{});
  EXPECT_EQ(spacing_warnings(coarse.stages.at(0)), 1);
}

double HighestTop(const Particles& p) {
  double top = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) top = std::max(top, p.x[i].z() + p.radius[i]);
  return top;
}

// A formed web with a fibre standing up out of it, as forming leaves a few: the plate meets
// that fibre first, comes down at the approach speed to the web's top surface (the one the
// thickness measure reads), laying the fibre down on the way, and presses from there.
TEST(Pipeline, PressingApproachesTheWebSurfaceLayingDownAStandingFibre) {
  const PipelineSpec spec = TinySpec(7);
  Network net = RunTiny(7, false).network;
  const double surface =
      MeasureSurfaces(net.world, spec.metrics.thickness_grid, spec.metrics.surface_percentile).top;
  const FibreRecord like = net.fibres.front();
  const int particles = 12;
  FibreProperties f;
  f.length = particles * like.diameter;
  f.diameter = like.diameter;
  f.coarseness = like.coarseness;
  f.youngs_modulus = like.youngs_modulus;
  f.shear_modulus = like.shear_modulus;
  f.strength = like.strength;
  // Leaning 5 degrees off the vertical, as a fibre propped up in a web does.
  const double base = HighestTop(net.world.particles);
  const Vec3 axis(std::sin(5.0 * kPi / 180.0), 0.0, std::cos(5.0 * kPi / 180.0));
  std::vector<Vec3> centres;
  for (int k = 0; k < particles; ++k)
    centres.push_back(Vec3(0.3e-3, 0.3e-3, base + 0.5 * like.diameter) + k * like.diameter * axis);
  net.AddFibre(f, centres, {});
  const double standing_top = centres.back().z() + 0.5 * like.diameter;

  const PressingResult r = Press(net, spec.sheet, *spec.pressing, spec.metrics, Progress{});
  EXPECT_GT(r.first_touch, standing_top - like.diameter) << "the plate met the standing fibre first";
  EXPECT_NEAR(r.press_start, std::max(surface, spec.pressing->target_thickness), like.diameter);
  EXPECT_LT(r.press_start, base);
  EXPECT_LT(HighestTop(net.world.particles), surface) << "the standing fibre was laid down";
  EXPECT_EQ(net.CheckInvariants(), "");
}

// Two pressing speeds: the plate presses at the fast speed down to 1.5 x the target, then at
// the slow one, in fewer steps, and the pressed web comes out within the guard and at the
// target as with the slow speed alone.
TEST(Pipeline, TwoPressingSpeedsPressFastWhereTheWebIsLooseAndEndSlowly) {
  const PipelineSpec spec = TinySpec(7);
  Network one_speed = RunTiny(7, false).network;
  const PressingResult slow =
      Press(one_speed, spec.sheet, *spec.pressing, spec.metrics, Progress{});
  PressingSettings two = *spec.pressing;
  two.fast_speed = 3.0 * two.speed;
  two.fast_until_ratio = 1.5;
  Network two_speeds = RunTiny(7, false).network;
  const PressingResult fast = Press(two_speeds, spec.sheet, two, spec.metrics, Progress{});
  for (const std::string& w : fast.warnings) ADD_FAILURE() << "warning: " << w;
  EXPECT_LT(fast.steps, slow.steps);
  EXPECT_LE(fast.kinetic_to_work_ratio, two.kinetic_work_tolerance);
  EXPECT_NEAR(fast.thickness_at_hold, two.target_thickness,
              two.control_tolerance * two.target_thickness);

  // The plate's speed between samples while it presses: the fast one above 1.5 x the target,
  // the slow one below.
  const double slow_from = two.fast_until_ratio * two.target_thickness;
  int fast_samples = 0, slow_samples = 0;
  for (std::size_t k = 1; k < fast.curve.size(); ++k) {
    const PressPoint& a = fast.curve[k - 1];
    const PressPoint& b = fast.curve[k];
    if (a.plate_z <= two.target_thickness + 1e-12) break;  // at the target: the hold
    if (a.plate_z > fast.press_start) continue;             // the approach
    const double speed = (a.plate_z - b.plate_z) / (b.time - a.time);
    if (b.plate_z > slow_from + 1e-9) {
      EXPECT_NEAR(speed, two.fast_speed, 1e-6 * two.fast_speed) << "sample " << k;
      ++fast_samples;
    } else if (a.plate_z <= slow_from + 1e-9) {
      EXPECT_NEAR(speed, two.speed, 1e-6 * two.speed) << "sample " << k;
      ++slow_samples;
    }
  }
  EXPECT_GT(fast_samples, 3);
  EXPECT_GT(slow_samples, 3);
  std::printf("two speeds: %ld steps (one speed %ld), kinetic / work %.3g (%.3g), bonds %zu "
              "(%zu)\n",
              static_cast<long>(fast.steps), static_cast<long>(slow.steps),
              fast.kinetic_to_work_ratio, slow.kinetic_to_work_ratio, fast.bonds_formed,
              slow.bonds_formed);
}

}  // namespace
}  // namespace fibrenet::pipeline
