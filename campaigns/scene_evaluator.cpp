#include "campaigns/scene_evaluator.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <fmt/format.h>

#include "campaigns/scene.h"
#include "campaigns/stage_cache.h"
#include "engine/core/error.h"
#include "engine/pipeline/pipeline.h"

namespace fibrenet::campaigns {

Evaluator MakeSceneEvaluator(const std::string& scene_path,
                             const std::vector<std::string>& goal_metrics,
                             const std::string& stage_folder) {
  // Read and check the base scene once; every evaluation re-reads the text with its own
  // overrides so that validation sees the design's values.
  auto text = std::make_shared<const std::string>(ReadSceneText(scene_path));
  ParseScene(*text, scene_path);
  auto cache = std::make_shared<StageCache>(std::size_t{1} << 30, stage_folder);
  return [scene_path, text, cache, goal_metrics](const optimizer::Design& design,
                                   const optimizer::Fidelity& fidelity, std::uint64_t seed) {
    std::vector<Override> overrides;
    for (const auto& [key, value] : design) overrides.push_back({key, value});
    for (const auto& [key, value] : fidelity.overrides) overrides.push_back({key, value});
    pipeline::PipelineSpec spec = ParseScene(*text, scene_path, overrides);
    spec.seed = seed;
    const std::vector<std::string> keys = StageKeys(*text, overrides, seed);
    const pipeline::StageState* start = cache->Find(keys);
    const double reused = start ? static_cast<double>(start->stages.size()) : 0.0;
    std::vector<pipeline::StageState> kept;
    pipeline::PipelineReport report =
        pipeline::RunPipeline(spec, pipeline::Progress{}, start, &kept);
    pipeline::KeepFinalState(report, start, kept);
    cache->Keep(keys, kept);
    optimizer::EvaluationResult result;
    for (const pipeline::Metric& m : report.AllMetrics()) {
      if (!std::isfinite(m.value)) {
        if (std::find(goal_metrics.begin(), goal_metrics.end(), m.name) != goal_metrics.end())
          throw RunError(fmt::format("goal metric '{}' is not finite ({})", m.name, m.value));
        continue;  // an undefined diagnostic, e.g. a stress ratio of a sheet that carried none
      }
      result.metrics[m.name] = m.value;
      result.units.emplace(m.name, m.unit);
    }
    result.metrics["wall_s"] = report.wall_s;
    // Network stages taken from the stage cache (0: none, 1: forming, 2: forming and pressing).
    result.metrics["reused_stages"] = reused;
    result.units.emplace("reused_stages", "-");
    result.units.emplace("wall_s", "s");
    return result;
  };
}

}  // namespace fibrenet::campaigns
