// Stage snapshots: the network after a stage, written to HDF5 and read back, continues a run
// bit for bit, and files that are not stage snapshots are refused with InputError.
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "campaigns/scene.h"
#include "campaigns/stage_snapshot.h"
#include "engine/core/error.h"
#include "engine/io/snapshot.h"

namespace fibrenet::campaigns {
namespace {

const std::string kScenes = FIBRENET_SCENES_DIR;

std::string TempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / name).string();
}

TEST(StageSnapshot, ContinuesARunBitForBit) {
  const std::string path = kScenes + "/tiny.toml";
  // Fast, loosely guarded pressing: this test is about continuation, not pressing physics.
  const pipeline::PipelineSpec spec = LoadScene(
      path, {{"pressing.speed_m_per_s", 0.5}, {"pressing.kinetic_work_tolerance", 1.0}});
  std::vector<pipeline::StageState> kept;
  const pipeline::PipelineReport scratch = pipeline::RunPipeline(spec, {}, nullptr, &kept);
  ASSERT_EQ(kept.size(), 1u);  // the formed network; the pressed one is scratch.network

  const std::string file = TempPath("fibrenet_stage_snapshot_test.h5");
  WriteStageSnapshot(kept[0], file, {"tiny.toml", "abc", 7});
  const StageSnapshot read = ReadStageSnapshot(file);
  EXPECT_EQ(read.origin.scene, "tiny.toml");
  EXPECT_EQ(read.origin.scene_hash, "abc");
  EXPECT_EQ(read.origin.seed, 7u);
  ASSERT_EQ(read.state.stages.size(), 1u);
  EXPECT_EQ(read.state.stages[0].name, "forming");
  EXPECT_EQ(read.state.stages[0].steps, kept[0].stages[0].steps);
  EXPECT_EQ(read.state.stages[0].metrics.List(), kept[0].stages[0].metrics.List());
  // Details come back by name (JSON objects keep no order).
  auto sorted = [](auto details) {
    std::sort(details.begin(), details.end());
    return details;
  };
  EXPECT_EQ(sorted(read.state.stages[0].details), sorted(kept[0].stages[0].details));
  const pipeline::Network& a = read.state.network;
  const pipeline::Network& b = kept[0].network;
  ASSERT_EQ(a.fibres.size(), b.fibres.size());
  for (std::size_t f = 0; f < a.fibres.size(); ++f) {
    EXPECT_EQ(a.fibres[f].first_particle, b.fibres[f].first_particle);
    EXPECT_EQ(a.fibres[f].bond_count, b.fibres[f].bond_count);
    EXPECT_EQ(a.fibres[f].coarseness, b.fibres[f].coarseness);
    EXPECT_EQ(a.fibres[f].strength, b.fibres[f].strength);
  }

  // Pressing from the file ends exactly where the uninterrupted run ended.
  const pipeline::PipelineReport resumed = pipeline::RunPipeline(spec, {}, &read.state);
  ASSERT_EQ(resumed.stages.size(), scratch.stages.size());
  EXPECT_EQ(resumed.Final().List(), scratch.Final().List());
  const auto& x = resumed.network.world.particles.x;
  const auto& y = scratch.network.world.particles.x;
  ASSERT_EQ(x.size(), y.size());
  for (std::size_t i = 0; i < x.size(); ++i) ASSERT_EQ(x[i], y[i]) << "particle " << i;
  std::filesystem::remove(file);
  std::filesystem::remove(TempPath("fibrenet_stage_snapshot_test.xdmf"));
}

TEST(StageSnapshot, RefusesFilesThatAreNotStageSnapshots) {
  EXPECT_THROW(ReadStageSnapshot(TempPath("fibrenet_no_such_snapshot.h5")), InputError);
  // A bare World snapshot has no fibre table.
  World w;
  w.cell.hi = Vec3(1e-3, 1e-3, 1e-3);
  w.particles.Add(Vec3(5e-4, 5e-4, 5e-4), 1e-5, 1e-12, 0);
  const std::string file = TempPath("fibrenet_bare_world.h5");
  io::WriteSnapshot(w, file);
  try {
    ReadStageSnapshot(file);
    ADD_FAILURE() << "a bare World snapshot was read as a stage snapshot";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not a fibre-network snapshot"), std::string::npos)
        << e.what();
  }
  std::filesystem::remove(file);
  std::filesystem::remove(TempPath("fibrenet_bare_world.xdmf"));
}

}  // namespace
}  // namespace fibrenet::campaigns
