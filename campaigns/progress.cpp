#include "campaigns/progress.h"

#include <fmt/format.h>

#include <cmath>

namespace fibrenet::campaigns {

std::string FormatDuration(double seconds) {
  if (seconds < 60.0) return fmt::format("{:.1f}s", seconds);
  const auto total = static_cast<long long>(std::llround(seconds));
  if (total < 3600) return fmt::format("{}m{:02}s", total / 60, total % 60);
  return fmt::format("{}h{:02}m", total / 3600, (total % 3600) / 60);
}

Progress::Progress(std::ostream* out, const CampaignSpec& spec, const std::string& scheduler)
    : out_(out), spec_(spec) {
  if (!out_) return;
  std::string levels;
  for (const optimizer::Fidelity& f : spec.fidelities) {
    levels += fmt::format("{}{} ({} replicate{})", levels.empty() ? "" : " > ", f.name,
                          f.replicates, f.replicates == 1 ? "" : "s");
  }
  *out_ << fmt::format("campaign '{}': {} variable{}, fidelity {}, evaluating: {}\n", spec.name,
                       spec.space.size(), spec.space.size() == 1 ? "" : "s", levels, scheduler)
        << std::flush;
}

void Progress::Phase(const std::string& text) {
  if (out_) *out_ << "== " << text << "\n" << std::flush;
}

void Progress::Candidate(const CandidateRecord& r, const CandidateBook& book,
                         const ProgressStatus& status) {
  if (!out_) return;
  std::string line = fmt::format("[#{} {} {}{}]", r.eval_index, r.phase,
                                 spec_.fidelities[static_cast<std::size_t>(r.level)].name,
                                 r.replayed ? ", replayed" : "");
  for (const auto& [key, value] : r.design) line += fmt::format(" {}={:.5g}", key, value);
  if (r.state == CandidateState::kFailed) {
    line += fmt::format(" -> FAILED ({}), penalty {:.4g}", r.reason, r.penalty);
  } else {
    line += " ->";
    for (const std::string& name : spec_.goals.Metrics()) {
      const auto it = r.metrics.find(name);
      if (it == r.metrics.end()) continue;
      line += fmt::format(" {}={:.5g}", name, it->second.value);
      if (it->second.std_error) line += fmt::format("+-{:.2g}", *it->second.std_error);
    }
    line += fmt::format(" | objective {:.6g} {}", r.goals.objective,
                        r.goals.feasible ? "feasible" : "infeasible");
  }
  const auto ranked = book.Ranked(r.level);
  if (!ranked.empty() && ranked.front()->goals.feasible) {
    line += fmt::format(" | best feasible {:.6g} (#{})", ranked.front()->goals.objective,
                        ranked.front()->eval_index);
  } else {
    line += " | no feasible candidate yet";
  }
  if (status.max_evaluations > 0 && r.phase == "optimise") {
    line += fmt::format(" | eval {}/{}", status.optimiser_calls, status.max_evaluations);
  }
  line += status.max_wall_s > 0.0
              ? fmt::format(", {} left",
                            FormatDuration(std::max(0.0, status.max_wall_s - status.elapsed_s)))
              : fmt::format(", {} elapsed", FormatDuration(status.elapsed_s));
  *out_ << line << "\n" << std::flush;
}

void Progress::Finished(const CampaignResult& result) {
  if (!out_) return;
  *out_ << fmt::format(
      "campaign '{}' {}: {} candidates ({} evaluated, {} replayed from the "
      "database, {} failed) in {}\n",
      result.name, result.status, result.candidates, result.evaluated, result.replayed,
      result.failed, FormatDuration(result.wall_s));
  if (result.best) {
    std::string line =
        fmt::format("best: #{} at fidelity '{}':", result.best->eval_index, result.best->fidelity);
    for (const auto& [key, value] : result.best->design)
      line += fmt::format(" {}={:.6g}", key, value);
    line += fmt::format(" | objective {:.6g} {}", result.best->objective,
                        result.best->feasible ? "feasible"
                                              : "INFEASIBLE (no candidate met the "
                                                "constraints)");
    *out_ << line << "\n";
  } else {
    *out_ << "best: none (no candidate finished)\n";
  }
  *out_ << std::flush;
}

}  // namespace fibrenet::campaigns
