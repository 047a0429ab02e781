// The results database of fibrenet: one SQLite file holding campaigns and every candidate they
// evaluate. This header opens it and writes to it; db/queries.h reads it, db/export.h exports.
//
// Every candidate is stored (pending) before it runs and updated when it ends, each write in
// one transaction, so a campaign killed at any moment resumes from what the file holds. Values
// are always bound, never spliced into SQL.
//
// Concurrency: one ResultsDb is used by one thread. The file has one writer at a time (the
// campaign driver, MPI rank 0); any number of readers (fibrenet db, the sqlite3 shell, Python)
// may read it while the writer works, thanks to WAL mode.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "db/error.h"
#include "db/types.h"

namespace SQLite {
class Database;
}

namespace fibrenet::db {

enum class OpenMode {
  kReadWrite,  // create the file if missing and migrate it to the current schema
  kReadOnly,   // the file must exist at the current schema version; nothing is ever written
};

class ResultsDb {
 public:
  // Opens the database at `path` (":memory:" for a private in-memory database). In kReadWrite
  // mode a missing file is created and an older schema migrated.
  // Throws DbError naming `path` if it cannot be opened, is not an SQLite file, belongs to
  // another application, or has a schema version this build does not know.
  explicit ResultsDb(const std::string& path, OpenMode mode = OpenMode::kReadWrite);
  ~ResultsDb();
  ResultsDb(ResultsDb&&) noexcept;
  ResultsDb& operator=(ResultsDb&&) noexcept;
  ResultsDb(const ResultsDb&) = delete;
  ResultsDb& operator=(const ResultsDb&) = delete;

  const std::string& path() const { return path_; }
  OpenMode mode() const { return mode_; }
  int schema_version() const;

  // Inserts the campaign called `name` with status "created", or, if it exists, replaces its
  // spec, hash, software version and commit (status, candidates and created_at are kept).
  // Returns its id. Whether a changed spec may resume old candidates is the caller's call:
  // compare find_campaign(db, name)->spec_hash first.
  std::int64_t upsert_campaign(const std::string& name, const std::string& spec_text,
                               const std::string& spec_hash, const std::string& software_version,
                               const std::string& git_commit);

  // Free text, e.g. "running", "done", "stopped"; must not be empty.
  void set_campaign_status(std::int64_t campaign_id, const std::string& status);

  // Stores a candidate before it runs, with status pending, and returns its id. `key` (a hash of
  // parameters, fidelity and seeds) must be new in this campaign: look it up first with
  // find_candidate_by_key to resume. Parameter values must be finite (SI units).
  // `provenance` is an optional JSON object (e.g. {"phase": "doe"}).
  std::int64_t insert_candidate(std::int64_t campaign_id, std::int64_t eval_index,
                                const std::string& key, const std::string& fidelity,
                                const std::vector<std::uint64_t>& seeds,
                                const std::map<std::string, double>& parameters,
                                const nlohmann::json& provenance = nullptr);

  // pending -> running (also running -> running, to restart a candidate after a crash).
  // Sets started_at to now and clears any end time.
  void mark_running(std::int64_t candidate_id);

  // running -> done, with its metrics, objective (finite; lower is better), feasibility, wall
  // time [s] and artifact paths, all in one transaction: if any row is refused (e.g. two
  // metrics with one name) nothing is written and DbError is thrown. A non-null `provenance`
  // object is merged into the stored one (JSON merge patch).
  void mark_done(std::int64_t candidate_id, const std::vector<MetricValue>& metrics,
                 double objective, bool feasible, double wall_s,
                 const std::vector<Artifact>& artifacts = {},
                 const nlohmann::json& provenance = nullptr);

  // pending or running -> failed, with a non-empty reason (e.g. "unstable: kinetic energy
  // diverged at t = 1.2e-3 s") and the wall time spent [s].
  void mark_failed(std::int64_t candidate_id, const std::string& reason, double wall_s,
                   const std::vector<Artifact>& artifacts = {});

  // For db/ internals (queries, export) only: the open connection. Outside db/ the type is
  // incomplete, which keeps SQL inside db/.
  SQLite::Database& connection() const { return *db_; }

 private:
  // Moves the WAL's content into the database file before the connection closes.
  void checkpoint_before_close() noexcept;

  std::string path_;
  OpenMode mode_ = OpenMode::kReadWrite;
  std::unique_ptr<SQLite::Database> db_;
};

}  // namespace fibrenet::db
