// Reading the results database: campaign listings with counts, candidates in order, the best
// candidates (feasible first), and the candidate_summary view that SQL users see.
#include "db/queries.h"

#include <SQLiteCpp/SQLiteCpp.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "db/results_db.h"

namespace fibrenet::db {
namespace {

class QueriesTest : public ::testing::Test {
 protected:
  ResultsDb db_{":memory:"};
  std::int64_t campaign_ = db_.upsert_campaign("soft-strong", "spec", "h", "0.1.0", "abc");

  // Stores a candidate and finishes it: done with `objective` and `feasible`, or failed.
  std::int64_t Done(std::int64_t eval_index, double objective, bool feasible) {
    const std::int64_t id =
        db_.insert_candidate(campaign_, eval_index, "k" + std::to_string(eval_index), "cheap", {1},
                             {{"x", static_cast<double>(eval_index)}});
    db_.mark_running(id);
    db_.mark_done(id, {{"softness_index", 0.1 * eval_index, "1", std::nullopt, 1}}, objective,
                  feasible, 1.0);
    return id;
  }
  std::int64_t Failed(std::int64_t eval_index) {
    const std::int64_t id =
        db_.insert_candidate(campaign_, eval_index, "k" + std::to_string(eval_index), "cheap", {1},
                             {{"x", static_cast<double>(eval_index)}});
    db_.mark_failed(id, "time-out", 10.0);
    return id;
  }
};

std::vector<std::int64_t> ids(const std::vector<CandidateRow>& rows) {
  std::vector<std::int64_t> out;
  for (const CandidateRow& r : rows) out.push_back(r.id);
  return out;
}

TEST_F(QueriesTest, ListCampaignsCountsCandidatesPerStatus) {
  Done(0, 1.0, true);
  Done(1, 2.0, false);
  Failed(2);
  const std::int64_t running = db_.insert_candidate(campaign_, 3, "k3", "cheap", {}, {});
  db_.mark_running(running);
  db_.insert_candidate(campaign_, 4, "k4", "cheap", {}, {});
  db_.upsert_campaign("empty", "spec", "h", "0.1.0", "abc");

  const auto campaigns = list_campaigns(db_);
  ASSERT_EQ(campaigns.size(), 2u);
  EXPECT_EQ(campaigns[0].name, "soft-strong");
  EXPECT_EQ(campaigns[0].status, "created");
  EXPECT_EQ(campaigns[0].counts.done, 2);
  EXPECT_EQ(campaigns[0].counts.failed, 1);
  EXPECT_EQ(campaigns[0].counts.running, 1);
  EXPECT_EQ(campaigns[0].counts.pending, 1);
  EXPECT_EQ(campaigns[0].counts.total(), 5);
  EXPECT_EQ(campaigns[1].name, "empty");
  EXPECT_EQ(campaigns[1].counts.total(), 0);
  EXPECT_FALSE(find_campaign(db_, "nope").has_value());
}

TEST_F(QueriesTest, CandidatesComeInEvalIndexOrder) {
  const std::int64_t c2 = Done(2, 1.0, true);
  const std::int64_t c0 = Done(0, 1.0, true);
  const std::int64_t c1 = Failed(1);
  const auto rows = candidates(db_, "soft-strong");
  EXPECT_EQ(ids(rows), (std::vector<std::int64_t>{c0, c1, c2}));
  EXPECT_EQ(rows[0].parameters.at("x"), 0.0);
  EXPECT_EQ(rows[2].metric("softness_index")->value, 0.2);
  EXPECT_TRUE(rows[1].metrics.empty());
  EXPECT_FALSE(candidate(db_, 12345).has_value());
  EXPECT_THROW(candidates(db_, "nope"), DbError);
}

TEST_F(QueriesTest, BestPutsFeasibleFirstThenLowestObjective) {
  const std::int64_t infeasible_low = Done(0, 0.5, false);
  const std::int64_t feasible_high = Done(1, 5.0, true);
  const std::int64_t feasible_low = Done(2, 3.0, true);
  const std::int64_t infeasible_high = Done(3, 9.0, false);
  Failed(4);
  db_.insert_candidate(campaign_, 5, "k5", "cheap", {}, {});  // pending: not ranked

  EXPECT_EQ(
      ids(best(db_, "soft-strong", 10)),
      (std::vector<std::int64_t>{feasible_low, feasible_high, infeasible_low, infeasible_high}));
  EXPECT_EQ(ids(best(db_, "soft-strong", 2)),
            (std::vector<std::int64_t>{feasible_low, feasible_high}));
  EXPECT_EQ(best(db_, "soft-strong", -1).size(), 4u);
  EXPECT_TRUE(best(db_, "soft-strong", 0).empty());
  EXPECT_THROW(best(db_, "nope", 3), DbError);
}

TEST_F(QueriesTest, SummaryViewHasOneRowPerCandidateWithJsonColumns) {
  const std::int64_t done = Done(0, 1.5, true);
  Failed(1);
  SQLite::Statement q(db_.connection(),
                      "SELECT candidate_id, campaign, status, objective, feasible, parameters, "
                      "metrics FROM candidate_summary ORDER BY eval_index");
  ASSERT_TRUE(q.executeStep());
  EXPECT_EQ(q.getColumn(0).getInt64(), done);
  EXPECT_EQ(q.getColumn(1).getString(), "soft-strong");
  EXPECT_EQ(q.getColumn(2).getString(), "done");
  EXPECT_EQ(q.getColumn(3).getDouble(), 1.5);
  EXPECT_EQ(q.getColumn(4).getInt(), 1);
  EXPECT_EQ(nlohmann::json::parse(q.getColumn(5).getString()), (nlohmann::json{{"x", 0.0}}));
  EXPECT_EQ(nlohmann::json::parse(q.getColumn(6).getString()),
            (nlohmann::json{{"softness_index", 0.0}}));
  ASSERT_TRUE(q.executeStep());
  EXPECT_EQ(q.getColumn(2).getString(), "failed");
  EXPECT_TRUE(q.getColumn(3).isNull());
  EXPECT_EQ(q.getColumn(6).getString(), "{}");
  EXPECT_FALSE(q.executeStep());
}

}  // namespace
}  // namespace fibrenet::db
