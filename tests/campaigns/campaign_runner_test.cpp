// The campaign runner against analytic evaluators: sweeps, recovery of known parameters,
// constraints, failed evaluations, resume after a crash, replicates, fidelity levels.
#include "campaigns/campaign_runner.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <sstream>
#include <thread>

#include "db/queries.h"
#include "engine/core/error.h"
#include "optimizer/doe.h"
#include "optimizer/replicates.h"
#include "tests/db/temp_db.h"

namespace fibrenet::campaigns {
namespace {

using db::testing::TempDbPath;
using optimizer::Design;
using optimizer::EvaluationResult;
using optimizer::Fidelity;

// A toy sheet: softness rises with thickness and falls with fibre length, strength the other
// way round; smooth, monotonic, so that (softness, strength) determines (length, thickness).
std::map<std::string, double> Sheet(double length_mm, double thickness_um) {
  return {
      {"softness_index", 0.2 + 0.5 * std::pow(thickness_um / 400.0, 0.6) / (1.0 + 0.2 * length_mm)},
      {"tensile_strength", 40.0 * std::pow(length_mm, 0.7) * std::pow(200.0 / thickness_um, 0.8)},
      {"basis_weight", 12.0 + 2.0 * length_mm + 0.01 * thickness_um}};
}

// Counts its calls; optionally fails, adds seeded noise, or crashes after `crash_after` calls.
struct SheetEvaluator {
  struct Crash {};
  int* calls;
  int crash_after = -1;
  double fail_above_length = HUGE_VAL;
  double noise = 0.0;

  EvaluationResult operator()(const Design& d, const Fidelity& f, std::uint64_t seed) const {
    if (crash_after >= 0 && *calls >= crash_after) throw Crash{};
    ++*calls;
    const double length = d.at("fibres.length_mm");
    if (length > fail_above_length) throw RunError("unstable: kinetic energy jump at step 12");
    EvaluationResult r;
    r.metrics = Sheet(length, d.at("pressing.target_thickness_um"));
    const auto bias = f.overrides.find("bias");
    if (bias != f.overrides.end()) r.metrics["tensile_strength"] += bias->second;
    r.metrics["tensile_strength"] += noise * (static_cast<double>(seed % 1000) / 1000.0 - 0.5);
    r.units = {{"softness_index", "1"}, {"tensile_strength", "N/m"}, {"basis_weight", "g/m^2"}};
    return r;
  }
};

const char* kSpace = R"(
base_scene = "analytic:quadratic"
[[variables]]
key = "fibres.length_mm"
lower = 0.5
upper = 4.0
start = 1.0
[[variables]]
key = "pressing.target_thickness_um"
lower = 50.0
upper = 400.0
log = true
start = 300.0
)";

// `head` holds top-level keys (they must come before the [[variables]] tables).
CampaignSpec Spec(const std::string& name, const std::string& rest, const std::string& head = "") {
  return ParseCampaign(std::string("name = \"") + name + "\"\n" + head + kSpace + rest,
                       name + ".toml", "/tmp");
}

const char* kConstrained = R"(
[goals]
minimise = "basis_weight"
[goals.constraints]
softness_index = { min = 0.45 }
tensile_strength = { min = 30 }
[doe]
points = 6
[algorithm]
name = "LN_COBYLA"
[budget]
max_evaluations = 25
)";

TEST(CampaignRunner, SweepStoresEveryPointInOrder) {
  TempDbPath path;
  db::ResultsDb db(path.str());
  int calls = 0;
  const CampaignSpec spec = Spec("sweep", R"(
[goals]
maximise = "softness_index"
[doe]
points = 8
)");
  const CampaignResult r = RunCampaign(spec, db, SheetEvaluator{&calls}, {});
  EXPECT_EQ(r.status, "done");
  EXPECT_EQ(calls, 8);
  EXPECT_EQ(r.evaluated, 8);
  const auto rows = db::candidates(db, "sweep");
  ASSERT_EQ(rows.size(), 8u);
  const auto points = optimizer::GenerateDoe(*spec.doe, 2);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].eval_index, static_cast<std::int64_t>(i));
    EXPECT_EQ(rows[i].status, db::CandidateStatus::kDone);
    EXPECT_EQ(rows[i].parameters, spec.space.ToDesign(points[i]));
    EXPECT_EQ(rows[i].metric("tensile_strength")->unit, "N/m");
    EXPECT_EQ(rows[i].fidelity, "default");
  }
  ASSERT_TRUE(r.best);
  EXPECT_EQ(r.best->id, db::best(db, "sweep", 1).at(0).id);
  EXPECT_DOUBLE_EQ(r.best->objective, -r.best->metrics.at("softness_index"));
  EXPECT_EQ(db::find_campaign(db, "sweep")->status, "done");
}

