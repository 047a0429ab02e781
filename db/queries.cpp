#include "db/queries.h"

#include <SQLiteCpp/Transaction.h>

#include <functional>
#include <unordered_map>

#include "db/sqlite_util.h"

namespace fibrenet::db {
namespace {

using Binder = std::function<void(SQLite::Statement&)>;

constexpr const char* kCampaignSelect =
    "SELECT k.id, k.name, k.spec_text, k.spec_hash, k.status, k.software_version, "
    "k.git_commit, k.created_at, k.updated_at, p.n_pending, p.n_running, p.n_done, p.n_failed "
    "FROM campaigns k JOIN campaign_progress p ON p.campaign_id = k.id ";

constexpr const char* kCandidateSelect =
    "SELECT c.id, c.campaign_id, k.name, c.eval_index, c.key, c.fidelity, c.seeds, c.status, "
    "c.reason, c.created_at, c.started_at, c.ended_at, c.wall_s, c.objective, c.feasible, "
    "c.provenance FROM candidates c JOIN campaigns k ON k.id = c.campaign_id ";

std::optional<double> optional_real(const SQLite::Column& c) {
  if (c.isNull()) return std::nullopt;
  return c.getDouble();
}

CampaignRow read_campaign(const SQLite::Statement& q) {
  CampaignRow r;
  r.id = q.getColumn(0).getInt64();
  r.name = q.getColumn(1).getString();
  r.spec_text = q.getColumn(2).getString();
  r.spec_hash = q.getColumn(3).getString();
  r.status = q.getColumn(4).getString();
  r.software_version = q.getColumn(5).getString();
  r.git_commit = q.getColumn(6).getString();
  r.created_at = q.getColumn(7).getString();
  r.updated_at = q.getColumn(8).getString();
  r.counts.pending = q.getColumn(9).getInt();
  r.counts.running = q.getColumn(10).getInt();
  r.counts.done = q.getColumn(11).getInt();
  r.counts.failed = q.getColumn(12).getInt();
  return r;
}

CandidateRow read_candidate(const SQLite::Statement& q) {
  CandidateRow r;
  r.id = q.getColumn(0).getInt64();
  r.campaign_id = q.getColumn(1).getInt64();
  r.campaign = q.getColumn(2).getString();
  r.eval_index = q.getColumn(3).getInt64();
  r.key = q.getColumn(4).getString();
  r.fidelity = q.getColumn(5).getString();
  r.seeds = nlohmann::json::parse(q.getColumn(6).getString()).get<std::vector<std::uint64_t>>();
  // The CHECK constraint admits only the four statuses.
  r.status = parse_candidate_status(q.getColumn(7).getString()).value_or(CandidateStatus::kFailed);
  r.reason = detail::text_or_empty(q.getColumn(8));
  r.created_at = detail::text_or_empty(q.getColumn(9));
  r.started_at = detail::text_or_empty(q.getColumn(10));
  r.ended_at = detail::text_or_empty(q.getColumn(11));
  r.wall_s = optional_real(q.getColumn(12));
  r.objective = optional_real(q.getColumn(13));
  if (!q.getColumn(14).isNull()) r.feasible = q.getColumn(14).getInt() != 0;
  if (!q.getColumn(15).isNull()) r.provenance = nlohmann::json::parse(q.getColumn(15).getString());
  return r;
}

// Runs kCandidateSelect + `tail` (constant SQL; values bound by `bind`), then fills in the
// parameters, metrics and artifacts of the rows found, keeping the order of `tail`.
std::vector<CandidateRow> load_candidates(SQLite::Database& db, const std::string& tail,
                                          const Binder& bind) {
  std::vector<CandidateRow> rows;
  SQLite::Statement q(db, kCandidateSelect + tail);
  bind(q);
  while (q.executeStep()) rows.push_back(read_candidate(q));
  if (rows.empty()) return rows;

  std::unordered_map<std::int64_t, CandidateRow*> by_id;
  nlohmann::json ids = nlohmann::json::array();
  for (CandidateRow& r : rows) {
    by_id[r.id] = &r;
    ids.push_back(r.id);
  }
  const std::string id_list = ids.dump();
  constexpr const char* kInIds = " WHERE candidate_id IN (SELECT value FROM json_each(?))";

  SQLite::Statement par(db,
                        std::string("SELECT candidate_id, name, value FROM parameters") + kInIds);
  par.bind(1, id_list);
  while (par.executeStep()) {
    by_id.at(par.getColumn(0).getInt64())->parameters[par.getColumn(1).getString()] =
        par.getColumn(2).getDouble();
  }

  SQLite::Statement met(db, std::string("SELECT candidate_id, name, value, unit, std_error, "
                                        "n_replicates FROM metrics") +
                                kInIds + " ORDER BY candidate_id, name");
  met.bind(1, id_list);
  while (met.executeStep()) {
    MetricValue m;
    m.name = met.getColumn(1).getString();
    m.value = met.getColumn(2).getDouble();
    m.unit = met.getColumn(3).getString();
    m.std_error = optional_real(met.getColumn(4));
    m.n_replicates = met.getColumn(5).getInt();
    by_id.at(met.getColumn(0).getInt64())->metrics.push_back(std::move(m));
  }

  SQLite::Statement art(
      db, std::string("SELECT candidate_id, kind, path FROM artifacts") + kInIds + " ORDER BY id");
  art.bind(1, id_list);
  while (art.executeStep()) {
    by_id.at(art.getColumn(0).getInt64())
        ->artifacts.push_back({art.getColumn(1).getString(), art.getColumn(2).getString()});
  }
  return rows;
}

std::int64_t campaign_id_of(SQLite::Database& db, const std::string& path,
                            const std::string& name) {
  SQLite::Statement q(db, "SELECT id FROM campaigns WHERE name = ?");
  q.bind(1, name);
  if (!q.executeStep()) {
    throw DbError(detail::message(path, "no campaign named '" + name + "'", ""));
  }
  return q.getColumn(0).getInt64();
}

// Runs `body` inside one read transaction, so all its statements see the same snapshot even
// while another connection commits. Nothing is written, so the transaction just ends.
template <class Body>
auto in_snapshot(const ResultsDb& db, const std::string& what, Body&& body) {
  return detail::guarded(db.path(), what, [&] {
    SQLite::Transaction snapshot(db.connection(), SQLite::TransactionBehavior::DEFERRED);
    try {
      auto result = body(db.connection());
      snapshot.commit();
      return result;
    } catch (const nlohmann::json::exception& e) {
      // Only if someone edited the JSON columns by hand: the CHECK constraints keep them valid.
      throw DbError(detail::message(db.path(), what, std::string("malformed JSON: ") + e.what()));
    }
  });
}

}  // namespace

std::vector<CampaignRow> list_campaigns(const ResultsDb& db) {
  return in_snapshot(db, "listing campaigns", [&](SQLite::Database& conn) {
    std::vector<CampaignRow> rows;
    SQLite::Statement q(conn, std::string(kCampaignSelect) + "ORDER BY k.id");
    while (q.executeStep()) rows.push_back(read_campaign(q));
    return rows;
  });
}

std::optional<CampaignRow> find_campaign(const ResultsDb& db, const std::string& name) {
  return in_snapshot(db, "reading campaign '" + name + "'", [&](SQLite::Database& conn) {
    std::optional<CampaignRow> row;
    SQLite::Statement q(conn, std::string(kCampaignSelect) + "WHERE k.name = ?");
    q.bind(1, name);
    if (q.executeStep()) row = read_campaign(q);
    return row;
  });
}

std::vector<CandidateRow> candidates(const ResultsDb& db, const std::string& campaign) {
  return in_snapshot(
      db, "reading the candidates of campaign '" + campaign + "'", [&](SQLite::Database& conn) {
        const std::int64_t id = campaign_id_of(conn, db.path(), campaign);
        return load_candidates(conn, "WHERE c.campaign_id = ? ORDER BY c.eval_index, c.id",
                               [&](SQLite::Statement& q) { q.bind(1, id); });
      });
}

std::optional<CandidateRow> candidate(const ResultsDb& db, std::int64_t candidate_id) {
  return in_snapshot(
      db, "reading candidate " + std::to_string(candidate_id), [&](SQLite::Database& conn) {
        std::vector<CandidateRow> rows = load_candidates(
            conn, "WHERE c.id = ?", [&](SQLite::Statement& q) { q.bind(1, candidate_id); });
        return rows.empty() ? std::nullopt : std::optional<CandidateRow>(std::move(rows[0]));
      });
}

std::optional<CandidateRow> find_candidate_by_key(const ResultsDb& db, std::int64_t campaign_id,
                                                  const std::string& key) {
  return in_snapshot(db, "looking up candidate key '" + key + "'", [&](SQLite::Database& conn) {
    std::vector<CandidateRow> rows =
        load_candidates(conn, "WHERE c.campaign_id = ? AND c.key = ?", [&](SQLite::Statement& q) {
          q.bind(1, campaign_id);
          q.bind(2, key);
        });
    return rows.empty() ? std::nullopt : std::optional<CandidateRow>(std::move(rows[0]));
  });
}

std::vector<CandidateRow> best(const ResultsDb& db, const std::string& campaign, int n) {
  return in_snapshot(
      db, "ranking the candidates of campaign '" + campaign + "'", [&](SQLite::Database& conn) {
        const std::int64_t id = campaign_id_of(conn, db.path(), campaign);
        return load_candidates(conn,
                               "WHERE c.campaign_id = ? AND c.status = 'done' "
                               "ORDER BY c.feasible DESC, c.objective ASC, c.eval_index, c.id "
                               "LIMIT ?",
                               [&](SQLite::Statement& q) {
                                 q.bind(1, id);
                                 q.bind(2, n);
                               });
      });
}

}  // namespace fibrenet::db
