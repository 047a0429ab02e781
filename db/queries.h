// Reads of the results database: campaigns, candidates with their parameters and metrics, and
// the best candidates of a campaign. Each call reads one consistent snapshot, so it may run
// while another process writes the file.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "db/results_db.h"
#include "db/types.h"

namespace fibrenet::db {

// All campaigns, oldest first, with their candidate counts per status.
std::vector<CampaignRow> list_campaigns(const ResultsDb& db);

// The campaign called `name`, or std::nullopt.
std::optional<CampaignRow> find_campaign(const ResultsDb& db, const std::string& name);

// The candidates of campaign `campaign` (a name) ordered by eval_index, each with parameters,
// metrics and artifacts. Throws DbError if there is no such campaign.
std::vector<CandidateRow> candidates(const ResultsDb& db, const std::string& campaign);

// One candidate by id, or std::nullopt.
std::optional<CandidateRow> candidate(const ResultsDb& db, std::int64_t candidate_id);

// The candidate of `campaign_id` stored under `key`, or std::nullopt: how a resumed campaign
// finds work it already stored (and, if done, its results to replay).
std::optional<CandidateRow> find_candidate_by_key(const ResultsDb& db, std::int64_t campaign_id,
                                                  const std::string& key);

// Up to `n` finished (done) candidates of `campaign`: feasible ones first, then by lowest
// objective, then by eval_index. A negative `n` returns all of them. Throws DbError if there is
// no such campaign.
std::vector<CandidateRow> best(const ResultsDb& db, const std::string& campaign, int n);

}  // namespace fibrenet::db
