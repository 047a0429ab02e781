// Runs a campaign: an optional design-of-experiments sweep and an optional NLopt search at the
// first (cheap) fidelity level, then the confirmation of the best candidates at each finer
// level. Every candidate goes through the results database (campaigns/candidate_book.h), so
// running the same campaign again resumes it: finished candidates are replayed to the
// optimiser from the database instead of being evaluated again.
//
// The evaluator is injected (an Evaluator, or a Scheduler that owns one), so the runner never
// knows whether it drives the DEM pipeline, an analytic function or remote MPI ranks.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "campaigns/campaign_file.h"
#include "campaigns/evaluator.h"
#include "db/results_db.h"
#include "optimizer/scheduler.h"

namespace fibrenet::campaigns {

struct RunnerOptions {
  std::ostream* progress = nullptr;  // one line per candidate and per phase; nullptr: silent
  std::string software_version = "unknown";
  std::string git_commit = "unknown";
};

struct CandidateSummary {
  std::int64_t id = 0;
  std::int64_t eval_index = 0;
  std::string fidelity;
  std::string phase;
  optimizer::Design design;
  std::map<std::string, double> metrics;  // means over replicates
  std::map<std::string, double> std_errors;
  std::map<std::string, std::string> units;
  double objective = 0.0;  // lower is better (a maximised metric is stored negated)
  bool feasible = false;
};

struct CampaignResult {
  std::int64_t campaign_id = 0;
  std::string name;
  std::string status;            // "done", or "stopped: ..." when the wall-time budget ran out
  std::string optimiser_status;  // NLopt's result, or "" without [algorithm]
  int candidates = 0;            // distinct candidates of this run (evaluated or replayed)
  int evaluated = 0;             // candidates evaluated by this invocation
  int replayed = 0;              // candidates taken from the database
  int failed = 0;                // failed candidates among them
  int evaluator_calls = 0;       // replicate evaluations started by this invocation
  double wall_s = 0.0;
  // The best candidate at the finest fidelity level that has one (feasible first).
  std::optional<CandidateSummary> best;
  // The best candidate of each fidelity level, coarse to fine (empty entries left out).
  std::vector<CandidateSummary> best_per_level;
};

// Runs (or resumes) `spec` against `db`, evaluating through `scheduler` (which must be the
// driver). Throws fibrenet::InputError when the database holds a campaign of the same name from
// a different campaign file (anything but [budget] changed) or a goal metric is missing, and
// whatever the evaluator throws besides failed evaluations (optimizer/evaluation.h).
CampaignResult RunCampaign(const CampaignSpec& spec, db::ResultsDb& db,
                           optimizer::Scheduler& scheduler, const RunnerOptions& options);

// The same, evaluating serially in this process with `evaluator`.
CampaignResult RunCampaign(const CampaignSpec& spec, db::ResultsDb& db, const Evaluator& evaluator,
                           const RunnerOptions& options);

}  // namespace fibrenet::campaigns
