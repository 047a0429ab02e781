// The campaign's record of its candidates, kept in step with the results database: every
// candidate is stored (pending) before it runs, marked running when its first replicate
// starts, and updated (done or failed) when its last replicate ends. A candidate already in
// the database (same parameters, fidelity and seeds: the same key) is not run again: a done or
// failed one is replayed from its stored results, a pending or running one (left by a crash)
// is run. Internal to campaigns/.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "campaigns/campaign_file.h"
#include "db/results_db.h"
#include "optimizer/goals.h"
#include "optimizer/scheduler.h"

namespace fibrenet::campaigns {

struct MetricSummary {
  double value = 0.0;  // mean over replicates
  std::optional<double> std_error;
  std::string unit;
  int n = 1;
};

enum class CandidateState { kToRun, kDone, kFailed };

struct CandidateRecord {
  std::int64_t id = 0;
  std::int64_t eval_index = 0;
  std::string key;
  optimizer::Design design;
  int level = 0;  // index into CampaignSpec::fidelities
  std::string phase;
  std::vector<std::uint64_t> seeds;
  CandidateState state = CandidateState::kToRun;
  bool replayed = false;  // results taken from the database, not evaluated in this run
  bool running = false;   // marked running in the database by this run
  std::map<std::string, MetricSummary> metrics;
  optimizer::GoalValues goals;  // when done
  std::string reason;           // when failed
  double penalty = 0.0;         // when failed: the value handed to the optimiser
  double wall_s = 0.0;
  std::vector<std::optional<optimizer::TaskResult>> replicates;  // while running

  bool finished() const { return state != CandidateState::kToRun; }
};

class CandidateBook {
 public:
  CandidateBook(db::ResultsDb& db, std::int64_t campaign_id, const CampaignSpec& spec);

  // The record of `design` at fidelity `level`: found in this run, or in the database (done
  // and failed ones are replayed at once), or inserted into the database as pending.
  CandidateRecord& Propose(const optimizer::Design& design, int level, const std::string& phase);

  // Marks the candidate running in the database (once).
  void MarkRunning(CandidateRecord& record);

  // Stores one replicate's result; when all are in, reduces them, evaluates the goals, writes
  // the candidate (done, or failed with its reason and `penalty`) and returns true.
  // Throws fibrenet::InputError (after storing the candidate as failed) when a goal metric is
  // missing from the scene's metrics.
  bool AddReplicate(CandidateRecord& record, int replicate, optimizer::TaskResult&& result,
                    double penalty);

  // Finished candidates at `level`, best first: feasible first, then lower objective, then
  // earlier evaluation.
  std::vector<const CandidateRecord*> Ranked(int level) const;

  // Records in the order they were first proposed in this run.
  const std::vector<CandidateRecord*>& in_order() const { return order_; }

  // The database key of a candidate: a hash of fidelity name, seeds and parameter values.
  static std::string Key(const optimizer::Design& design, const std::string& fidelity,
                         const std::vector<std::uint64_t>& seeds);

 private:
  void Replay(CandidateRecord& record, const db::CandidateRow& row);
  void EvaluateGoals(CandidateRecord& record);

  db::ResultsDb& db_;
  std::int64_t campaign_id_;
  const CampaignSpec& spec_;
  std::int64_t next_index_ = 0;
  std::map<std::string, std::unique_ptr<CandidateRecord>> by_key_;
  std::vector<CandidateRecord*> order_;
};

// True if `a` ranks before `b` (see CandidateBook::Ranked).
bool RanksBefore(const CandidateRecord& a, const CandidateRecord& b);

}  // namespace fibrenet::campaigns
