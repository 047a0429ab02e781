// Plain rows handed out by the results database: no SQL, no handles, copyable values.
// Units: parameter and metric values are SI, as named by the scene key or the metric's `unit`;
// times are seconds; timestamps are ISO 8601 UTC text ("2024-05-01T12:00:00.000Z").
#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fibrenet::db {

// Life of a candidate: stored kPending before it runs, kRunning while it runs, then kDone with
// metrics or kFailed with a reason.
enum class CandidateStatus { kPending, kRunning, kDone, kFailed };

// The text stored in candidates.status: "pending", "running", "done" or "failed".
std::string_view to_string(CandidateStatus status);

// Inverse of to_string; std::nullopt for any other text.
std::optional<CandidateStatus> parse_candidate_status(std::string_view text);

// One measured quantity of a candidate, already reduced over its replicates.
struct MetricValue {
  std::string name;                 // e.g. "tensile_strength_md"
  double value = 0.0;               // mean over replicates, in `unit`; must be finite
  std::string unit;                 // SI unit text, e.g. "N/m"; "1" for dimensionless
  std::optional<double> std_error;  // standard error of the mean, in `unit`; empty if unknown
  int n_replicates = 1;             // replicates behind `value`, >= 1
};

// A file written by a candidate, e.g. {"snapshot", "runs/c12/pressed.h5"}.
struct Artifact {
  std::string kind;
  std::string path;
};

// Candidates of one campaign by status.
struct StatusCounts {
  int pending = 0;
  int running = 0;
  int done = 0;
  int failed = 0;
  int total() const { return pending + running + done + failed; }
};

struct CampaignRow {
  std::int64_t id = 0;
  std::string name;
  std::string spec_text;  // the campaign file as given
  std::string spec_hash;
  std::string status;  // free text set by the campaign driver; "created" on insert
  std::string software_version;
  std::string git_commit;
  std::string created_at;
  std::string updated_at;  // last change to the campaign or any of its candidates
  StatusCounts counts;
};

struct CandidateRow {
  std::int64_t id = 0;
  std::int64_t campaign_id = 0;
  std::string campaign;  // campaign name
  std::int64_t eval_index = 0;
  std::string key;  // hash of parameters + fidelity + seeds, unique per campaign
  std::string fidelity;
  std::vector<std::uint64_t> seeds;  // one per replicate
  CandidateStatus status = CandidateStatus::kPending;
  std::string reason;      // why it failed; empty otherwise
  std::string created_at;  // timestamps are empty while unset
  std::string started_at;
  std::string ended_at;
  std::optional<double> wall_s;     // wall time of the evaluation [s]
  std::optional<double> objective;  // set when done
  std::optional<bool> feasible;     // set when done
  std::map<std::string, double> parameters;
  std::vector<MetricValue> metrics;  // sorted by name
  std::vector<Artifact> artifacts;
  nlohmann::json provenance;  // JSON object, or null when nothing was recorded

  // The metric called `name`, or nullptr.
  const MetricValue* metric(std::string_view name) const;
};

}  // namespace fibrenet::db
