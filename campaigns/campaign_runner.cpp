#include "campaigns/campaign_runner.h"

#include <fmt/format.h>

#include <set>

#include "campaigns/candidate_book.h"
#include "campaigns/progress.h"
#include "db/queries.h"
#include "engine/core/error.h"
#include "engine/core/stopwatch.h"
#include "optimizer/doe.h"
#include "optimizer/nlopt_driver.h"

namespace fibrenet::campaigns {
namespace {

class CampaignRun {
 public:
  CampaignRun(const CampaignSpec& spec, db::ResultsDb& db, optimizer::Scheduler& scheduler,
              const RunnerOptions& options)
      : spec_(spec),
        db_(db),
        scheduler_(scheduler),
        options_(options),
        penalty_(spec.failure_penalty) {
    const optimizer::AlgorithmInfo* info =
        spec.algorithm ? optimizer::FindAlgorithm(spec.algorithm->name) : nullptr;
    native_constraints_ = info && info->constraints && spec.goals.NumConstraintValues() > 0;
  }

  CampaignResult Run() {
    Open();
    try {
      RunDoe();
      RunOptimiser();
      RunConfirmations();
    } catch (...) {
      try {
        db_.set_campaign_status(result_.campaign_id, "failed");
      } catch (const std::exception&) {
        // The original error matters more than a status that could not be written.
      }
      throw;
    }
    Close();
    return result_;
  }

 private:
  void Open() {
    if (!scheduler_.is_driver()) throw Error("the campaign runner must run on the driver rank");
    if (const auto existing = db::find_campaign(db_, spec_.name)) {
      if (existing->spec_hash != spec_.spec_hash) {
        throw InputError(fmt::format(
            "{}: campaign '{}' in database {} was started from a different campaign file (only "
            "[budget] may change to resume it); give the campaign a new name or use another "
            "--db",
            spec_.path.empty() ? "campaign" : spec_.path, spec_.name, db_.path()));
      }
    }
    result_.name = spec_.name;
    result_.campaign_id = db_.upsert_campaign(spec_.name, spec_.text, spec_.spec_hash,
                                              options_.software_version, options_.git_commit);
    db_.set_campaign_status(result_.campaign_id, "running");
    book_ = std::make_unique<CandidateBook>(db_, result_.campaign_id, spec_);
    progress_ = std::make_unique<Progress>(options_.progress, spec_, scheduler_.description());
  }

  void Close() {
    for (int level = static_cast<int>(spec_.fidelities.size()) - 1; level >= 0; --level) {
      const auto ranked = book_->Ranked(level);
      if (ranked.empty()) continue;
      if (!result_.best) result_.best = Summarise(*ranked.front());
    }
    for (int level = 0; level < static_cast<int>(spec_.fidelities.size()); ++level) {
      const auto ranked = book_->Ranked(level);
      if (!ranked.empty()) result_.best_per_level.push_back(Summarise(*ranked.front()));
    }
    result_.candidates = static_cast<int>(book_->in_order().size());
    result_.wall_s = clock_.Seconds();
    result_.status = stopped_ ? fmt::format(
                                    "stopped: wall-time budget of {} s reached; run the "
                                    "same command again to continue",
                                    spec_.max_wall_s)
                              : "done";
    db_.set_campaign_status(result_.campaign_id, stopped_ ? "stopped" : "done");
    progress_->Finished(result_);
  }

  bool OutOfTime() const { return spec_.max_wall_s > 0.0 && clock_.Seconds() >= spec_.max_wall_s; }

  // The numbers the optimiser sees for a finished candidate (see optimizer/goals.h for the
  // penalty of failed ones: without native constraints the merit is the penalty itself).
  optimizer::ProblemValues Handed(const CandidateRecord& r) const {
    const std::size_t m = spec_.goals.NumConstraintValues();
    if (r.state == CandidateState::kDone) return {r.goals.objective, r.goals.constraints};
    return {r.penalty,
            std::vector<double>(
                m, native_constraints_ ? optimizer::FailurePenalty::kConstraintValue : 0.0)};
  }

  // Records finished candidates in the history (in the given, deterministic order) once.
  void Observe(CandidateRecord& r) {
    if (!r.finished() || !observed_.insert(&r).second) return;
    if (r.replayed) {
      ++result_.replayed;
      progress_->Candidate(r, *book_, Status());
    }
    if (r.state == CandidateState::kFailed) {
      ++result_.failed;
      return;
    }
    penalty_.Observe(native_constraints_ ? r.goals.objective : spec_.goals.Merit(r.goals));
  }

  ProgressStatus Status() const {
    ProgressStatus s;
    s.elapsed_s = clock_.Seconds();
    s.max_wall_s = spec_.max_wall_s;
    s.optimiser_calls = optimiser_calls_;
    s.max_evaluations = spec_.algorithm ? spec_.stop.max_evaluations : 0;
    return s;
  }

