// The binding of campaigns to the DEM scene pipeline: evaluating a candidate means loading the
// base scene, applying the design's values and the fidelity's overrides by dotted key path
// (e.g. "pressing.target_thickness_um" = 150), running it with the replicate's seed and
// returning its metrics with units.
#pragma once

#include <string>
#include <vector>

#include "campaigns/evaluator.h"

namespace fibrenet::campaigns {

// The evaluator of the scene file at `scene_path` (read and checked here: InputError when
// it is missing or invalid). Each call applies design then fidelity overrides, runs the
// pipeline with the replicate's seed and returns the final network metrics (and wall_s).
// `stage_folder`: the stage cache's folder on disk ("" for memory only).
Evaluator MakeSceneEvaluator(const std::string& scene_path,
                             const std::vector<std::string>& goal_metrics = {},
                             const std::string& stage_folder = "");

}  // namespace fibrenet::campaigns
