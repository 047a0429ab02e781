// Progress lines of a running campaign (stderr in the CLI): one per phase and one per finished
// candidate with its parameters, goal metrics, objective, the best feasible candidate so far,
// and the budget left. Internal to campaigns/.
#pragma once

#include <ostream>
#include <string>

#include "campaigns/campaign_file.h"
#include "campaigns/campaign_runner.h"
#include "campaigns/candidate_book.h"

namespace fibrenet::campaigns {

struct ProgressStatus {
  double elapsed_s = 0.0;
  double max_wall_s = 0.0;  // 0: unlimited
  int optimiser_calls = 0;
  int max_evaluations = 0;  // 0: no optimiser
};

class Progress {
 public:
  // Writes nothing when `out` is null.
  Progress(std::ostream* out, const CampaignSpec& spec, const std::string& scheduler);

  void Phase(const std::string& text);
  void Candidate(const CandidateRecord& record, const CandidateBook& book,
                 const ProgressStatus& status);
  void Finished(const CampaignResult& result);

 private:
  std::ostream* out_;
  const CampaignSpec& spec_;
};

// "1h02m", "4m10s", "12.3s".
std::string FormatDuration(double seconds);

}  // namespace fibrenet::campaigns
