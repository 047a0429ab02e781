// Opening, creating and migrating the results database, and refusing files that are not ours.
#include "db/schema.h"

#include <SQLiteCpp/SQLiteCpp.h>
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>

#include "db/queries.h"
#include "db/results_db.h"
#include "temp_db.h"

namespace fibrenet::db {
namespace {

using testing::TempDbPath;

bool has_object(SQLite::Database& raw, const std::string& type, const std::string& name) {
  SQLite::Statement q(raw, "SELECT count(*) FROM sqlite_schema WHERE type = ? AND name = ?");
  q.bind(1, type);
  q.bind(2, name);
  q.executeStep();
  return q.getColumn(0).getInt() == 1;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Expects `open` to throw DbError whose message names `path` and contains `needle`.
template <class Open>
void expect_refused(Open open, const std::string& path, const std::string& needle) {
  try {
    open();
    FAIL() << "opening " << path << " should have been refused";
  } catch (const DbError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find(needle), std::string::npos) << what;
  }
}

TEST(Schema, MigrationsCreateTablesViewsAndVersion) {
  TempDbPath path;
  ResultsDb db(path.str());
  EXPECT_EQ(db.schema_version(), kSchemaVersion);

  SQLite::Database raw(path.str(), SQLite::OPEN_READONLY);
  EXPECT_EQ(raw.execAndGet("PRAGMA user_version").getInt(), kSchemaVersion);
  EXPECT_EQ(raw.execAndGet("PRAGMA application_id").getInt(), kApplicationId);
  EXPECT_EQ(raw.execAndGet("PRAGMA journal_mode").getString(), "wal");
  for (const char* table : {"campaigns", "candidates", "parameters", "metrics", "artifacts"}) {
    EXPECT_TRUE(has_object(raw, "table", table)) << table;
  }
  EXPECT_TRUE(has_object(raw, "view", "candidate_summary"));
  EXPECT_TRUE(has_object(raw, "view", "campaign_progress"));
}

TEST(Schema, ConnectionEnforcesForeignKeys) {
  ResultsDb db(":memory:");
  EXPECT_EQ(db.connection().execAndGet("PRAGMA foreign_keys").getInt(), 1);
  EXPECT_THROW((db.insert_candidate(42, 0, "k", "cheap", {1}, {{"x", 1.0}})), DbError);
}

TEST(Schema, InMemoryDatabaseIsMigrated) {
  ResultsDb db(":memory:");
  EXPECT_EQ(db.schema_version(), kSchemaVersion);
  EXPECT_TRUE(list_campaigns(db).empty());
}

TEST(Schema, ReopeningAFileKeepsItsData) {
  TempDbPath path;
  std::int64_t candidate_id = 0;
  {
    ResultsDb db(path.str());
    const std::int64_t c = db.upsert_campaign("soft-strong", "spec", "h1", "0.1.0", "abc123");
    candidate_id = db.insert_candidate(c, 0, "key0", "cheap", {11, 12}, {{"curl", 0.25}});
  }
  ResultsDb again(path.str());
  EXPECT_EQ(again.schema_version(), kSchemaVersion);
  const auto campaigns = list_campaigns(again);
  ASSERT_EQ(campaigns.size(), 1u);
  EXPECT_EQ(campaigns[0].name, "soft-strong");
  EXPECT_EQ(campaigns[0].git_commit, "abc123");
  EXPECT_EQ(campaigns[0].counts.pending, 1);
  const auto row = candidate(again, candidate_id);
  ASSERT_TRUE(row.has_value());
  EXPECT_EQ(row->parameters.at("curl"), 0.25);
  EXPECT_EQ(row->seeds, (std::vector<std::uint64_t>{11, 12}));
}

TEST(Schema, RefusesAFileThatIsNotSqlite) {
  TempDbPath path;
  const std::string text = "[campaign]\nname = \"oops, this is TOML\"\n";
  { std::ofstream(path.str(), std::ios::binary) << text; }
  expect_refused([&] { ResultsDb db(path.str()); }, path.str(), "not an SQLite database");
  expect_refused([&] { ResultsDb db(path.str(), OpenMode::kReadOnly); }, path.str(),
                 "not an SQLite database");
  EXPECT_EQ(read_file(path.str()), text) << "a refused file must be left untouched";
}

TEST(Schema, RefusesAnSqliteFileOfAnotherApplication) {
  TempDbPath path;
  {
    SQLite::Database raw(path.str(), SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE);
    raw.exec("CREATE TABLE notes (body TEXT)");
  }
  expect_refused([&] { ResultsDb db(path.str()); }, path.str(), "not a fibrenet results database");
  SQLite::Database raw(path.str(), SQLite::OPEN_READONLY);
  EXPECT_EQ(raw.execAndGet("PRAGMA journal_mode").getString(), "delete")
      << "a foreign file must not be switched to WAL";
}

TEST(Schema, RefusesANewerSchemaVersion) {
  TempDbPath path;
  { ResultsDb db(path.str()); }
  {
    SQLite::Database raw(path.str(), SQLite::OPEN_READWRITE);
    raw.exec("PRAGMA user_version = " + std::to_string(kSchemaVersion + 1));
  }
  expect_refused([&] { ResultsDb db(path.str()); }, path.str(), "unknown schema version");
  expect_refused([&] { ResultsDb db(path.str(), OpenMode::kReadOnly); }, path.str(),
                 "unknown schema version");
  SQLite::Database raw(path.str(), SQLite::OPEN_READONLY);
  EXPECT_EQ(raw.execAndGet("PRAGMA user_version").getInt(), kSchemaVersion + 1)
      << "a refused file must be left untouched";
}

TEST(Schema, ReadOnlyOpenNeedsAnExistingCurrentDatabase) {
  TempDbPath path;
  expect_refused([&] { ResultsDb db(path.str(), OpenMode::kReadOnly); }, path.str(), "cannot open");
  { ResultsDb db(path.str()); }
  ResultsDb reader(path.str(), OpenMode::kReadOnly);
  EXPECT_EQ(reader.schema_version(), kSchemaVersion);
  EXPECT_THROW(reader.upsert_campaign("c", "", "", "", ""), DbError);
}

}  // namespace
}  // namespace fibrenet::db
