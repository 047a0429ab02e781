// What a pipeline run hands back to its caller, in the forms the CLI and the campaign
// driver need: one JSON document, and files (metrics, density profiles, the pressing curve,
// particle positions) written under an output folder.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "engine/pipeline/pipeline.h"

namespace fibrenet::campaigns {

// {"metrics": {...final...}, "stages": [{"name", "wall_s", "steps", "metrics", "details",
//  "warnings"}], "wall_s": ...}
nlohmann::json ReportJson(const pipeline::PipelineReport& report);

// One stage's entry of "stages" above, and back (the density profile and pressing curve
// are not part of it). StageFromJson throws fibrenet::Error on a malformed entry.
nlohmann::json StageJson(const pipeline::StageReport& stage);
pipeline::StageReport StageFromJson(const nlohmann::json& j);

// Writes under dir (created if needed): metrics.json, <stage>_density_profile.csv,
// pressing_curve.csv, the virtual tests' curves under curves/, and the final particles.csv.
// Throws RunError on I/O failure.
void WriteOutputs(const std::string& dir, const pipeline::PipelineReport& report);

}  // namespace fibrenet::campaigns
