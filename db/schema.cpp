#include "db/schema.h"

#include <SQLiteCpp/Transaction.h>
#include <sqlite3.h>

#include <string>

#include "db/sqlite_util.h"

namespace fibrenet::db {
namespace {

struct Migration {
  int version;          // user_version after this migration
  const char* summary;  // one line, for the docs and for error messages
  const char* sql;
};

// Migrations in order. Never edit a released migration: append a new one that alters the
// schema, bump kSchemaVersion, and describe the change in docs/database.md.
constexpr Migration kMigrations[] = {
    {1, "initial schema: campaigns, candidates, parameters, metrics, artifacts, views",
     R"sql(
CREATE TABLE campaigns (
  id               INTEGER PRIMARY KEY,
  name             TEXT NOT NULL UNIQUE CHECK (name <> ''),
  spec_text        TEXT NOT NULL,
  spec_hash        TEXT NOT NULL,
  status           TEXT NOT NULL DEFAULT 'created' CHECK (status <> ''),
  software_version TEXT NOT NULL,
  git_commit       TEXT NOT NULL,
  created_at       TEXT NOT NULL,
  updated_at       TEXT NOT NULL
);

CREATE TABLE candidates (
  id          INTEGER PRIMARY KEY,
  campaign_id INTEGER NOT NULL REFERENCES campaigns(id) ON DELETE CASCADE,
  eval_index  INTEGER NOT NULL CHECK (eval_index >= 0),
  key         TEXT NOT NULL CHECK (key <> ''),
  fidelity    TEXT NOT NULL,
  seeds       TEXT NOT NULL DEFAULT '[]'
              CHECK (json_valid(seeds) AND json_type(seeds) = 'array'),
  status      TEXT NOT NULL DEFAULT 'pending'
              CHECK (status IN ('pending', 'running', 'done', 'failed')),
  reason      TEXT,
  created_at  TEXT NOT NULL,
  started_at  TEXT,
  ended_at    TEXT,
  wall_s      REAL CHECK (wall_s IS NULL OR wall_s >= 0),
  objective   REAL,
  feasible    INTEGER CHECK (feasible IS NULL OR feasible IN (0, 1)),
  provenance  TEXT CHECK (provenance IS NULL OR json_valid(provenance)),
  UNIQUE (campaign_id, key),
  CHECK (status <> 'failed' OR reason IS NOT NULL),
  CHECK (status <> 'done' OR (objective IS NOT NULL AND feasible IS NOT NULL))
);
CREATE INDEX candidates_by_eval ON candidates (campaign_id, eval_index);
CREATE INDEX candidates_by_status ON candidates (campaign_id, status);

CREATE TABLE parameters (
  candidate_id INTEGER NOT NULL REFERENCES candidates(id) ON DELETE CASCADE,
  name         TEXT NOT NULL CHECK (name <> ''),
  value        REAL NOT NULL,
  PRIMARY KEY (candidate_id, name)
) WITHOUT ROWID;

CREATE TABLE metrics (
  candidate_id INTEGER NOT NULL REFERENCES candidates(id) ON DELETE CASCADE,
  name         TEXT NOT NULL CHECK (name <> ''),
  value        REAL NOT NULL,
  unit         TEXT NOT NULL,
  std_error    REAL CHECK (std_error IS NULL OR std_error >= 0),
  n_replicates INTEGER NOT NULL DEFAULT 1 CHECK (n_replicates >= 1),
  PRIMARY KEY (candidate_id, name)
) WITHOUT ROWID;

CREATE TABLE artifacts (
  id           INTEGER PRIMARY KEY,
  candidate_id INTEGER NOT NULL REFERENCES candidates(id) ON DELETE CASCADE,
  kind         TEXT NOT NULL CHECK (kind <> ''),
  path         TEXT NOT NULL CHECK (path <> ''),
  UNIQUE (candidate_id, kind, path)
);

CREATE VIEW candidate_summary AS
SELECT c.id          AS candidate_id,
       k.name        AS campaign,
       c.eval_index  AS eval_index,
       c.status      AS status,
       c.reason      AS reason,
       c.fidelity    AS fidelity,
       c.objective   AS objective,
       c.feasible    AS feasible,
       c.wall_s      AS wall_s,
       c.started_at  AS started_at,
       c.ended_at    AS ended_at,
       (SELECT json_group_object(p.name, p.value)
          FROM parameters p WHERE p.candidate_id = c.id) AS parameters,
       (SELECT json_group_object(m.name, m.value)
          FROM metrics m WHERE m.candidate_id = c.id) AS metrics
  FROM candidates c JOIN campaigns k ON k.id = c.campaign_id;

CREATE VIEW campaign_progress AS
SELECT k.id   AS campaign_id,
       k.name AS campaign,
       k.status AS status,
       count(c.id) FILTER (WHERE c.status = 'pending') AS n_pending,
       count(c.id) FILTER (WHERE c.status = 'running') AS n_running,
       count(c.id) FILTER (WHERE c.status = 'done')    AS n_done,
       count(c.id) FILTER (WHERE c.status = 'failed')  AS n_failed,
       count(c.id) AS n_total,
       min(c.objective) FILTER (WHERE c.status = 'done' AND c.feasible = 1)
                    AS best_feasible_objective
  FROM campaigns k LEFT JOIN candidates c ON c.campaign_id = k.id
 GROUP BY k.id;
)sql"},
};

static_assert(sizeof(kMigrations) / sizeof(kMigrations[0]) == kSchemaVersion,
              "one migration per schema version, the last one reaching kSchemaVersion");

std::int64_t pragma_int(SQLite::Database& db, const char* pragma) {
  return db.execAndGet(std::string("PRAGMA ") + pragma).getInt64();
}

// Refuses files that are not SQLite, SQLite files of another application, and schemas newer
// than this build. Returns the stored schema version (0 for an empty file). Reads only.
int check_identity(SQLite::Database& db, const std::string& path) {
  std::int64_t n_objects = 0;
  try {
    // The first read of the header: fails with "file is not a database" for other files.
    n_objects = db.execAndGet("SELECT count(*) FROM sqlite_schema").getInt64();
  } catch (const SQLite::Exception& e) {
    throw DbError(detail::message(path, "not an SQLite database", e.what()));
  }
  const std::int64_t app_id = pragma_int(db, "application_id");
  const std::int64_t version = pragma_int(db, "user_version");
  const bool empty = n_objects == 0 && app_id == 0 && version == 0;
  if (empty) return 0;
  if (app_id != kApplicationId) {
    throw DbError(detail::message(path, "not a fibrenet results database",
                                  "it is an SQLite file of another application (application_id " +
                                      std::to_string(app_id) + ", schema objects " +
                                      std::to_string(n_objects) + ")"));
  }
  if (version < 1 || version > kSchemaVersion) {
    throw DbError(detail::message(
        path, "unknown schema version " + std::to_string(version),
        "this build of fibrenet reads schema versions 1 to " + std::to_string(kSchemaVersion) +
            "; open it with the fibrenet release that wrote it, or a newer one"));
  }
  return static_cast<int>(version);
}

void apply(SQLite::Database& db, const std::string& path, const Migration& m) {
  detail::guarded(path,
                  std::string("migrating to schema version ") + std::to_string(m.version) + " (" +
                      m.summary + ")",
                  [&] {
                    // IMMEDIATE takes the write lock first, so two processes opening the same
                    // new file cannot both migrate: the second waits, then sees the new version.
                    SQLite::Transaction tx(db, SQLite::TransactionBehavior::IMMEDIATE);
                    if (stored_schema_version(db) >= m.version) return;
                    db.exec(m.sql);
                    db.exec("PRAGMA application_id = " + std::to_string(kApplicationId));
                    db.exec("PRAGMA user_version = " + std::to_string(m.version));
                    tx.commit();
                  });
}

}  // namespace

int stored_schema_version(SQLite::Database& db) {
  return static_cast<int>(pragma_int(db, "user_version"));
}

void prepare_for_writing(SQLite::Database& db, const std::string& path) {
  const int version =
      detail::guarded(path, "reading the schema version", [&] { return check_identity(db, path); });
  detail::guarded(path, "configuring the connection", [&] {
    db.exec("PRAGMA foreign_keys = ON");
    // WAL lets any SQLite client read while a campaign writes. It is a property of the file,
    // so it is set only after the file was recognised as ours (or empty).
    const std::string mode = db.execAndGet("PRAGMA journal_mode = WAL").getString();
    if (mode != "wal" && mode != "memory") {
      throw DbError(
          detail::message(path, "cannot switch to WAL journal mode",
                          "SQLite kept '" + mode + "' (is it on a network file system?)"));
    }
    // SQLite's checkpoint at close takes an exclusive lock and deletes the WAL: a reader that
    // opens the file in that instant gets "database is locked" at once, whatever its busy
    // timeout. The writer checkpoints before it closes instead (ResultsDb), so the file ends
    // complete, with an empty -wal and the -shm file left beside it.
    sqlite3_db_config(db.getHandle(), SQLITE_DBCONFIG_NO_CKPT_ON_CLOSE, 1, nullptr);
  });
  for (const Migration& m : kMigrations) {
    if (m.version > version) apply(db, path, m);
  }
}

void check_for_reading(SQLite::Database& db, const std::string& path) {
  const int version =
      detail::guarded(path, "reading the schema version", [&] { return check_identity(db, path); });
  if (version == 0) {
    throw DbError(detail::message(path, "not a fibrenet results database", "the file is empty"));
  }
  if (version < kSchemaVersion) {
    throw DbError(detail::message(path,
                                  "schema version " + std::to_string(version) +
                                      " is older than this build's " +
                                      std::to_string(kSchemaVersion),
                                  "open it once for writing (any campaign command) to migrate it"));
  }
}

}  // namespace fibrenet::db
