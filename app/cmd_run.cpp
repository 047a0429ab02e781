// `fibrenet run SCENE.toml [--out DIR] [--json] [--threads N] [--set KEY=VALUE ...]`: one
// pipeline run. Progress goes to stderr; metrics to stdout (one JSON document with --json);
// files only under --out.
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "campaigns/run_report.h"
#include "campaigns/scene.h"
#include "engine/core/parallel.h"
#include "engine/pipeline/pipeline.h"

namespace fibrenet::cli {

namespace {

struct RunOptions {
  std::string scene;
  std::string out;
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

int Run(const RunOptions& o) {
  std::vector<campaigns::Override> overrides;
  for (const std::string& text : o.overrides) overrides.push_back(campaigns::ParseOverride(text));
  const pipeline::PipelineSpec spec = campaigns::LoadScene(o.scene, overrides);
  if (o.threads > 0) SetThreadCount(o.threads);

  pipeline::Progress progress;
  progress.interval_s = o.progress_interval_s;
  progress.report = [](const std::string& line) { std::cerr << line << std::endl; };
  progress.Say(fmt::format("run {}: seed {}, {} thread(s)", o.scene, spec.seed, ThreadCount()));
  const pipeline::PipelineReport report = pipeline::RunPipeline(spec, progress);
  for (const pipeline::StageReport& s : report.stages)
    for (const std::string& w : s.warnings) std::cerr << "warning (" << s.name << "): " << w << "\n";
  if (!o.out.empty()) campaigns::WriteOutputs(o.out, report);
  if (o.json)
    std::cout << campaigns::ReportJson(report).dump(2) << "\n";
  else
    PrintHuman(report);
  return 0;
}

}  // namespace

void AddRunCommand(CLI::App& app, Context& context) {
  auto options = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "Run the pipeline of one scene file and print metrics");
  cmd->add_option("scene", options->scene, "Scene file (TOML)")->required();
  cmd->add_option("--out", options->out, "Write metrics, profiles, curves and particles here");
  cmd->add_flag("--json", options->json, "Print one JSON document on stdout");
  cmd->add_option("--threads", options->threads, "OpenMP threads (default: all)")
      ->check(CLI::Range(1, 1024));
  cmd->add_option("--set", options->overrides,
                  "Override a numeric scene key, KEY=VALUE (dotted path, repeatable)");
  cmd->add_option("--progress-interval", options->progress_interval_s,
                  "Seconds between progress lines on stderr")
      ->check(CLI::Range(0.1, 3600.0));
  cmd->callback([options, &context] { context.exit_code = Run(*options); });
}

}  // namespace fibrenet::cli
