#include "db/results_db.h"

#include <SQLiteCpp/Transaction.h>
#include <sqlite3.h>

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>

#include "db/schema.h"
#include "db/sqlite_util.h"

namespace fibrenet::db {
namespace {

using detail::kNowSql;

// How long the checkpoint at close waits for a reader to leave the WAL.
constexpr int kCloseCheckpointWaitMs = 100;

void require_finite(const std::string& path, double value, const std::string& what) {
  if (!std::isfinite(value)) {
    throw DbError(detail::message(path, what + " must be finite", "got " + std::to_string(value)));
  }
}

void require_non_negative(const std::string& path, double value, const std::string& what) {
  require_finite(path, value, what);
  if (value < 0.0) {
    throw DbError(detail::message(path, what + " must be >= 0", "got " + std::to_string(value)));
  }
}

void require_text(const std::string& path, const std::string& value, const std::string& what) {
  if (value.empty()) throw DbError(detail::message(path, what + " must not be empty", ""));
}

void validate_metrics(const std::string& path, std::int64_t id,
                      const std::vector<MetricValue>& metrics) {
  const std::string owner = "candidate " + std::to_string(id) + ": metric ";
  for (const MetricValue& m : metrics) {
    require_text(path, m.name, owner + "name");
    require_finite(path, m.value, owner + "'" + m.name + "' value");
    if (m.std_error) require_non_negative(path, *m.std_error, owner + "'" + m.name + "' std_error");
    if (m.n_replicates < 1) {
      throw DbError(detail::message(path, owner + "'" + m.name + "' n_replicates must be >= 1",
                                    "got " + std::to_string(m.n_replicates)));
    }
  }
}

// Called when an UPDATE guarded by a status condition changed nothing: says why.
[[noreturn]] void refuse_transition(SQLite::Database& db, const std::string& path, std::int64_t id,
                                    const char* target, const char* allowed) {
  SQLite::Statement q(db, "SELECT status FROM candidates WHERE id = ?");
  q.bind(1, id);
  if (!q.executeStep()) {
    throw DbError(detail::message(path, "no candidate with id " + std::to_string(id), ""));
  }
  throw DbError(detail::message(
      path, "cannot mark candidate " + std::to_string(id) + " " + target,
      "it is " + q.getColumn(0).getString() + "; only " + allowed + " candidates can be"));
}

void touch_campaign_of(SQLite::Database& db, std::int64_t candidate_id) {
  SQLite::Statement q(db, std::string("UPDATE campaigns SET updated_at = ") + kNowSql +
                              " WHERE id = (SELECT campaign_id FROM candidates WHERE id = ?)");
  q.bind(1, candidate_id);
  q.exec();
}

void insert_artifacts(SQLite::Database& db, std::int64_t candidate_id,
                      const std::vector<Artifact>& artifacts) {
  SQLite::Statement q(db, "INSERT INTO artifacts (candidate_id, kind, path) VALUES (?, ?, ?)");
  for (const Artifact& a : artifacts) {
    q.bind(1, candidate_id);
    q.bind(2, a.kind);
    q.bind(3, a.path);
    q.exec();
    q.reset();
  }
}

// JSON object text for a provenance column, or std::nullopt for null.
std::optional<std::string> provenance_text(const std::string& path,
                                           const nlohmann::json& provenance) {
  if (provenance.is_null()) return std::nullopt;
  if (!provenance.is_object()) {
    throw DbError(detail::message(path, "provenance must be a JSON object",
                                  "got " + std::string(provenance.type_name())));
  }
  return provenance.dump();
}

bool is_plain_file_path(const std::string& path) {
  return !path.empty() && path != ":memory:" && path.rfind("file:", 0) != 0;
}

// Why `path` cannot be opened in `mode`, or "" when it looks openable. SQLite itself says only
// "unable to open database file"; this names the part of the path that is wrong, and is asked
// before SQLite runs so that nothing is created next to a path that will be refused.
std::string path_problem(const std::string& path, OpenMode mode) {
  namespace fs = std::filesystem;
  if (!is_plain_file_path(path)) return "";
  std::error_code ec;
  const fs::path file(path);
  const fs::path folder = file.has_parent_path() ? file.parent_path() : fs::path(".");
  const bool writing = mode == OpenMode::kReadWrite;
  if (fs::is_directory(file, ec)) return "it is a folder; accepted: the path of a database file";
  // A name the system refuses outright (too long, a loop of links): say so in its words.
  if (ec && ec != std::errc::no_such_file_or_directory && ec != std::errc::not_a_directory) {
    return ec.message() + "; accepted: the path of a database file";
  }
  const std::string in_folder = "'" + folder.string() + "'";
  if (!fs::exists(folder, ec)) {
    return "folder " + in_folder + " does not exist; accepted: a file in an existing folder";
  }
  if (!fs::is_directory(folder, ec)) {
    return in_folder + " is not a folder; accepted: a file in an existing folder";
  }
  const bool exists = fs::exists(file, ec);
  if (!exists && !writing) {
    return "no such file; accepted: an existing results database (campaign run creates one)";
  }
  // A writer needs the folder too: SQLite keeps its WAL and shared-memory files next to the file.
  if (writing && ::access(folder.c_str(), W_OK | X_OK) != 0) {
    return "folder " + in_folder + " is not writable; accepted: a file in a writable folder";
  }
  if (exists && ::access(path.c_str(), writing ? R_OK | W_OK : R_OK) != 0) {
    return writing ? "the file is not writable; accepted: a file fibrenet may read and write"
                   : "the file is not readable; accepted: a file fibrenet may read";
  }
  return "";
}

void remove_sqlite_files(const std::string& path) {
  std::error_code ignored;
  for (const char* suffix : {"", "-wal", "-shm", "-journal"}) {
    std::filesystem::remove(path + suffix, ignored);
  }
}

// Creates a new results database at `path` whole: built under a private name, closed (which
// folds its WAL into the file), then linked into place. A reader never sees the file empty (no
// tables yet) or with its first transaction under way.
// link() refuses to replace: if another process created `path` meanwhile, theirs is kept.
void create_whole_file(const std::string& path) {
  const std::string draft = path + ".new-" + std::to_string(::getpid());
  remove_sqlite_files(draft);
  try {
    detail::guarded(path, "cannot create", [&] {
      SQLite::Database db(draft, SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE, kBusyTimeoutMs);
      prepare_for_writing(db, path);
      // Nobody else knows the draft: let SQLite checkpoint and delete its WAL at close.
      sqlite3_db_config(db.getHandle(), SQLITE_DBCONFIG_NO_CKPT_ON_CLOSE, 0, nullptr);
    });
    if (::link(draft.c_str(), path.c_str()) != 0 && errno != EEXIST) {
      throw DbError(detail::message(path, "cannot create", std::strerror(errno)));
    }
  } catch (...) {
    remove_sqlite_files(draft);
    throw;
  }
  remove_sqlite_files(draft);
}

}  // namespace

ResultsDb::ResultsDb(const std::string& path, OpenMode mode) : path_(path), mode_(mode) {
  if (const std::string problem = path_problem(path_, mode); !problem.empty()) {
    throw DbError(detail::message(path_, "cannot open", problem));
  }
  std::error_code ec;
  if (mode == OpenMode::kReadWrite && is_plain_file_path(path_) &&
      !std::filesystem::exists(path_, ec)) {
    create_whole_file(path_);
  }
  const int flags = mode == OpenMode::kReadOnly ? SQLite::OPEN_READONLY
                                                : SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE;
  db_ = detail::guarded(path_, "cannot open", [&] {
    return std::make_unique<SQLite::Database>(path_, flags, kBusyTimeoutMs);
  });
  if (mode == OpenMode::kReadOnly) {
    check_for_reading(*db_, path_);
  } else {
    prepare_for_writing(*db_, path_);
  }
}

ResultsDb::~ResultsDb() { checkpoint_before_close(); }
ResultsDb::ResultsDb(ResultsDb&&) noexcept = default;

ResultsDb& ResultsDb::operator=(ResultsDb&& other) noexcept {
  if (this != &other) {
    checkpoint_before_close();
    path_ = std::move(other.path_);
    mode_ = other.mode_;
    db_ = std::move(other.db_);
  }
  return *this;
}

void ResultsDb::checkpoint_before_close() noexcept {
  if (!db_ || mode_ != OpenMode::kReadWrite) return;
  // Copy everything into the main file so that the .db alone is complete. The close that
  // follows skips SQLite's own checkpoint (prepare_for_writing), whose exclusive lock made a
  // reader opening in that instant fail with "database is locked". Waiting here is short:
  // if another connection holds the write lock or a reader is still on the WAL, this copies
  // what it can without blocking anyone, and the WAL keeps the rest for the next open.
  sqlite3_busy_timeout(db_->getHandle(), kCloseCheckpointWaitMs);
  try {
    db_->exec("PRAGMA wal_checkpoint(TRUNCATE)");
  } catch (const std::exception&) {
    // Out of disk or I/O error: the WAL still holds the data; the next open recovers it.
  }
}

int ResultsDb::schema_version() const {
  return detail::guarded(path_, "reading the schema version",
                         [&] { return stored_schema_version(*db_); });
}

std::int64_t ResultsDb::upsert_campaign(const std::string& name, const std::string& spec_text,
                                        const std::string& spec_hash,
                                        const std::string& software_version,
                                        const std::string& git_commit) {
  require_text(path_, name, "campaign name");
  return detail::guarded(path_, "storing campaign '" + name + "'", [&] {
    SQLite::Transaction tx(*db_, SQLite::TransactionBehavior::IMMEDIATE);
    SQLite::Statement up(
        *db_, std::string("INSERT INTO campaigns (name, spec_text, spec_hash, software_version, "
                          "git_commit, created_at, updated_at) VALUES (?, ?, ?, ?, ?, ") +
                  kNowSql + ", " + kNowSql +
                  ") ON CONFLICT (name) DO UPDATE SET spec_text = excluded.spec_text, "
                  "spec_hash = excluded.spec_hash, software_version = excluded.software_version, "
                  "git_commit = excluded.git_commit, updated_at = excluded.updated_at");
    up.bind(1, name);
    up.bind(2, spec_text);
    up.bind(3, spec_hash);
    up.bind(4, software_version);
    up.bind(5, git_commit);
    up.exec();
    SQLite::Statement id(*db_, "SELECT id FROM campaigns WHERE name = ?");
    id.bind(1, name);
    id.executeStep();
    const std::int64_t campaign_id = id.getColumn(0).getInt64();
    id.reset();
    tx.commit();
    return campaign_id;
  });
}

void ResultsDb::set_campaign_status(std::int64_t campaign_id, const std::string& status) {
  require_text(path_, status, "campaign status");
  detail::guarded(path_, "setting the status of campaign " + std::to_string(campaign_id), [&] {
    SQLite::Transaction tx(*db_, SQLite::TransactionBehavior::IMMEDIATE);
    SQLite::Statement q(*db_, std::string("UPDATE campaigns SET status = ?, updated_at = ") +
                                  kNowSql + " WHERE id = ?");
    q.bind(1, status);
    q.bind(2, campaign_id);
    if (q.exec() != 1) {
      throw DbError(
          detail::message(path_, "no campaign with id " + std::to_string(campaign_id), ""));
    }
    tx.commit();
  });
}

std::int64_t ResultsDb::insert_candidate(std::int64_t campaign_id, std::int64_t eval_index,
                                         const std::string& key, const std::string& fidelity,
                                         const std::vector<std::uint64_t>& seeds,
                                         const std::map<std::string, double>& parameters,
                                         const nlohmann::json& provenance) {
  require_text(path_, key, "candidate key");
  if (eval_index < 0) {
    throw DbError(
        detail::message(path_, "eval_index must be >= 0", "got " + std::to_string(eval_index)));
  }
  for (const auto& [name, value] : parameters) {
    require_text(path_, name, "parameter name");
    require_finite(path_, value, "parameter '" + name + "'");
  }
  const std::optional<std::string> prov = provenance_text(path_, provenance);
  const std::string what =
      "storing candidate '" + key + "' of campaign " + std::to_string(campaign_id);
  return detail::guarded(path_, what, [&] {
    SQLite::Transaction tx(*db_, SQLite::TransactionBehavior::IMMEDIATE);
    SQLite::Statement owner(*db_, "SELECT 1 FROM campaigns WHERE id = ?");
    owner.bind(1, campaign_id);
    if (!owner.executeStep()) {
      throw DbError(detail::message(path_, what, "there is no campaign with that id"));
    }
    owner.reset();
    SQLite::Statement dup(*db_, "SELECT id FROM candidates WHERE campaign_id = ? AND key = ?");
    dup.bind(1, campaign_id);
    dup.bind(2, key);
    if (dup.executeStep()) {
      throw DbError(
          detail::message(path_, what,
                          "the key is already stored as candidate " + dup.getColumn(0).getString() +
                              "; resume it (find_candidate_by_key) instead of inserting it again"));
    }
    SQLite::Statement ins(*db_, std::string("INSERT INTO candidates (campaign_id, eval_index, "
                                            "key, fidelity, seeds, provenance, created_at) "
                                            "VALUES (?, ?, ?, ?, ?, ?, ") +
                                    kNowSql + ")");
    ins.bind(1, campaign_id);
    ins.bind(2, eval_index);
    ins.bind(3, key);
    ins.bind(4, fidelity);
    ins.bind(5, nlohmann::json(seeds).dump());
    if (prov) {
      ins.bind(6, *prov);
    } else {
      ins.bind(6);
    }
    ins.exec();
    const std::int64_t id = db_->getLastInsertRowid();
    SQLite::Statement par(*db_,
                          "INSERT INTO parameters (candidate_id, name, value) VALUES (?, ?, ?)");
    for (const auto& [name, value] : parameters) {
      par.bind(1, id);
      par.bind(2, name);
      par.bind(3, value);
      par.exec();
      par.reset();
    }
    touch_campaign_of(*db_, id);
    tx.commit();
    return id;
  });
}

void ResultsDb::mark_running(std::int64_t candidate_id) {
  detail::guarded(path_, "marking candidate " + std::to_string(candidate_id) + " running", [&] {
    SQLite::Transaction tx(*db_, SQLite::TransactionBehavior::IMMEDIATE);
    SQLite::Statement q(*db_, std::string("UPDATE candidates SET status = 'running', "
                                          "started_at = ") +
                                  kNowSql +
                                  ", ended_at = NULL, wall_s = NULL, reason = NULL "
                                  "WHERE id = ? AND status IN ('pending', 'running')");
    q.bind(1, candidate_id);
    if (q.exec() != 1)
      refuse_transition(*db_, path_, candidate_id, "running", "pending or running");
    touch_campaign_of(*db_, candidate_id);
    tx.commit();
  });
}

void ResultsDb::mark_done(std::int64_t candidate_id, const std::vector<MetricValue>& metrics,
                          double objective, bool feasible, double wall_s,
                          const std::vector<Artifact>& artifacts,
                          const nlohmann::json& provenance) {
  const std::string id_text = std::to_string(candidate_id);
  validate_metrics(path_, candidate_id, metrics);
  require_finite(path_, objective, "candidate " + id_text + ": objective");
  require_non_negative(path_, wall_s, "candidate " + id_text + ": wall_s");
  const std::optional<std::string> prov = provenance_text(path_, provenance);
  detail::guarded(path_, "recording the results of candidate " + id_text, [&] {
    SQLite::Transaction tx(*db_, SQLite::TransactionBehavior::IMMEDIATE);
    SQLite::Statement q(
        *db_, std::string("UPDATE candidates SET status = 'done', reason = NULL, ended_at = ") +
                  kNowSql +
                  ", wall_s = ?, objective = ?, feasible = ?, provenance = CASE WHEN ? IS NULL "
                  "THEN provenance ELSE json_patch(coalesce(provenance, '{}'), ?) END "
                  "WHERE id = ? AND status = 'running'");
    q.bind(1, wall_s);
    q.bind(2, objective);
    q.bind(3, feasible ? 1 : 0);
    if (prov) {
      q.bind(4, *prov);
      q.bind(5, *prov);
    } else {
      q.bind(4);
      q.bind(5);
    }
    q.bind(6, candidate_id);
    if (q.exec() != 1) refuse_transition(*db_, path_, candidate_id, "done", "running");
    SQLite::Statement met(*db_,
                          "INSERT INTO metrics (candidate_id, name, value, unit, std_error, "
                          "n_replicates) VALUES (?, ?, ?, ?, ?, ?)");
    for (const MetricValue& m : metrics) {
      met.bind(1, candidate_id);
      met.bind(2, m.name);
      met.bind(3, m.value);
      met.bind(4, m.unit);
      if (m.std_error) {
        met.bind(5, *m.std_error);
      } else {
        met.bind(5);
      }
      met.bind(6, m.n_replicates);
      met.exec();
      met.reset();
    }
    insert_artifacts(*db_, candidate_id, artifacts);
    touch_campaign_of(*db_, candidate_id);
    tx.commit();
  });
}

void ResultsDb::mark_failed(std::int64_t candidate_id, const std::string& reason, double wall_s,
                            const std::vector<Artifact>& artifacts) {
  const std::string id_text = std::to_string(candidate_id);
  require_text(path_, reason, "candidate " + id_text + ": failure reason");
  require_non_negative(path_, wall_s, "candidate " + id_text + ": wall_s");
  detail::guarded(path_, "recording the failure of candidate " + id_text, [&] {
    SQLite::Transaction tx(*db_, SQLite::TransactionBehavior::IMMEDIATE);
    SQLite::Statement q(*db_, std::string("UPDATE candidates SET status = 'failed', reason = ?, "
                                          "ended_at = ") +
                                  kNowSql +
                                  ", wall_s = ?, objective = NULL, feasible = NULL "
                                  "WHERE id = ? AND status IN ('pending', 'running')");
    q.bind(1, reason);
    q.bind(2, wall_s);
    q.bind(3, candidate_id);
    if (q.exec() != 1) refuse_transition(*db_, path_, candidate_id, "failed", "pending or running");
    insert_artifacts(*db_, candidate_id, artifacts);
    touch_campaign_of(*db_, candidate_id);
    tx.commit();
  });
}

}  // namespace fibrenet::db