// The recovery test of the issue: metrics computed at known parameters become the targets of a
// campaign that starts elsewhere; it must reach them within 5%.
TEST(CampaignRunner, RecoversTargetsOfKnownParameters) {
  const auto truth = Sheet(2.2, 180.0);
  for (const char* algorithm : {"LN_BOBYQA", "LN_NELDERMEAD", "LN_COBYLA"}) {
    TempDbPath path;
    db::ResultsDb db(path.str());
    int calls = 0;
    const CampaignSpec spec = Spec("recover", fmt::format(R"(
[goals.targets]
softness_index = {}
tensile_strength = {}
[algorithm]
name = "{}"
[budget]
max_evaluations = 120
)",
                                                          truth.at("softness_index"),
                                                          truth.at("tensile_strength"), algorithm));
    const CampaignResult r = RunCampaign(spec, db, SheetEvaluator{&calls}, {});
    ASSERT_TRUE(r.best) << algorithm;
    for (const char* metric : {"softness_index", "tensile_strength"}) {
      EXPECT_NEAR(r.best->metrics.at(metric), truth.at(metric), 0.05 * truth.at(metric))
          << algorithm << " " << metric;
    }
    EXPECT_LE(calls, 120);
    EXPECT_NEAR(r.best->design.at("fibres.length_mm"), 2.2, 0.2) << algorithm;
  }
}

TEST(CampaignRunner, ConstrainedSearchEndsFeasibleAndBeatsTheSweep) {
  TempDbPath path;
  db::ResultsDb db(path.str());
  int calls = 0;
  const CampaignResult r =
      RunCampaign(Spec("constrained", kConstrained), db, SheetEvaluator{&calls}, {});
  ASSERT_TRUE(r.best);
  EXPECT_TRUE(r.best->feasible);
  EXPECT_GE(r.best->metrics.at("softness_index"), 0.45 - 1e-6);
  EXPECT_GE(r.best->metrics.at("tensile_strength"), 30.0 - 1e-4);
  double best_sweep = HUGE_VAL;
  for (const auto& row : db::candidates(db, "constrained")) {
    if (row.provenance.value("phase", "") == "doe" && row.feasible.value_or(false)) {
      best_sweep = std::min(best_sweep, *row.objective);
    }
  }
  EXPECT_LT(r.best->objective, best_sweep);
  EXPECT_EQ(r.optimiser_status.empty(), false);
}

TEST(CampaignRunner, FailedEvaluationsGetAPenaltyAndTheCampaignGoesOn) {
  TempDbPath path;
  db::ResultsDb db(path.str());
  int calls = 0;
  SheetEvaluator evaluator{&calls};
  evaluator.fail_above_length = 2.5;
  std::ostringstream progress;
  RunnerOptions options;
  options.progress = &progress;
  const CampaignResult r = RunCampaign(Spec("failing", kConstrained), db, evaluator, options);
  EXPECT_EQ(r.status, "done");
  EXPECT_GT(r.failed, 0);
  int failed = 0;
  for (const auto& row : db::candidates(db, "failing")) {
    if (row.status != db::CandidateStatus::kFailed) continue;
    ++failed;
    EXPECT_GT(row.parameters.at("fibres.length_mm"), 2.5);
    EXPECT_NE(row.reason.find("unstable: kinetic energy jump"), std::string::npos);
    EXPECT_NE(row.reason.find("[penalty "), std::string::npos) << row.reason;
  }
  EXPECT_EQ(failed, r.failed);
  ASSERT_TRUE(r.best);
  EXPECT_TRUE(r.best->feasible);
  EXPECT_LE(r.best->design.at("fibres.length_mm"), 2.5);
  EXPECT_NE(progress.str().find("FAILED (unstable"), std::string::npos) << progress.str();
  EXPECT_NE(progress.str().find("best feasible"), std::string::npos);
}

// Everything that identifies a stored candidate and its results.
std::vector<std::string> Fingerprint(const db::ResultsDb& db, const std::string& campaign) {
  std::vector<std::string> out;
  for (const auto& row : db::candidates(db, campaign)) {
    std::string s =
        fmt::format("{}|{}|{}|{}|{}|{}", row.eval_index, row.key, db::to_string(row.status),
                    row.fidelity, row.objective.value_or(NAN), row.feasible.value_or(false));
    for (const auto& [k, v] : row.parameters) s += fmt::format("|{}={:.17g}", k, v);
    for (const auto& m : row.metrics) s += fmt::format("|{}={:.17g}", m.name, m.value);
    out.push_back(s);
  }
  return out;
}

