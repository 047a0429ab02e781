// Writing campaigns and candidates: the candidate life cycle, failures, resume by key, and
// transactions that leave nothing behind when they fail.
#include "db/results_db.h"

#include <SQLiteCpp/SQLiteCpp.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "db/queries.h"

namespace fibrenet::db {
namespace {

class ResultsDbTest : public ::testing::Test {
 protected:
  ResultsDb db_{":memory:"};
  std::int64_t campaign_ =
      db_.upsert_campaign("soft-strong", "[goals]\n", "hash-1", "0.1.0", "c0ffee");

  std::int64_t Insert(std::int64_t eval_index, const std::string& key) {
    return db_.insert_candidate(campaign_, eval_index, key, "cheap", {7, 8, 9},
                                {{"fibre_length_m", 1.2e-3}, {"curl", 0.3}});
  }

  int Count(const std::string& table) {
    return db_.connection().execAndGet("SELECT count(*) FROM " + table).getInt();
  }
};

TEST_F(ResultsDbTest, CandidateGoesPendingRunningDoneWithMetrics) {
  const std::int64_t id = Insert(0, "k0");
  auto row = candidate(db_, id);
  ASSERT_TRUE(row.has_value());
  EXPECT_EQ(row->status, CandidateStatus::kPending);
  EXPECT_EQ(row->campaign, "soft-strong");
  EXPECT_EQ(row->fidelity, "cheap");
  EXPECT_EQ(row->seeds, (std::vector<std::uint64_t>{7, 8, 9}));
  EXPECT_EQ(row->parameters.at("fibre_length_m"), 1.2e-3);
  EXPECT_FALSE(row->created_at.empty());
  EXPECT_TRUE(row->started_at.empty());
  EXPECT_FALSE(row->objective.has_value());

  db_.mark_running(id);
  row = candidate(db_, id);
  EXPECT_EQ(row->status, CandidateStatus::kRunning);
  EXPECT_FALSE(row->started_at.empty());
  EXPECT_TRUE(row->ended_at.empty());

  db_.mark_done(id,
                {{"tensile_strength_md", 812.5, "N/m", 12.5, 3},
                 {"softness_index", 0.71, "1", std::nullopt, 1}},
                /*objective=*/42.0, /*feasible=*/true, /*wall_s=*/3.5,
                {{"snapshot", "runs/c0/pressed.h5"}, {"curve", "runs/c0/tensile.csv"}},
                {{"rank", 2}});
  row = candidate(db_, id);
  EXPECT_EQ(row->status, CandidateStatus::kDone);
  EXPECT_FALSE(row->ended_at.empty());
  EXPECT_EQ(row->objective, 42.0);
  EXPECT_EQ(row->feasible, true);
  EXPECT_EQ(row->wall_s, 3.5);
  ASSERT_EQ(row->metrics.size(), 2u);
  EXPECT_EQ(row->metrics[0].name, "softness_index");  // sorted by name
  EXPECT_FALSE(row->metrics[0].std_error.has_value());
  const MetricValue* strength = row->metric("tensile_strength_md");
  ASSERT_NE(strength, nullptr);
  EXPECT_EQ(strength->value, 812.5);
  EXPECT_EQ(strength->unit, "N/m");
  EXPECT_EQ(strength->std_error, 12.5);
  EXPECT_EQ(strength->n_replicates, 3);
  ASSERT_EQ(row->artifacts.size(), 2u);
  EXPECT_EQ(row->artifacts[0].kind, "snapshot");
  EXPECT_EQ(row->artifacts[1].path, "runs/c0/tensile.csv");
  EXPECT_EQ(row->provenance, (nlohmann::json{{"rank", 2}}));
}

TEST_F(ResultsDbTest, ProvenanceGivenAtInsertIsMergedWhenDone) {
  const std::int64_t id = db_.insert_candidate(campaign_, 0, "k0", "cheap", {1}, {{"x", 1.0}},
                                               {{"phase", "doe"}, {"rank", 0}});
  db_.mark_running(id);
  db_.mark_done(id, {}, 1.0, false, 0.1, {}, {{"rank", 3}});
  EXPECT_EQ(candidate(db_, id)->provenance, (nlohmann::json{{"phase", "doe"}, {"rank", 3}}));
  EXPECT_THROW(db_.insert_candidate(campaign_, 1, "k1", "cheap", {1}, {}, nlohmann::json(5)),
               DbError);
}

TEST_F(ResultsDbTest, FailedCandidateKeepsItsReason) {
  const std::int64_t id = Insert(0, "k0");
  db_.mark_running(id);
  db_.mark_failed(id, "unstable: kinetic energy diverged at t = 1.2e-3 s", 0.8);
  const auto row = candidate(db_, id);
  EXPECT_EQ(row->status, CandidateStatus::kFailed);
  EXPECT_EQ(row->reason, "unstable: kinetic energy diverged at t = 1.2e-3 s");
  EXPECT_EQ(row->wall_s, 0.8);
  EXPECT_FALSE(row->objective.has_value());
  EXPECT_FALSE(row->feasible.has_value());
  EXPECT_TRUE(row->metrics.empty());

  // A candidate may also fail before it starts, e.g. parameters the scene rejects.
  const std::int64_t early = Insert(1, "k1");
  db_.mark_failed(early, "scene rejected: curl must be in [0, 1]", 0.0);
  EXPECT_EQ(candidate(db_, early)->status, CandidateStatus::kFailed);
  EXPECT_THROW(db_.mark_failed(early, "", 0.0), DbError);
}

TEST_F(ResultsDbTest, IllegalStatusChangesAreRefused) {
  const std::int64_t id = Insert(0, "k0");
  try {
    db_.mark_done(id, {}, 1.0, true, 1.0);
    FAIL() << "a pending candidate cannot be done";
  } catch (const DbError& e) {
    EXPECT_NE(std::string(e.what()).find("it is pending"), std::string::npos) << e.what();
  }
  db_.mark_running(id);
  db_.mark_running(id);  // restarting after a crash is allowed
  db_.mark_done(id, {}, 1.0, true, 1.0);
  EXPECT_THROW(db_.mark_running(id), DbError);
  EXPECT_THROW(db_.mark_failed(id, "late", 1.0), DbError);
  try {
    db_.mark_running(999);
    FAIL() << "unknown candidate";
  } catch (const DbError& e) {
    EXPECT_NE(std::string(e.what()).find("no candidate with id 999"), std::string::npos);
  }
}

TEST_F(ResultsDbTest, KeyLookupFindsStoredWorkForResume) {
  const std::int64_t id = Insert(0, "abc");
  db_.mark_running(id);
  db_.mark_done(id, {{"softness_index", 0.5, "1", std::nullopt, 1}}, 3.0, true, 2.0);

  const auto found = find_candidate_by_key(db_, campaign_, "abc");
  ASSERT_TRUE(found.has_value());
  EXPECT_EQ(found->id, id);
  EXPECT_EQ(found->status, CandidateStatus::kDone);
  EXPECT_EQ(found->objective, 3.0);
  EXPECT_EQ(found->metric("softness_index")->value, 0.5);
  EXPECT_FALSE(find_candidate_by_key(db_, campaign_, "other").has_value());

  // The same key again in the same campaign is a bug in the caller: it must resume instead.
  try {
    Insert(1, "abc");
    FAIL() << "duplicate key";
  } catch (const DbError& e) {
    EXPECT_NE(std::string(e.what()).find("already stored as candidate"), std::string::npos);
  }
  // Keys are unique per campaign only.
  const std::int64_t other = db_.upsert_campaign("sweep", "", "hash-2", "0.1.0", "c0ffee");
  EXPECT_NO_THROW(db_.insert_candidate(other, 0, "abc", "cheap", {}, {}));
  EXPECT_FALSE(find_candidate_by_key(db_, other, "missing").has_value());
}

TEST_F(ResultsDbTest, WriteThatFailsMidwayLeavesNothing) {
  const std::int64_t id = Insert(0, "k0");
  db_.mark_running(id);
  // The candidate row is updated and the first metric inserted before the second metric, with
  // the same name, violates the primary key: the whole transaction must roll back.
  EXPECT_THROW(db_.mark_done(id,
                             {{"softness_index", 0.5, "1", std::nullopt, 1},
                              {"softness_index", 0.6, "1", std::nullopt, 1}},
                             1.0, true, 1.0, {{"snapshot", "a.h5"}}),
               DbError);
  auto row = candidate(db_, id);
  EXPECT_EQ(row->status, CandidateStatus::kRunning);
  EXPECT_FALSE(row->objective.has_value());
  EXPECT_EQ(Count("metrics"), 0);
  EXPECT_EQ(Count("artifacts"), 0);

  // Same for a duplicate artifact after metrics went in.
  EXPECT_THROW(db_.mark_done(id, {{"softness_index", 0.5, "1", std::nullopt, 1}}, 1.0, true, 1.0,
                             {{"snapshot", "a.h5"}, {"snapshot", "a.h5"}}),
               DbError);
  EXPECT_EQ(Count("metrics"), 0);
  EXPECT_EQ(Count("artifacts"), 0);

  // The connection is usable afterwards: nothing was left open.
  db_.mark_done(id, {{"softness_index", 0.5, "1", std::nullopt, 1}}, 1.0, true, 1.0);
  EXPECT_EQ(candidate(db_, id)->status, CandidateStatus::kDone);
}

TEST_F(ResultsDbTest, CandidateOfAnUnknownCampaignIsRefused) {
  // The foreign key refuses it; neither the candidate nor its parameters may remain.
  EXPECT_THROW((db_.insert_candidate(campaign_ + 100, 0, "k", "cheap", {1}, {{"x", 1.0}})),
               DbError);
  EXPECT_EQ(Count("candidates"), 0);
  EXPECT_EQ(Count("parameters"), 0);
}

TEST_F(ResultsDbTest, NonFiniteValuesAreRefusedBeforeWriting) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW((db_.insert_candidate(campaign_, 0, "k", "cheap", {}, {{"x", nan}})), DbError);
  EXPECT_EQ(Count("candidates"), 0);
  const std::int64_t id = Insert(0, "k0");
  db_.mark_running(id);
  EXPECT_THROW(db_.mark_done(id, {{"m", nan, "1", std::nullopt, 1}}, 1.0, true, 1.0), DbError);
  EXPECT_THROW(db_.mark_done(id, {}, std::numeric_limits<double>::infinity(), true, 1.0), DbError);
  EXPECT_THROW(db_.mark_done(id, {{"m", 1.0, "1", -1.0, 2}}, 1.0, true, 1.0), DbError);
  EXPECT_THROW(db_.mark_done(id, {{"m", 1.0, "1", std::nullopt, 0}}, 1.0, true, 1.0), DbError);
  EXPECT_THROW(db_.mark_done(id, {}, 1.0, true, -1.0), DbError);
  EXPECT_EQ(candidate(db_, id)->status, CandidateStatus::kRunning);
}

TEST_F(ResultsDbTest, UpsertCampaignKeepsIdAndStatus) {
  db_.set_campaign_status(campaign_, "running");
  const std::int64_t again =
      db_.upsert_campaign("soft-strong", "[goals] # edited\n", "hash-2", "0.2.0", "beef");
  EXPECT_EQ(again, campaign_);
  const auto row = find_campaign(db_, "soft-strong");
  ASSERT_TRUE(row.has_value());
  EXPECT_EQ(row->status, "running");
  EXPECT_EQ(row->spec_hash, "hash-2");
  EXPECT_EQ(row->software_version, "0.2.0");
  EXPECT_EQ(row->git_commit, "beef");
  EXPECT_THROW(db_.set_campaign_status(campaign_ + 100, "done"), DbError);
  EXPECT_THROW(db_.set_campaign_status(campaign_, ""), DbError);
  EXPECT_THROW(db_.upsert_campaign("", "", "", "", ""), DbError);
}

}  // namespace
}  // namespace fibrenet::db
