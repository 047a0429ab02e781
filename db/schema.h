// The schema of the results database and the migrations that build it. Only db/ includes this.
//
// The schema version lives in `PRAGMA user_version`; `PRAGMA application_id` marks the file as
// a fibrenet results database. Migration N takes a database from version N-1 to N inside one
// transaction, so a crash mid-migration leaves the previous version intact.
#pragma once

#include <cstdint>
#include <string>

namespace SQLite {
class Database;
}

namespace fibrenet::db {

// The newest schema version this build writes and reads.
inline constexpr int kSchemaVersion = 1;

// "FBNT": stored in the SQLite header so other tools (and we) can recognise the file.
inline constexpr std::int32_t kApplicationId = 0x46424E54;

// How long a connection waits for a lock before failing with "database is locked" [ms].
inline constexpr int kBusyTimeoutMs = 10000;

// Prepares a freshly opened read-write connection: checks that `path` is an SQLite file and a
// fibrenet database (or an empty file), switches to WAL (file databases), turns foreign keys on,
// and applies every pending migration in order, each in its own transaction.
// Throws DbError naming `path` for a non-SQLite file, a foreign SQLite database, or a schema
// version newer than kSchemaVersion.
void prepare_for_writing(SQLite::Database& db, const std::string& path);

// Checks a read-only connection: `path` must hold a fibrenet database at exactly
// kSchemaVersion (a read-only connection cannot migrate). Throws DbError naming `path`.
void check_for_reading(SQLite::Database& db, const std::string& path);

// The schema version stored in the file (`PRAGMA user_version`).
int stored_schema_version(SQLite::Database& db);

}  // namespace fibrenet::db