TEST(CampaignRunner, ResumesAfterACrashWithoutLosingOrRepeatingWork) {
  const CampaignSpec spec = Spec("resume", kConstrained);
  // The uninterrupted run.
  TempDbPath full_path;
  int full_calls = 0;
  CampaignResult full;
  {
    db::ResultsDb db(full_path.str());
    full = RunCampaign(spec, db, SheetEvaluator{&full_calls}, {});
  }
  ASSERT_GT(full_calls, 12);

  // Crash after 11 evaluations (inside the optimisation: the sweep has 6), as kill -9 would:
  // the database is closed without any cleanup.
  TempDbPath path;
  int first_calls = 0;
  {
    db::ResultsDb db(path.str());
    SheetEvaluator crashing{&first_calls};
    crashing.crash_after = 11;
    EXPECT_THROW(RunCampaign(spec, db, crashing, {}), SheetEvaluator::Crash);
  }
  EXPECT_EQ(first_calls, 11);
  {
    db::ResultsDb db(path.str(), db::OpenMode::kReadOnly);
    const auto counts = db::find_campaign(db, "resume")->counts;
    EXPECT_EQ(counts.done, 11);
    EXPECT_EQ(counts.running, 1);  // the candidate that was being evaluated
  }
  // Resume: the 11 finished candidates are replayed, the rest evaluated.
  int second_calls = 0;
  CampaignResult resumed;
  {
    db::ResultsDb db(path.str());
    resumed = RunCampaign(spec, db, SheetEvaluator{&second_calls}, {});
  }
  EXPECT_EQ(first_calls + second_calls, full_calls);  // nothing repeated
  EXPECT_EQ(resumed.replayed, 11);
  EXPECT_EQ(resumed.evaluated, full.evaluated - 11);
  ASSERT_TRUE(resumed.best && full.best);
  EXPECT_EQ(resumed.best->eval_index, full.best->eval_index);
  EXPECT_EQ(resumed.best->design, full.best->design);
  EXPECT_EQ(resumed.best->objective, full.best->objective);
  EXPECT_EQ(resumed.optimiser_status, full.optimiser_status);
  {
    db::ResultsDb a(full_path.str(), db::OpenMode::kReadOnly);
    db::ResultsDb b(path.str(), db::OpenMode::kReadOnly);
    EXPECT_EQ(Fingerprint(a, "resume"), Fingerprint(b, "resume"));  // nothing lost
  }
  // Running a finished campaign again evaluates nothing and gives the same answer.
  int third_calls = 0;
  db::ResultsDb db(path.str());
  const CampaignResult again = RunCampaign(spec, db, SheetEvaluator{&third_calls}, {});
  EXPECT_EQ(third_calls, 0);
  EXPECT_EQ(again.replayed, again.candidates);
  EXPECT_EQ(again.best->id, resumed.best->id);
}

TEST(CampaignRunner, ResumeRefusesAChangedCampaignButAcceptsABiggerBudget) {
  TempDbPath path;
  db::ResultsDb db(path.str());
  int calls = 0;
  RunCampaign(Spec("change", kConstrained), db, SheetEvaluator{&calls}, {});
  const std::string changed = std::string(kConstrained);
  std::string other = changed;
  other.replace(other.find("min = 0.45"), 10, "min = 0.46");
  EXPECT_THROW(RunCampaign(Spec("change", other), db, SheetEvaluator{&calls}, {}), InputError);
  std::string bigger = changed;
  bigger.replace(bigger.find("max_evaluations = 25"), 20, "max_evaluations = 40");
  const int before = calls;
  const CampaignResult r = RunCampaign(Spec("change", bigger), db, SheetEvaluator{&calls}, {});
  EXPECT_GT(r.replayed, 0);
  EXPECT_GE(calls, before);
}