  // Evaluates the designs at `level` as one batch (replicates of all candidates spread over the
  // evaluators). Returns their records in the order of `designs`.
  std::vector<CandidateRecord*> EvaluateBatch(const std::vector<optimizer::Design>& designs,
                                              int level, const std::string& phase) {
    const double penalty = penalty_.Value();
    std::vector<CandidateRecord*> records;
    struct Slot {
      CandidateRecord* record;
      int replicate;
    };
    std::vector<Slot> slots;
    std::vector<optimizer::Task> tasks;
    std::set<CandidateRecord*> queued;
    const optimizer::Fidelity& fidelity = spec_.fidelities[static_cast<std::size_t>(level)];
    for (const optimizer::Design& design : designs) {
      CandidateRecord& r = book_->Propose(design, level, phase);
      records.push_back(&r);
      if (r.replayed && r.state == CandidateState::kFailed && !observed_.count(&r)) {
        r.penalty = penalty;
      }
      if (r.finished() || !queued.insert(&r).second) continue;
      for (int k = 0; k < static_cast<int>(r.seeds.size()); ++k) {
        tasks.push_back({r.design, fidelity, r.seeds[static_cast<std::size_t>(k)]});
        slots.push_back({&r, k});
      }
    }
    optimizer::BatchCallbacks callbacks;
    callbacks.on_start = [&](std::size_t i) {
      book_->MarkRunning(*slots[i].record);
      ++result_.evaluator_calls;
    };
    callbacks.on_finish = [&](optimizer::TaskResult&& t) {
      const Slot& slot = slots.at(t.index);
      if (book_->AddReplicate(*slot.record, slot.replicate, std::move(t), penalty)) {
        ++result_.evaluated;
        progress_->Candidate(*slot.record, *book_, Status());
      }
    };
    callbacks.stop_requested = [&] { return OutOfTime(); };
    if (!tasks.empty()) scheduler_.Run(tasks, callbacks);
    for (CandidateRecord* r : records) {
      if (!r->finished()) stopped_ = true;
      Observe(*r);
    }
    return records;
  }

  void RunDoe() {
    if (!spec_.doe) return;
    const auto points = optimizer::GenerateDoe(*spec_.doe, static_cast<int>(spec_.space.size()));
    std::vector<optimizer::Design> designs;
    for (const auto& u : points) designs.push_back(spec_.space.ToDesign(u));
    progress_->Phase(fmt::format("design of experiments: {} points", designs.size()));
    EvaluateBatch(designs, 0, "doe");
  }

  void RunOptimiser() {
    if (!spec_.algorithm || stopped_) return;
    std::vector<double> start = spec_.space.StartPoint();
    const auto ranked = book_->Ranked(0);
    // Starting from the best sweep point: its unit coordinates need not map back to exactly the
    // same values, so the first call is given the stored design itself (no repeated evaluation).
    std::optional<optimizer::Design> start_design;
    if (!ranked.empty()) {
      start_design = ranked.front()->design;
      start = spec_.space.ToUnit(*start_design);
    }
    progress_->Phase(fmt::format("optimisation: {} from {}", spec_.algorithm->name,
                                 ranked.empty() ? "the start values" : "the best sweep point"));
    const std::size_t m = spec_.goals.NumConstraintValues();
    auto problem = [&](const std::vector<double>& u) -> optimizer::ProblemValues {
      if (OutOfTime()) {
        stopped_ = true;
        return {penalty_.Value(), std::vector<double>(m, 0.0)};
      }
      ++optimiser_calls_;
      const optimizer::Design design =
          start_design && u == start ? *start_design : spec_.space.ToDesign(u);
      CandidateRecord& r = *EvaluateBatch({design}, 0, "optimise").front();
      if (!r.finished()) return {penalty_.Value(), std::vector<double>(m, 0.0)};
      return Handed(r);
    };
    const optimizer::OptimiseResult r =
        optimizer::Minimise(*spec_.algorithm, spec_.stop, start, m, spec_.goals.constraint_weight(),
                            problem, [&] { return stopped_ || OutOfTime(); });
    result_.optimiser_status = r.status;
    if (OutOfTime()) stopped_ = true;
  }

  void RunConfirmations() {
    for (std::size_t level = 1; level < spec_.fidelities.size() && !stopped_; ++level) {
      const auto ranked = book_->Ranked(static_cast<int>(level) - 1);
      std::vector<optimizer::Design> designs;
      for (const CandidateRecord* r : ranked) {
        if (static_cast<int>(designs.size()) >= spec_.fidelities[level].top) break;
        designs.push_back(r->design);
      }
      if (designs.empty()) continue;
      progress_->Phase(fmt::format("confirmation at fidelity '{}': best {} of '{}'",
                                   spec_.fidelities[level].name, designs.size(),
                                   spec_.fidelities[level - 1].name));
      EvaluateBatch(designs, static_cast<int>(level), "confirm");
    }
  }

  CandidateSummary Summarise(const CandidateRecord& r) const {
    CandidateSummary s;
    s.id = r.id;
    s.eval_index = r.eval_index;
    s.fidelity = spec_.fidelities[static_cast<std::size_t>(r.level)].name;
    s.phase = r.phase;
    s.design = r.design;
    for (const auto& [name, m] : r.metrics) {
      s.metrics[name] = m.value;
      if (m.std_error) s.std_errors[name] = *m.std_error;
      s.units[name] = m.unit;
    }
    s.objective = r.goals.objective;
    s.feasible = r.goals.feasible;
    return s;
  }

  const CampaignSpec& spec_;
  db::ResultsDb& db_;
  optimizer::Scheduler& scheduler_;
  const RunnerOptions& options_;
  optimizer::FailurePenalty penalty_;
  Stopwatch clock_;  // since the run began
  bool native_constraints_ = false;
  bool stopped_ = false;
  int optimiser_calls_ = 0;
  std::set<const CandidateRecord*> observed_;
  std::unique_ptr<CandidateBook> book_;
  std::unique_ptr<Progress> progress_;
  CampaignResult result_;
};

}  // namespace

CampaignResult RunCampaign(const CampaignSpec& spec, db::ResultsDb& db,
                           optimizer::Scheduler& scheduler, const RunnerOptions& options) {
  return CampaignRun(spec, db, scheduler, options).Run();
}

CampaignResult RunCampaign(const CampaignSpec& spec, db::ResultsDb& db, const Evaluator& evaluator,
                           const RunnerOptions& options) {
  const auto scheduler = optimizer::MakeSerialScheduler(evaluator);
  return RunCampaign(spec, db, *scheduler, options);
}

}  // namespace fibrenet::campaigns
