#include "campaigns/evaluator.h"

#include "campaigns/analytic_evaluator.h"
#include "campaigns/campaign_file.h"
#include "campaigns/scene_evaluator.h"

namespace fibrenet::campaigns {

Evaluator MakeEvaluator(const std::string& base_scene, const std::vector<std::string>& goal_metrics,
                        const std::string& stage_folder) {
  if (base_scene.rfind(kAnalyticPrefix, 0) == 0) {
    return MakeAnalyticEvaluator(base_scene.substr(kAnalyticPrefix.size()));
  }
  return MakeSceneEvaluator(base_scene, goal_metrics, stage_folder);
}

}  // namespace fibrenet::campaigns
