// `fibrenet campaign run CAMPAIGN.toml --db FILE [--json] [--quiet]`: runs or resumes an
// inverse-design campaign (docs/campaigns.md). Under `mpirun -n K` every rank runs this
// command: rank 0 drives the campaign and writes the database, the others evaluate.
#include <fmt/format.h>

#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "app/commands.h"
#include "campaigns/campaign_check.h"
#include "campaigns/campaign_file.h"
#include "campaigns/campaign_runner.h"
#include "campaigns/evaluator.h"
#include "db/error.h"
#include "db/queries.h"
#include "db/results_db.h"
#include "engine/core/error.h"
#include "optimizer/scheduler.h"

namespace fibrenet::cli {

namespace {

struct CampaignRunOptions {
  std::string campaign_file;
  std::string db_path;
  bool json = false;
  bool quiet = false;
  std::string stage_cache;  // folder; "" = next to the database, "none" = memory only
};

// The stage cache's folder: one per build, since another build may make other networks
// from the same scene.
std::string StageFolder(const CampaignRunOptions& o) {
  if (o.stage_cache == "none") return "";
  const std::string root = o.stage_cache.empty() ? o.db_path + ".stages" : o.stage_cache;
  return fmt::format("{}/{}-{}", root, FIBRENET_VERSION, FIBRENET_GIT_COMMIT);
}

nlohmann::json SummaryJson(const campaigns::CandidateSummary& s) {
  nlohmann::json metrics = nlohmann::json::object();
  for (const auto& [name, value] : s.metrics) {
    const auto se = s.std_errors.find(name);
    metrics[name] = {{"value", value},
                     {"unit", s.units.at(name)},
                     {"std_error", se != s.std_errors.end() ? nlohmann::json(se->second)
                                                            : nlohmann::json(nullptr)}};
  }
  return {{"candidate_id", s.id},     {"eval_index", s.eval_index}, {"fidelity", s.fidelity},
          {"phase", s.phase},         {"parameters", s.design},     {"metrics", metrics},
          {"objective", s.objective}, {"feasible", s.feasible}};
}

// Candidates of the campaign whose networks came from the stage cache (metric
// `reused_stages`: 1 formed network reused, 2 formed and pressed): the evaluations saved.
struct StageReuse {
  int forming = 0, pressing = 0;
};

StageReuse CountStageReuse(const db::ResultsDb& db, const std::string& campaign) {
  StageReuse reuse;
  for (const db::CandidateRow& c : db::candidates(db, campaign))
    if (const db::MetricValue* m = c.metric("reused_stages")) {
      reuse.forming += m->value >= 1.0 ? 1 : 0;
      reuse.pressing += m->value >= 2.0 ? 1 : 0;
    }
  return reuse;
}

nlohmann::json ResultJson(const campaigns::CampaignResult& r, const std::string& db_path,
                          const std::string& evaluators) {
  nlohmann::json per_level = nlohmann::json::array();
  for (const auto& s : r.best_per_level) per_level.push_back(SummaryJson(s));
  return {{"campaign", r.name},
          {"campaign_id", r.campaign_id},
          {"database", db_path},
          {"status", r.status},
          {"optimiser_status", r.optimiser_status},
          {"candidates", r.candidates},
          {"evaluated", r.evaluated},
          {"replayed", r.replayed},
          {"failed", r.failed},
          {"evaluator_calls", r.evaluator_calls},
          {"wall_s", r.wall_s},
          {"evaluators", evaluators},
          {"best", r.best ? SummaryJson(*r.best) : nlohmann::json(nullptr)},
          {"best_per_level", per_level}};
}

int RunCampaignCommand(const CampaignRunOptions& o) {
  // Every rank reads the campaign and builds the evaluator, so that workers can evaluate.
  const campaigns::CampaignSpec spec = campaigns::LoadCampaignFile(o.campaign_file);
  campaigns::CheckAgainstBaseScene(spec);  // before the database is touched
  const auto scheduler = optimizer::MakeScheduler(
      campaigns::MakeEvaluator(spec.base_scene, spec.goals.Metrics(), StageFolder(o)));
  if (!scheduler->is_driver()) {
    scheduler->Serve();
    return 0;
  }
  std::unique_ptr<db::ResultsDb> db;
  try {
    db = std::make_unique<db::ResultsDb>(o.db_path, db::OpenMode::kReadWrite);
  } catch (const db::DbError& e) {
    throw InputError(fmt::format("--db {}: {}", o.db_path, e.what()));
  }
  campaigns::RunnerOptions options;
  options.progress = o.quiet ? nullptr : &std::cerr;
  options.software_version = FIBRENET_VERSION;
  options.git_commit = FIBRENET_GIT_COMMIT;
  campaigns::CampaignResult result;
  try {
    result = campaigns::RunCampaign(spec, *db, *scheduler, options);
  } catch (const db::DbError& e) {
    throw RunError(std::string("results database: ") + e.what());
  }
  const StageReuse reuse = CountStageReuse(*db, result.name);
  if (o.json) {
    nlohmann::json j = ResultJson(result, o.db_path, scheduler->description());
    j["stage_cache"] = {{"forming_reused", reuse.forming}, {"pressing_reused", reuse.pressing}};
    std::cout << j.dump(2) << "\n";
  } else {
    std::cout << fmt::format(
        "campaign '{}' {}; {} candidates ({} evaluated, {} replayed, {} "
        "failed); results in {}\n",
        result.name, result.status, result.candidates, result.evaluated, result.replayed,
        result.failed, o.db_path);
    if (reuse.forming > 0)
      std::cout << fmt::format("stage cache: {} candidates reused a formed network ({} of them "
                               "also the pressed one)\n", reuse.forming, reuse.pressing);
    if (result.best) {
      std::cout << fmt::format("best: candidate {} (#{}, fidelity '{}'), objective {:.6g}, {}\n",
                               result.best->id, result.best->eval_index, result.best->fidelity,
                               result.best->objective,
                               result.best->feasible ? "feasible" : "infeasible");
      for (const auto& [key, value] : result.best->design) {
        std::cout << fmt::format("  {} = {:.6g}\n", key, value);
      }
    }
  }
  return 0;
}

}  // namespace

void AddCampaignCommand(CLI::App& app, Context& context) {
  CLI::App* campaign = app.add_subcommand("campaign", "Inverse-design campaigns");
  campaign->require_subcommand(1);
  auto o = std::make_shared<CampaignRunOptions>();
  CLI::App* run = campaign->add_subcommand(
      "run", "Run or resume a campaign (re-running the same command resumes it)");
  run->add_option("campaign", o->campaign_file, "Campaign file (TOML)")->required();
  run->add_option("--db", o->db_path, "Results database (SQLite; created if missing)")->required();
  run->add_flag("--json", o->json, "Print one JSON document on stdout");
  run->add_flag("--quiet", o->quiet, "No progress lines on stderr");
  run->add_option("--stage-cache", o->stage_cache,
                  "Folder of the networks kept for reuse (default: DB.stages next to the "
                  "database; 'none': memory only)");
  run->callback([o, &context] { context.exit_code = RunCampaignCommand(*o); });
}

}  // namespace fibrenet::cli
