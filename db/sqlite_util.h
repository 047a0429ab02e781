// Small helpers shared by the .cpp files of db/. Private to db/: include only from .cpp files.
#pragma once

#include <SQLiteCpp/Database.h>
#include <SQLiteCpp/Exception.h>
#include <SQLiteCpp/Statement.h>

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

// Runs `body` and turns any SQLite::Exception into a DbError that names the file and says
// what was being done. DbErrors thrown by `body` pass through unchanged.
template <class Body>
auto guarded(const std::string& path, std::string_view what, Body&& body) -> decltype(body()) {
  try {
    return std::forward<Body>(body)();
  } catch (const SQLite::Exception& e) {
    throw DbError(message(path, what, e.what()));
  }
}

// Text of a nullable column; empty for NULL.
inline std::string text_or_empty(const SQLite::Column& c) {
  return c.isNull() ? std::string() : c.getString();
}

}  // namespace fibrenet::db::detail
