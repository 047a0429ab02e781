// Exporting a campaign as JSON and CSV.
#include "db/export.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "db/results_db.h"

namespace fibrenet::db {
namespace {

class ExportTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::int64_t c = db_.upsert_campaign("soft-strong", "spec", "h", "0.1.0", "abc");
    const std::int64_t a =
        db_.insert_candidate(c, 0, "ka", "cheap", {5, 6}, {{"curl", 0.25}, {"length_m", 1.5e-3}});
    db_.mark_running(a);
    db_.mark_done(a,
                  {{"tensile_strength_md", 812.5, "N/m", 12.5, 3},
                   {"softness_index", 0.1, "1", std::nullopt, 3}},
                  42.0, true, 3.25, {{"snapshot", "runs/a.h5"}});
    const std::int64_t b = db_.insert_candidate(c, 1, "kb", "cheap", {5, 6}, {{"curl", 0.5}});
    db_.mark_failed(b, "unstable, \"energy\" diverged", 0.5);
  }
  ResultsDb db_{":memory:"};
};

TEST_F(ExportTest, CsvHasOneRowPerCandidateAndAColumnPerParameterAndMetric) {
  std::ostringstream out;
  export_csv(db_, "soft-strong", out);
  const std::string csv = out.str();
  // The id columns come first; ids 1 and 2 are the first candidates of a fresh database.
  EXPECT_EQ(csv,
            "candidate_id,eval_index,status,fidelity,objective,feasible,wall_s,reason,"
            "param.curl,param.length_m,metric.softness_index,metric.tensile_strength_md\n"
            "1,0,done,cheap,42,1,3.25,,0.25,0.0015,0.1,812.5\n"
            "2,1,failed,cheap,,,0.5,\"unstable, \"\"energy\"\" diverged\",0.5,,,\n");
  EXPECT_THROW(export_csv(db_, "nope", out), DbError);
}

TEST_F(ExportTest, JsonHoldsCampaignAndCandidatesWithUnits) {
  const nlohmann::json j = export_json(db_, "soft-strong");
  EXPECT_EQ(j["schema_version"], 1);
  EXPECT_EQ(j["campaign"]["name"], "soft-strong");
  EXPECT_EQ(j["campaign"]["counts"]["done"], 1);
  EXPECT_EQ(j["campaign"]["counts"]["failed"], 1);
  ASSERT_EQ(j["candidates"].size(), 2u);

  const nlohmann::json& a = j["candidates"][0];
  EXPECT_EQ(a["status"], "done");
  EXPECT_EQ(a["seeds"], (nlohmann::json{5, 6}));
  EXPECT_EQ(a["parameters"]["length_m"], 1.5e-3);
  EXPECT_EQ(a["metrics"]["tensile_strength_md"]["value"], 812.5);
  EXPECT_EQ(a["metrics"]["tensile_strength_md"]["unit"], "N/m");
  EXPECT_EQ(a["metrics"]["tensile_strength_md"]["std_error"], 12.5);
  EXPECT_EQ(a["metrics"]["tensile_strength_md"]["n_replicates"], 3);
  EXPECT_TRUE(a["metrics"]["softness_index"]["std_error"].is_null());
  EXPECT_EQ(a["objective"], 42.0);
  EXPECT_EQ(a["feasible"], true);
  EXPECT_EQ(a["artifacts"][0]["path"], "runs/a.h5");

  const nlohmann::json& b = j["candidates"][1];
  EXPECT_EQ(b["status"], "failed");
  EXPECT_EQ(b["reason"], "unstable, \"energy\" diverged");
  EXPECT_TRUE(b["objective"].is_null());
  EXPECT_TRUE(b["feasible"].is_null());
  EXPECT_TRUE(b["metrics"].empty());
  EXPECT_THROW(export_json(db_, "nope"), DbError);
}

}  // namespace
}  // namespace fibrenet::db
