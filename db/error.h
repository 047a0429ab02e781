// The error type of the results database. Every message names the database file, so a user who
// passed the wrong --db path sees at once which file was refused and why.
#pragma once

#include <stdexcept>

namespace fibrenet::db {

// Thrown for a file that is not a fibrenet results database, a schema this build does not
// know, an illegal status change, an invalid value, or any SQLite failure (wrapped, with what
// was being done). It derives from std::runtime_error rather than fibrenet::Error because that
// type lives in engine/core and db/ must not depend on the engine (flow: campaigns -> db).
class DbError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace fibrenet::db
