#include "db/types.h"

#include <algorithm>

namespace fibrenet::db {

std::string_view to_string(CandidateStatus status) {
  switch (status) {
    case CandidateStatus::kPending:
      return "pending";
    case CandidateStatus::kRunning:
      return "running";
    case CandidateStatus::kDone:
      return "done";
    case CandidateStatus::kFailed:
      return "failed";
  }
  return "unknown";
}

std::optional<CandidateStatus> parse_candidate_status(std::string_view text) {
  for (CandidateStatus s : {CandidateStatus::kPending, CandidateStatus::kRunning,
                            CandidateStatus::kDone, CandidateStatus::kFailed}) {
    if (to_string(s) == text) return s;
  }
  return std::nullopt;
}

const MetricValue* CandidateRow::metric(std::string_view name) const {
  auto it = std::find_if(metrics.begin(), metrics.end(),
                         [name](const MetricValue& m) { return m.name == name; });
  return it == metrics.end() ? nullptr : &*it;
}

}  // namespace fibrenet::db
