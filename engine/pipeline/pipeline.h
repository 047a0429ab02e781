// One pipeline run: form the network, then run each enabled stage in order, measuring the
// network after each. This is the narrow call that scene files (campaigns/) and the
// optimiser use: everything in SI units, validated before anything runs.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "engine/pipeline/consolidation.h"
#include "engine/pipeline/creping.h"
#include "engine/pipeline/forming.h"
#include "engine/pipeline/metrics.h"
#include "engine/pipeline/network.h"
#include "engine/pipeline/progress.h"
#include "engine/pipeline/through_air.h"
#include "engine/pipeline/virtual_tests.h"

namespace fibrenet::pipeline {

struct PipelineSpec {
  std::uint64_t seed = 1;
  SheetSpec sheet;
  FormingSettings forming;                  // always runs: it makes the network
  // Consolidation, at most one: wet pressing with a flat or embossing plate, or moulding on
  // a through-air-drying fabric.
  std::optional<PressingSettings> pressing;
  std::optional<ThroughAirSettings> through_air;
  std::optional<CrepingSettings> creping;   // after consolidation, when present
  MetricsSettings metrics;
  VirtualTestsSpec tests;                   // run on the final network, when any

  // Empty when valid; otherwise "<section>.<field>: what is wrong and the accepted range".
  std::string Validate() const;
  // Name of the consolidation stage ("pressing", "through_air"), empty when there is none.
  std::string Consolidation() const;
};

struct StageReport {
  std::string name;
  double wall_s = 0.0;
  std::int64_t steps = 0;
  NetworkMetrics metrics;
  std::vector<std::pair<std::string, double>> details;  // stage-specific numbers
  std::vector<std::string> warnings;
  std::vector<PressPoint> press_curve;                   // pressing only
  std::vector<Curve> curves;                             // other stage curves (creping)
  std::vector<World> frames;                             // snapshots during the stage
};

struct PipelineReport {
  std::vector<StageReport> stages;
  double wall_s = 0.0;
  Network network;  // the final state (before the virtual tests, which work on copies)
  std::optional<VirtualTestsReport> tests;

  const NetworkMetrics& Final() const { return stages.back().metrics; }
  // Every scalar result: the final network's metrics, then the virtual tests' metrics.
  std::vector<Metric> AllMetrics() const;
};

// The state after a network stage (forming, pressing): its reports so far and the network.
// A run whose settings differ from an earlier one only downstream of that stage can start
// from it instead of making the network again (the campaign stage cache).
struct StageState {
  std::vector<StageReport> stages;  // "forming", then consolidation and creping when they ran
  Network network;
};

// Throws InputError when spec is invalid and RunError when a stage fails.
// `start`: continue after the stages it holds (they must be the spec's first stages).
// `kept`: receives the state after each network stage this run computes except the last,
// whose state is the returned report's network (with its stages before "tests").
PipelineReport RunPipeline(const PipelineSpec& spec, const Progress& progress,
                           const StageState* start = nullptr,
                           std::vector<StageState>* kept = nullptr);

// The report's network stages: its stages without the trailing "tests".
std::span<const StageReport> NetworkStages(const PipelineReport& report);

// Completes `kept` with the state after the run's last network stage, its network moved out of
// the report, when the run computed that stage (not when it started after it, from `start`).
void KeepFinalState(PipelineReport& report, const StageState* start,
                    std::vector<StageState>& kept);

}  // namespace fibrenet::pipeline
