// Recovery on the DEM pipeline: the metric of a known design becomes the target of a campaign
// started elsewhere in the design space, which must reach it within 5% inside its budget.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "campaigns/campaign_file.h"
#include "campaigns/campaign_runner.h"
#include "campaigns/scene_evaluator.h"
#include "optimizer/replicates.h"
#include "tests/db/temp_db.h"

namespace fibrenet::campaigns {
namespace {

const std::string kScenes = FIBRENET_SCENES_DIR;

TEST(SceneCampaign, RecoversTheBondLevelOfAKnownPressing) {
  constexpr std::uint64_t kSeed = 3;
  constexpr double kTruthThickness = 160.0;  // [um]
  constexpr int kBudget = 12;
  // A fast, loosely guarded pressing: this test is about the search, not pressing physics.
  optimizer::Fidelity fast;
  fast.name = "fast";
  fast.overrides = {{"pressing.speed_m_per_s", 0.5}, {"pressing.kinetic_work_tolerance", 1.0}};

  int calls = 0;
  const Evaluator scene = MakeSceneEvaluator(kScenes + "/tiny.toml");
  const Evaluator counted = [&](const optimizer::Design& d, const optimizer::Fidelity& f,
                                std::uint64_t seed) {
    ++calls;
    return scene(d, f, seed);
  };
  const optimizer::EvaluationResult truth =
      counted({{"pressing.target_thickness_um", kTruthThickness}}, fast,
              optimizer::ReplicateSeed(kSeed, 0));
  ASSERT_TRUE(truth.ok) << truth.reason;
  const double target = truth.metrics.at("bonds_per_fibre");
  ASSERT_GT(target, 1.0);
  // The campaign starts far from the answer, so the search has the work to do.
  const optimizer::EvaluationResult start =
      counted({{"pressing.target_thickness_um", 225.0}}, fast, optimizer::ReplicateSeed(kSeed, 0));
  ASSERT_TRUE(start.ok) << start.reason;
  ASSERT_GT(std::abs(start.metrics.at("bonds_per_fibre") - target), 0.2 * target);

  const std::string text = fmt::format(R"(
name = "recover-bonds"
base_scene = "tiny.toml"
seed = {}
[[variables]]
key = "pressing.target_thickness_um"
lower = 120
upper = 240
start = 225
[goals.targets]
bonds_per_fibre = {}
[algorithm]
name = "LN_COBYLA"
initial_step = 0.25
[budget]
max_evaluations = {}
[[fidelity]]
name = "fast"
overrides = {{ "pressing.speed_m_per_s" = 0.5, "pressing.kinetic_work_tolerance" = 1.0 }}
)",
                                       kSeed, target, kBudget);
  const CampaignSpec spec = ParseCampaign(text, "recover-bonds.toml", kScenes);
  db::testing::TempDbPath path;
  db::ResultsDb db(path.str());
  calls = 0;
  const CampaignResult r = RunCampaign(spec, db, counted, {});
  ASSERT_TRUE(r.best);
  const double reached = r.best->metrics.at("bonds_per_fibre");
  EXPECT_NEAR(reached, target, 0.05 * target)
      << "reached at " << r.best->design.at("pressing.target_thickness_um") << " um";
  EXPECT_LE(calls, kBudget);
}

}  // namespace
}  // namespace fibrenet::campaigns
