#include "campaigns/candidate_book.h"

#include <fmt/format.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <set>

#include "db/queries.h"
#include "engine/core/error.h"
#include "optimizer/replicates.h"

namespace fibrenet::campaigns {

bool RanksBefore(const CandidateRecord& a, const CandidateRecord& b) {
  if (a.goals.feasible != b.goals.feasible) return a.goals.feasible;
  if (a.goals.objective != b.goals.objective) return a.goals.objective < b.goals.objective;
  return a.eval_index < b.eval_index;
}

CandidateBook::CandidateBook(db::ResultsDb& db, std::int64_t campaign_id, const CampaignSpec& spec)
    : db_(db), campaign_id_(campaign_id), spec_(spec) {}

std::string CandidateBook::Key(const optimizer::Design& design, const std::string& fidelity,
                               const std::vector<std::uint64_t>& seeds) {
  // %.17g writes every double exactly, so equal keys mean equal parameters.
  std::string text = "fidelity=" + fidelity + ";seeds=";
  for (std::uint64_t s : seeds) text += fmt::format("{},", s);
  for (const auto& [name, value] : design) text += fmt::format(";{}={:.17g}", name, value);
  return HashText(text);
}

CandidateRecord& CandidateBook::Propose(const optimizer::Design& design, int level,
                                        const std::string& phase) {
  const optimizer::Fidelity& fidelity = spec_.fidelities.at(static_cast<std::size_t>(level));
  std::vector<std::uint64_t> seeds = optimizer::ReplicateSeeds(spec_.seed, fidelity.replicates);
  const std::string key = Key(design, fidelity.name, seeds);
  if (auto it = by_key_.find(key); it != by_key_.end()) return *it->second;

  auto record = std::make_unique<CandidateRecord>();
  record->key = key;
  record->design = design;
  record->level = level;
  record->phase = phase;
  record->seeds = std::move(seeds);
  if (const auto row = db::find_candidate_by_key(db_, campaign_id_, key)) {
    record->id = row->id;
    record->eval_index = row->eval_index;
    if (row->status == db::CandidateStatus::kDone || row->status == db::CandidateStatus::kFailed) {
      Replay(*record, *row);
    }
  } else {
    record->eval_index = next_index_;
    record->id =
        db_.insert_candidate(campaign_id_, record->eval_index, key, fidelity.name, record->seeds,
                             design, nlohmann::json{{"phase", phase}, {"level", level}});
  }
  next_index_ = std::max(next_index_, record->eval_index + 1);
  CandidateRecord& ref = *record;
  order_.push_back(record.get());
  by_key_.emplace(key, std::move(record));
  return ref;
}

void CandidateBook::Replay(CandidateRecord& record, const db::CandidateRow& row) {
  record.replayed = true;
  record.wall_s = row.wall_s.value_or(0.0);
  if (row.status == db::CandidateStatus::kFailed) {
    record.state = CandidateState::kFailed;
    record.reason = row.reason;
    return;
  }
  for (const db::MetricValue& m : row.metrics) {
    record.metrics[m.name] = MetricSummary{m.value, m.std_error, m.unit, m.n_replicates};
  }
  EvaluateGoals(record);
  record.state = CandidateState::kDone;
}

void CandidateBook::EvaluateGoals(CandidateRecord& record) {
  std::map<std::string, double> means;
  for (const auto& [name, m] : record.metrics) means[name] = m.value;
  record.goals = spec_.goals.Evaluate(means);
}

void CandidateBook::MarkRunning(CandidateRecord& record) {
  if (record.running) return;
  db_.mark_running(record.id);
  record.running = true;
}

bool CandidateBook::AddReplicate(CandidateRecord& record, int replicate,
                                 optimizer::TaskResult&& result, double penalty) {
  record.replicates.resize(record.seeds.size());
  record.replicates.at(static_cast<std::size_t>(replicate)) = std::move(result);
  for (const auto& r : record.replicates) {
    if (!r) return false;
  }
  std::vector<optimizer::EvaluationResult> results;
  std::vector<db::Artifact> artifacts;
  std::set<std::pair<std::string, std::string>> seen;
  std::string failure;
  record.wall_s = 0.0;
  for (std::size_t r = 0; r < record.replicates.size(); ++r) {
    const optimizer::TaskResult& t = *record.replicates[r];
    record.wall_s += t.wall_s;
    for (const optimizer::ArtifactPath& a : t.result.artifacts) {
      if (seen.insert({a.kind, a.path}).second) artifacts.push_back({a.kind, a.path});
    }
    if (!t.result.ok && failure.empty()) {
      failure = record.seeds.size() > 1
                    ? fmt::format("replicate {} (seed {}): {}", r, record.seeds[r], t.result.reason)
                    : t.result.reason;
    }
    results.push_back(t.result);
  }
  record.replicates.clear();
  if (!failure.empty()) {
    record.state = CandidateState::kFailed;
    record.reason = failure;
    record.penalty = penalty;
    db_.mark_failed(record.id, fmt::format("{} [penalty {:.6g}]", failure, penalty), record.wall_s,
                    artifacts);
    return true;
  }
  const auto stats = optimizer::ReduceReplicates(results);
  nlohmann::json replicate_values = nlohmann::json::object();
  for (const auto& [name, s] : stats) {
    record.metrics[name] = MetricSummary{
        s.mean, s.n > 1 ? std::optional<double>(s.std_error) : std::nullopt, s.unit, s.n};
    if (s.n > 1) replicate_values[name] = s.values;
  }
  try {
    EvaluateGoals(record);
  } catch (const InputError& e) {
    record.state = CandidateState::kFailed;
    record.reason = e.what();
    db_.mark_failed(record.id, record.reason, record.wall_s, artifacts);
    throw;
  }
  record.state = CandidateState::kDone;
  std::vector<db::MetricValue> metrics;
  for (const auto& [name, m] : record.metrics) {
    metrics.push_back({name, m.value, m.unit, m.std_error, m.n});
  }
  nlohmann::json constraints = nlohmann::json::object();
  const std::vector<std::string> labels = spec_.goals.ConstraintLabels();
  for (std::size_t i = 0; i < labels.size(); ++i)
    constraints[labels[i]] = record.goals.constraints[i];
  nlohmann::json provenance = {{"constraints", constraints},
                               {"merit", spec_.goals.Merit(record.goals)}};
  if (!replicate_values.empty()) provenance["replicates"] = replicate_values;
  db_.mark_done(record.id, metrics, record.goals.objective, record.goals.feasible, record.wall_s,
                artifacts, provenance);
  return true;
}

std::vector<const CandidateRecord*> CandidateBook::Ranked(int level) const {
  std::vector<const CandidateRecord*> ranked;
  for (const CandidateRecord* r : order_) {
    if (r->level == level && r->state == CandidateState::kDone) ranked.push_back(r);
  }
  std::sort(ranked.begin(), ranked.end(),
            [](const CandidateRecord* a, const CandidateRecord* b) { return RanksBefore(*a, *b); });
  return ranked;
}

}  // namespace fibrenet::campaigns