TEST(CampaignRunner, ReplicatesUseCommonRandomNumbers) {
  TempDbPath path;
  db::ResultsDb db(path.str());
  int calls = 0;
  SheetEvaluator noisy{&calls};
  noisy.noise = 2.0;
  const CampaignSpec spec = Spec("replicates", R"(
[goals]
maximise = "tensile_strength"
[doe]
points = 4
)",
                                 "seed = 9\nreplicates = 3\n");
  RunCampaign(spec, db, noisy, {});
  EXPECT_EQ(calls, 12);
  const auto seeds = optimizer::ReplicateSeeds(9, 3);
  for (const auto& row : db::candidates(db, "replicates")) {
    EXPECT_EQ(row.seeds, seeds);  // the same networks for every candidate
    const db::MetricValue* m = row.metric("tensile_strength");
    ASSERT_NE(m, nullptr);
    EXPECT_EQ(m->n_replicates, 3);
    ASSERT_TRUE(m->std_error);
    EXPECT_GT(*m->std_error, 0.0);
    const auto values = row.provenance.at("replicates").at("tensile_strength");
    EXPECT_EQ(values.size(), 3u);
    EXPECT_NEAR(m->value,
                (values[0].get<double>() + values[1].get<double>() + values[2].get<double>()) / 3.0,
                1e-12);
    // A metric the seed does not affect is the same in every replicate.
    EXPECT_EQ(row.metric("softness_index")->std_error, 0.0);
  }
}

TEST(CampaignRunner, FinerLevelsConfirmTheBestCandidates) {
  TempDbPath path;
  db::ResultsDb db(path.str());
  int calls = 0;
  const CampaignSpec spec = Spec("levels", R"(
[goals]
maximise = "tensile_strength"
[doe]
points = 8
[[fidelity]]
name = "coarse"
overrides = { bias = 5.0 }
[[fidelity]]
name = "fine"
top = 2
)");
  const CampaignResult r = RunCampaign(spec, db, SheetEvaluator{&calls}, {});
  EXPECT_EQ(calls, 10);
  ASSERT_TRUE(r.best);
  EXPECT_EQ(r.best->fidelity, "fine");
  EXPECT_EQ(r.best->phase, "confirm");
  ASSERT_EQ(r.best_per_level.size(), 2u);
  EXPECT_EQ(r.best_per_level[0].design, r.best->design);
  EXPECT_NEAR(r.best_per_level[0].metrics.at("tensile_strength"),
              r.best->metrics.at("tensile_strength") + 5.0, 1e-9);
  int fine = 0;
  for (const auto& row : db::candidates(db, "levels")) fine += row.fidelity == "fine";
  EXPECT_EQ(fine, 2);
}

TEST(CampaignRunner, AMissingGoalMetricStopsTheCampaignAsBadInput) {
  TempDbPath path;
  db::ResultsDb db(path.str());
  int calls = 0;
  const CampaignSpec spec = Spec("typo", R"(
[goals]
maximise = "softnes_index"
[doe]
points = 3
)");
  try {
    RunCampaign(spec, db, SheetEvaluator{&calls}, {});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'softness_index'"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(calls, 1);
  const auto rows = db::candidates(db, "typo");
  ASSERT_GE(rows.size(), 1u);
  EXPECT_EQ(rows[0].status, db::CandidateStatus::kFailed);
  EXPECT_EQ(db::find_campaign(db, "typo")->status, "failed");
}

TEST(CampaignRunner, WallTimeBudgetStopsAndTheNextRunContinues) {
  TempDbPath path;
  int calls = 0;
  struct Slow {
    SheetEvaluator inner;
    EvaluationResult operator()(const Design& d, const Fidelity& f, std::uint64_t s) const {
      std::this_thread::sleep_for(std::chrono::milliseconds(30));
      return inner(d, f, s);
    }
  };
  std::string rest = kConstrained;
  rest.replace(rest.find("max_evaluations = 25"), 20, "max_evaluations = 25\nmax_wall_s = 0.1");
  CampaignResult first;
  {
    db::ResultsDb db(path.str());
    first = RunCampaign(Spec("clock", rest), db, Slow{SheetEvaluator{&calls}}, {});
  }
  EXPECT_NE(first.status.find("stopped: wall-time budget"), std::string::npos) << first.status;
  EXPECT_LT(calls, 10);
  db::ResultsDb db(path.str());
  EXPECT_EQ(db::find_campaign(db, "clock")->status, "stopped");
  const CampaignResult second =
      RunCampaign(Spec("clock", kConstrained), db, SheetEvaluator{&calls}, {});
  EXPECT_EQ(second.status, "done");
  int reference_calls = 0;
  TempDbPath reference_path;
  db::ResultsDb reference_db(reference_path.str());
  const CampaignResult reference =
      RunCampaign(Spec("clock", kConstrained), reference_db, SheetEvaluator{&reference_calls}, {});
  EXPECT_EQ(calls, reference_calls);
  EXPECT_EQ(second.best->design, reference.best->design);
}

}  // namespace
}  // namespace fibrenet::campaigns
