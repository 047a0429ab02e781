// The stage cache: keys see exactly what is upstream of a stage, and a run resumed from a
// kept network reproduces a run from scratch bit for bit.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "campaigns/scene.h"
#include "campaigns/stage_cache.h"

namespace fibrenet::campaigns {
namespace {

const std::string kScenes = FIBRENET_SCENES_DIR;

TEST(StageKeys, SeeOnlyWhatIsUpstream) {
  const std::string text = "scene text";
  const auto base = StageKeys(text, {{"pressing.target_thickness_um", 150}, {"fibres.length_mm", 0.4}}, 7);
  ASSERT_EQ(base.size(), 3u);  // forming, consolidation, creping
  EXPECT_NE(base[0], base[1]);
  EXPECT_NE(base[1], base[2]);
  // Order of the overrides does not matter; the last of a repeated path wins.
  EXPECT_EQ(base, StageKeys(text, {{"fibres.length_mm", 0.4}, {"pressing.target_thickness_um", 150}}, 7));
  EXPECT_EQ(base, StageKeys(text, {{"fibres.length_mm", 0.3}, {"fibres.length_mm", 0.4},
                                   {"pressing.target_thickness_um", 150}}, 7));
  // A pressing setting changes the pressed key only; a test setting neither.
  const auto pressed = StageKeys(text, {{"pressing.target_thickness_um", 120}, {"fibres.length_mm", 0.4}}, 7);
  EXPECT_EQ(pressed[0], base[0]);
  EXPECT_NE(pressed[1], base[1]);
  EXPECT_NE(pressed[2], base[2]);
  // A creping setting changes the creped key only.
  const auto creped = StageKeys(text, {{"pressing.target_thickness_um", 150}, {"fibres.length_mm", 0.4},
                                       {"creping.creping_angle_deg", 75}}, 7);
  EXPECT_EQ(creped[0], base[0]);
  EXPECT_EQ(creped[1], base[1]);
  EXPECT_NE(creped[2], base[2]);
  const auto tested = StageKeys(text, {{"pressing.target_thickness_um", 150}, {"fibres.length_mm", 0.4},
                                       {"tensile.strain_rate_per_s", 5}}, 7);
  EXPECT_EQ(tested, base);
  // Fibres, seed and the scene text are upstream of everything.
  const auto fibres = StageKeys(text, {{"pressing.target_thickness_um", 150}, {"fibres.length_mm", 0.5}}, 7);
  EXPECT_NE(fibres[0], base[0]);
  EXPECT_NE(fibres[1], base[1]);
  EXPECT_NE(StageKeys(text, {{"pressing.target_thickness_um", 150}, {"fibres.length_mm", 0.4}}, 8)[0], base[0]);
  EXPECT_NE(StageKeys("other text", {{"pressing.target_thickness_um", 150}, {"fibres.length_mm", 0.4}}, 7)[0],
            base[0]);
}

TEST(StageCache, ResumedRunEqualsARunFromScratch) {
  const std::string path = kScenes + "/tiny.toml";
  const std::string text = ReadSceneText(path);
  // Fast, loosely guarded pressing: this test is about reuse, not about pressing physics.
  const std::vector<Override> first = {{"pressing.speed_m_per_s", 0.5},
                                       {"pressing.kinetic_work_tolerance", 1.0}};
  std::vector<Override> second = first;
  second.push_back({"pressing.target_thickness_um", 170});

  StageCache cache;
  std::vector<pipeline::StageState> kept;
  EXPECT_EQ(cache.Find(StageKeys(text, first, 7)), nullptr);
  pipeline::PipelineReport report =
      pipeline::RunPipeline(ParseScene(text, path, first), pipeline::Progress{}, nullptr, &kept);
  ASSERT_EQ(kept.size(), 1u);  // forming; pressing's state is the report's network
  pipeline::KeepFinalState(report, nullptr, kept);
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[1].stages.back().name, "pressing");
  EXPECT_EQ(report.network.world.particles.size(), 0u);  // moved, not copied
  cache.Keep(StageKeys(text, first, 7), kept);

  // Same scene: starts after pressing. Other pressing target: starts after forming.
  const pipeline::StageState* same = cache.Find(StageKeys(text, first, 7));
  ASSERT_NE(same, nullptr);
  EXPECT_EQ(same->stages.size(), 2u);
  const pipeline::StageState* formed = cache.Find(StageKeys(text, second, 7));
  ASSERT_NE(formed, nullptr);
  ASSERT_EQ(formed->stages.size(), 1u);

  const pipeline::PipelineSpec spec = ParseScene(text, path, second);
  const pipeline::PipelineReport resumed = pipeline::RunPipeline(spec, pipeline::Progress{}, formed);
  const pipeline::PipelineReport scratch = pipeline::RunPipeline(spec, pipeline::Progress{});
  ASSERT_EQ(resumed.stages.size(), scratch.stages.size());
  EXPECT_EQ(resumed.Final().List(), scratch.Final().List());
  const auto& a = resumed.network.world.particles.x;
  const auto& b = scratch.network.world.particles.x;
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i], b[i]) << "particle " << i;
  EXPECT_EQ(cache.hits(), 2);
  EXPECT_EQ(cache.misses(), 1);
}

TEST(StageCache, AFolderCarriesNetworksToTheNextProcess) {
  const std::string path = kScenes + "/tiny.toml";
  const std::string text = ReadSceneText(path);
  const std::vector<Override> first = {{"pressing.speed_m_per_s", 0.5},
                                       {"pressing.kinetic_work_tolerance", 1.0}};
  std::vector<Override> second = first;
  second.push_back({"pressing.target_thickness_um", 170});
  const std::string folder =
      (std::filesystem::temp_directory_path() / "fibrenet_stage_cache_test").string();
  std::filesystem::remove_all(folder);

  {  // One process forms and presses, keeping its networks in the folder.
    StageCache cache(std::size_t{1} << 30, folder);
    std::vector<pipeline::StageState> kept;
    pipeline::PipelineReport report =
        pipeline::RunPipeline(ParseScene(text, path, first), pipeline::Progress{}, nullptr, &kept);
    pipeline::KeepFinalState(report, nullptr, kept);
    cache.Keep(StageKeys(text, first, 7), kept);
  }
  // The next (a resumed campaign, another rank) finds the formed network there.
  StageCache next(std::size_t{1} << 30, folder);
  const pipeline::StageState* formed = next.Find(StageKeys(text, second, 7));
  ASSERT_NE(formed, nullptr);
  ASSERT_EQ(formed->stages.size(), 1u);
  EXPECT_EQ(next.folder_hits(), 1);
  const pipeline::PipelineSpec spec = ParseScene(text, path, second);
  const pipeline::PipelineReport resumed = pipeline::RunPipeline(spec, pipeline::Progress{}, formed);
  const pipeline::PipelineReport scratch = pipeline::RunPipeline(spec, pipeline::Progress{});
  EXPECT_EQ(resumed.Final().List(), scratch.Final().List());

  // A damaged file is forgotten, not trusted.
  const auto keys = StageKeys(text, second, 7);
  std::ofstream(std::filesystem::path(folder) / (keys[0] + ".h5")) << "damaged";
  StageCache third(std::size_t{1} << 30, folder);
  EXPECT_EQ(third.Find(keys), nullptr);
  EXPECT_FALSE(std::filesystem::exists(std::filesystem::path(folder) / (keys[0] + ".h5")));
  std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace fibrenet::campaigns
