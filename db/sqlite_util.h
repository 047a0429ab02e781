// Small helpers shared by the .cpp files of db/. Private to db/: include only from .cpp files.
#pragma once

#include <SQLiteCpp/Database.h>
#include <SQLiteCpp/Exception.h>
#include <SQLiteCpp/Statement.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <string_view>
#include <utility>

#include "db/error.h"

namespace fibrenet::db::detail {

// SQL expression for the current time as ISO 8601 UTC with milliseconds.
inline constexpr const char* kNowSql = "strftime('%Y-%m-%dT%H:%M:%fZ','now')";

// "results database 'PATH': WHAT: DETAIL" -- the one shape of every DbError message.
inline std::string message(const std::string& path, std::string_view what,
                           std::string_view detail) {
  std::string m = "results database '" + path + "': ";
  m += what;
  if (!detail.empty()) {
    m += ": ";
    m += detail;
  }
  return m;
}

// What the operating system said when a write failed ("No space left on device", "File too
// large" under a file-size limit, ...), or "" for any other errno. SQLite itself says only
// "disk I/O error" or "database or disk is full".
inline std::string storage_cause(int err) {
  const bool storage = err == ENOSPC || err == EFBIG || err == EDQUOT || err == EROFS || err == EIO;
  return storage ? std::string(" (") + std::strerror(err) + ")" : std::string();
}

// Runs `body` and turns any SQLite::Exception into a DbError that names the file and says
// what was being done, with the system's cause of a failed write. DbErrors thrown by `body`
// pass through unchanged.
template <class Body>
auto guarded(const std::string& path, std::string_view what, Body&& body) -> decltype(body()) {
  errno = 0;  // so that a cause found below comes from this operation
  try {
    return std::forward<Body>(body)();
  } catch (const SQLite::Exception& e) {
    const int err = errno;
    throw DbError(message(path, what, e.what() + storage_cause(err)));
  }
}

// Text of a nullable column; empty for NULL.
inline std::string text_or_empty(const SQLite::Column& c) {
  return c.isNull() ? std::string() : c.getString();
}

}  // namespace fibrenet::db::detail
