// WAL mode: readers (a second ResultsDb, or any SQLite client) read the last committed state
// while the campaign driver holds an open write transaction, without waiting for it.
#include <SQLiteCpp/SQLiteCpp.h>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <future>
#include <string>
#include <thread>
#include <vector>

#include "db/queries.h"
#include "db/results_db.h"
#include "db/schema.h"
#include "temp_db.h"

namespace fibrenet::db {
namespace {

using testing::TempDbPath;
using Clock = std::chrono::steady_clock;

// What a reader should set (the sqlite3 shell: .timeout 1000): see docs/database.md.
constexpr int kReaderBusyTimeoutMs = 1000;

TEST(Concurrency, SecondConnectionReadsWhileFirstHoldsAWriteTransaction) {
  TempDbPath path;
  ResultsDb writer(path.str());
  const std::int64_t c = writer.upsert_campaign("soft-strong", "spec", "h", "0.1.0", "abc");
  writer.insert_candidate(c, 0, "k0", "cheap", {1}, {{"x", 1.0}});

  // The writer opens a write transaction and leaves it uncommitted.
  SQLite::Transaction tx(writer.connection(), SQLite::TransactionBehavior::IMMEDIATE);
  writer.connection().exec("UPDATE campaigns SET status = 'uncommitted'");
  writer.connection().exec(
      "INSERT INTO candidates (campaign_id, eval_index, key, fidelity, created_at) "
      "VALUES (1, 1, 'k1', 'cheap', 'now')");

  const auto start = Clock::now();
  {
    // Opening for writing only reads while the schema is current, so it does not block either.
    ResultsDb reader(path.str());
    const auto campaigns = list_campaigns(reader);
    ASSERT_EQ(campaigns.size(), 1u);
    EXPECT_EQ(campaigns[0].status, "created");
    EXPECT_EQ(campaigns[0].counts.total(), 1);
    EXPECT_EQ(candidates(reader, "soft-strong").size(), 1u);
  }
  {
    ResultsDb reader(path.str(), OpenMode::kReadOnly);
    EXPECT_EQ(list_campaigns(reader).at(0).counts.total(), 1);
  }
  {
    // A plain SQLite client, as a user's sqlite3 shell or Python script would be.
    SQLite::Database shell(path.str(), SQLite::OPEN_READONLY);
    EXPECT_EQ(shell.execAndGet("SELECT count(*) FROM candidate_summary").getInt(), 1);
  }
  // Had any reader waited for the lock, it would have taken the busy timeout (10 s).
  EXPECT_LT(Clock::now() - start, std::chrono::seconds(2));

  tx.commit();
  ResultsDb reader(path.str(), OpenMode::kReadOnly);
  EXPECT_EQ(list_campaigns(reader).at(0).status, "uncommitted");
  EXPECT_EQ(list_campaigns(reader).at(0).counts.total(), 2);
}

TEST(Concurrency, ASecondWriterWaitsForTheLockThenSucceeds) {
  TempDbPath path;
  ResultsDb db(path.str());
  const std::int64_t c = db.upsert_campaign("soft-strong", "spec", "h", "0.1.0", "abc");

  // Another process (here a thread with its own connection) holds the write lock briefly.
  std::promise<void> locked;
  std::thread other([&] {
    SQLite::Database conn(path.str(), SQLite::OPEN_READWRITE);
    SQLite::Transaction tx(conn, SQLite::TransactionBehavior::IMMEDIATE);
    locked.set_value();
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    tx.commit();
  });
  locked.get_future().wait();
  const auto start = Clock::now();
  // The busy timeout makes this write wait for the lock instead of failing at once.
  EXPECT_NO_THROW(db.insert_candidate(c, 0, "k0", "cheap", {}, {}));
  EXPECT_GE(Clock::now() - start, std::chrono::milliseconds(200));
  other.join();
  EXPECT_EQ(candidates(db, "soft-strong").size(), 1u);
}

TEST(Concurrency, ClosedWriterLeavesTheDataInTheFileAndTheEmptyWalInPlace) {
  TempDbPath path;
  const std::string copy = path.str() + "-copy.db";
  {
    ResultsDb writer(path.str());
    const std::int64_t c = writer.upsert_campaign("soft-strong", "spec", "h", "0.1.0", "abc");
    writer.insert_candidate(c, 0, "k0", "cheap", {1}, {{"x", 1.0}});
    EXPECT_GT(std::filesystem::file_size(path.str() + "-wal"), 0u);
  }
  // Checkpointed before the close: the WAL is empty but still there, since SQLite's own
  // checkpoint at close (an exclusive lock that makes a reader opening just then fail at once)
  // was skipped.
  ASSERT_TRUE(std::filesystem::exists(path.str() + "-wal"));
  EXPECT_EQ(std::filesystem::file_size(path.str() + "-wal"), 0u);
  // The .db file alone, copied without its -wal, holds everything.
  std::filesystem::copy_file(path.str(), copy, std::filesystem::copy_options::overwrite_existing);
  {
    ResultsDb reader(copy, OpenMode::kReadOnly);
    EXPECT_EQ(candidates(reader, "soft-strong").size(), 1u);
  }
  for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(copy + suffix);
}

TEST(Concurrency, ANewFileAppearsWholeToAReader) {
  // A reader polls for each file while a writer creates it. The moment a file exists it must
  // hold the current schema: never empty, never in its first transaction. (The reader has a
  // busy timeout, as any reader needs: the first connection to attach to a WAL file runs
  // SQLite's WAL recovery, which refuses other connections for that instant.)
  constexpr int kFiles = 40;
  TempDbPath base;
  const auto file = [&](int i) { return base.str() + "-" + std::to_string(i) + ".db"; };
  std::atomic<int> polling{-1};
  std::thread writer([&] {
    for (int i = 0; i < kFiles; ++i) {
      while (polling < i) std::this_thread::yield();  // the reader is watching file i
      ResultsDb db(file(i));
      db.upsert_campaign("c", "spec", "h", "0.1.0", "abc");
    }
  });
  std::vector<std::string> failures;
  for (int i = 0; i < kFiles; ++i) {
    polling = i;
    while (!std::filesystem::exists(file(i))) std::this_thread::yield();
    try {
      SQLite::Database shell(file(i), SQLite::OPEN_READONLY, kReaderBusyTimeoutMs);
      const int version = shell.execAndGet("PRAGMA user_version").getInt();
      if (version != kSchemaVersion) {
        failures.push_back(file(i) + ": schema version " + std::to_string(version));
      }
    } catch (const SQLite::Exception& e) {
      failures.push_back(file(i) + ": " + e.what());
    }
  }
  writer.join();
  EXPECT_TRUE(failures.empty()) << failures.front();
  // Each file was built under a private name, now gone.
  const std::filesystem::path folder = std::filesystem::path(base.str()).parent_path();
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    const std::string name = entry.path().string();
    EXPECT_FALSE(name.rfind(base.str(), 0) == 0 && name.find(".db.new-") != std::string::npos)
        << name;
  }
  for (int i = 0; i < kFiles; ++i) {
    for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(file(i) + suffix);
  }
}

}  // namespace
}  // namespace fibrenet::db
