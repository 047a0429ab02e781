// `fibrenet run SCENE.toml [--out DIR] [--from SNAPSHOT] [--until STAGE] [--json]
// [--threads N] [--set KEY=VALUE ...]`: one pipeline run, or its continuation from the
// snapshot of a network stage that an earlier run wrote, or its first stages only. Progress
// goes to stderr; metrics to stdout (one JSON document with --json); files only under --out.
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "campaigns/run_report.h"
#include "campaigns/campaign_file.h"
#include "campaigns/scene.h"
#include "campaigns/stage_snapshot.h"
#include "engine/core/error.h"
#include "engine/core/parallel.h"
#include "engine/pipeline/pipeline.h"

namespace fibrenet::cli {

namespace {

struct RunOptions {
  std::string scene;
  std::string out;
  std::string from;
  std::string until;
  bool json = false;
  int threads = 0;
  std::vector<std::string> overrides;
  double progress_interval_s = 5.0;
};

void PrintHuman(const pipeline::PipelineReport& report) {
  for (const pipeline::StageReport& s : report.stages) {
    std::cout << fmt::format("stage {}: {} steps, {:.1f} s\n", s.name, s.steps, s.wall_s);
    for (const auto& [name, value] : s.metrics.List())
      std::cout << fmt::format("  {:36} {:.6g}\n", name, value);
    for (const auto& [name, value] : s.details)
      std::cout << fmt::format("  ({}) {:31} {:.6g}\n", s.name, name, value);
  }
  std::cout << fmt::format("total wall time {:.1f} s\n", report.wall_s);
}

// The snapshot's stages must be the scene's first stages; the scene's later stages run on.
campaigns::StageSnapshot LoadStart(const std::string& path, const pipeline::PipelineSpec& spec,
                                   const campaigns::SnapshotOrigin& scene) {
  campaigns::StageSnapshot start = campaigns::ReadStageSnapshot(path);
  const std::string& last = start.state.stages.back().name;
  const bool creped = last == "creping" && spec.creping;
  if (last != "forming" && last != spec.Consolidation() && !creped)
    throw InputError(fmt::format(
        "{}: holds the network after {}, but {} has no [{}] stage to continue after (accepted: "
        "a snapshot after forming{}{})", path, last, scene.scene, last,
        spec.Consolidation().empty() ? "" : " or after " + spec.Consolidation(),
        spec.creping ? " or after creping" : ""));
  if (start.origin.scene_hash != scene.scene_hash || start.origin.seed != scene.seed)
    std::cerr << fmt::format("note: {} was made from {} (seed {}), not from this scene text and "
                             "seed; its stages are kept as they are and the stages after {} "
                             "come from {}\n",
                             path, start.origin.scene, start.origin.seed, last, scene.scene);
  return start;
}

// With --from, the snapshot's stages are kept as they are: an override of a table only they
// read would change nothing, so it is refused rather than ignored.
void RefuseOverridesOfKeptStages(const std::vector<campaigns::Override>& overrides,
                                 const std::string& from, const std::string& last) {
  using campaigns::KeyStage;
  const KeyStage kept = last == "forming"   ? KeyStage::kForming
                        : last == "creping" ? KeyStage::kCreping
                                            : KeyStage::kConsolidation;
  for (const campaigns::Override& o : overrides) {
    const KeyStage fed = campaigns::StageOfKey(o.path);
    const std::string table = o.path.substr(0, o.path.find('.'));
    if (fed != KeyStage::kEvery && static_cast<int>(fed) <= static_cast<int>(kept))
      throw InputError(fmt::format(
          "--set {}: {} holds the network after {}, made with its own [{}], so the override would "
          "change nothing; accepted with this snapshot: keys of the stages after {}, or a run "
          "from an earlier snapshot",
          o.path, from, last, table, last));
  }
}

// The scene cut after the stage `until` names: the stages before it are the scene's own, so
// their snapshots are the ones a whole run writes.
void StopAfter(pipeline::PipelineSpec& spec, const std::string& until, const std::string& scene) {
  std::vector<std::string> stages = {"forming"};
  if (!spec.Consolidation().empty()) stages.push_back(spec.Consolidation());
  if (spec.creping) stages.push_back("creping");
  if (until == "forming") {
    spec.pressing.reset();
    spec.through_air.reset();
  }
  if (until != "creping") spec.creping.reset();
  spec.tests = {};
  if (std::find(stages.begin(), stages.end(), until) == stages.end())
    throw InputError(fmt::format("--until {}: {} has no such stage; accepted: {}", until, scene,
                                 fmt::join(stages, ", ")));
}

int Run(const RunOptions& o) {
  std::vector<campaigns::Override> overrides;
  for (const std::string& text : o.overrides) overrides.push_back(campaigns::ParseOverride(text));
  const std::string scene_text = campaigns::ReadSceneText(o.scene);
  pipeline::PipelineSpec spec = campaigns::ParseScene(scene_text, o.scene, overrides);
  if (!o.until.empty()) StopAfter(spec, o.until, o.scene);
  // The overrides are part of what made the networks, as the campaigns' stage keys have it.
  std::string identity = scene_text;
  for (const campaigns::Override& v : overrides)
    identity += v.flag ? fmt::format("\n{} = {}", v.path, *v.flag)
                       : fmt::format("\n{} = {:.17g}", v.path, v.value);
  const campaigns::SnapshotOrigin origin{o.scene, campaigns::HashText(identity), spec.seed};
  std::optional<campaigns::StageSnapshot> start;
  if (!o.from.empty()) {
    start = LoadStart(o.from, spec, origin);
    RefuseOverridesOfKeptStages(overrides, o.from, start->state.stages.back().name);
  }
  if (o.threads > 0) SetThreadCount(o.threads);

  pipeline::Progress progress;
  progress.interval_s = o.progress_interval_s;
  progress.report = [](const std::string& line) { std::cerr << line << std::endl; };
  progress.Say(fmt::format("run {}: seed {}, {} thread(s)", o.scene, spec.seed, ThreadCount()));
  std::vector<pipeline::StageState> kept;
  const pipeline::PipelineReport report = pipeline::RunPipeline(
      spec, progress, start ? &start->state : nullptr, o.out.empty() ? nullptr : &kept);
  for (const pipeline::StageReport& s : report.stages)
    for (const std::string& w : s.warnings) std::cerr << "warning (" << s.name << "): " << w << "\n";
  if (!o.out.empty()) {
    campaigns::WriteOutputs(o.out, report);
    campaigns::WriteStageSnapshots(o.out, std::move(kept), origin, report);
  }
  if (o.json)
    std::cout << campaigns::ReportJson(report).dump(2) << "\n";
  else
    PrintHuman(report);
  return 0;
}

// Checks --out before the run, so that a path that cannot become a folder is bad input found
// at once rather than a failure after the whole simulation: an existing writable folder, or a
// new one whose nearest existing ancestor is a writable folder. Creates nothing.
std::string CheckOutFolder(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path path = fs::absolute(fs::path(dir), ec);
  fs::path existing = path;
  while (!fs::exists(existing, ec) && existing != existing.parent_path())
    existing = existing.parent_path();
  if (!fs::is_directory(existing, ec)) {
    return fmt::format("'{}' is not a folder{}; accepted: a folder, existing or new",
                       existing.string(),
                       existing == path ? "" : fmt::format(", so {} cannot be made", dir));
  }
  if (::access(existing.c_str(), W_OK | X_OK) != 0)
    return fmt::format("folder '{}' is not writable; accepted: a folder fibrenet may write",
                       existing.string());
  return "";
}

}  // namespace

void AddRunCommand(CLI::App& app, Context& context) {
  auto options = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "Run the pipeline of one scene file and print metrics");
  cmd->add_option("scene", options->scene, "Scene file (TOML)")->required();
  cmd->add_option("--out", options->out, "Write metrics, profiles, curves and particles here")
      ->check(CLI::Validator(CheckOutFolder, "DIR"));
  cmd->add_option("--from", options->from,
                  "Continue from a stage snapshot (DIR/snapshots/*.h5 of an earlier --out)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--until", options->until,
                  "Stop after this stage (forming, pressing, through_air or creping): no tests");
  cmd->add_flag("--json", options->json, "Print one JSON document on stdout");
  cmd->add_option("--threads", options->threads, "OpenMP threads (default: all)")
      ->check(CLI::Range(1, 1024));
  cmd->add_option("--set", options->overrides,
                  "Override a scene key, KEY=NUMBER or KEY=true|false (dotted path, repeatable)");
  cmd->add_option("--progress-interval", options->progress_interval_s,
                  "Seconds between progress lines on stderr")
      ->check(CLI::Range(0.1, 3600.0));
  cmd->callback([options, &context] { context.exit_code = Run(*options); });
}

}  // namespace fibrenet::cli
