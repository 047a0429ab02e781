// Exports of one campaign for tools outside fibrenet: JSON (everything, nested) and CSV (one
// row per candidate, one column per parameter and per metric, for spreadsheets and pandas).
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "db/results_db.h"
#include "db/types.h"

namespace fibrenet::db {

// JSON forms of the rows, also used by `fibrenet db ... --json`. Metrics become an object
// {name: {value, unit, std_error, n_replicates}}; unset optionals become null.
void to_json(nlohmann::json& j, const MetricValue& m);
void to_json(nlohmann::json& j, const Artifact& a);
void to_json(nlohmann::json& j, const CampaignRow& c);
void to_json(nlohmann::json& j, const CandidateRow& c);

// {"schema_version": N, "campaign": {...}, "candidates": [...]} with candidates ordered by
// eval_index. Throws DbError if there is no such campaign.
nlohmann::json export_json(const ResultsDb& db, const std::string& campaign);

// Writes a header and one row per candidate (ordered by eval_index): candidate_id, eval_index,
// status, fidelity, objective, feasible (1/0), wall_s, reason, then "param.<name>" for every
// parameter and "metric.<name>" for every metric seen in the campaign (sorted by name). Missing
// values are empty fields; numbers round-trip exactly; fields are quoted as RFC 4180 asks
// (lines end in "\n").
// Throws DbError if there is no such campaign.
void export_csv(const ResultsDb& db, const std::string& campaign, std::ostream& out);

}  // namespace fibrenet::db
