#include "optimizer/replicates.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace fibrenet::optimizer {
namespace {

EvaluationResult Result(std::map<std::string, double> metrics) {
  EvaluationResult r;
  r.metrics = std::move(metrics);
  r.units["strength"] = "N/m";
  return r;
}

TEST(Replicates, SeedsAreCommonAndDistinct) {
  const auto seeds = ReplicateSeeds(7, 5);
  EXPECT_EQ(seeds, ReplicateSeeds(7, 5));  // the same for every candidate
  EXPECT_EQ(std::set<std::uint64_t>(seeds.begin(), seeds.end()).size(), 5u);
  EXPECT_EQ(seeds[2], ReplicateSeed(7, 2));
  EXPECT_NE(ReplicateSeeds(8, 5), seeds);
  for (auto s : seeds) EXPECT_LT(s, std::uint64_t{1} << 63);
}

TEST(Replicates, MeanAndStandardError) {
  const auto stats = ReduceReplicates({Result({{"strength", 1.0}, {"x", 5.0}}),
                                       Result({{"strength", 2.0}}), Result({{"strength", 6.0}})});
  ASSERT_EQ(stats.size(), 1u);  // "x" is not in every replicate
  const MetricStatistics& s = stats.at("strength");
  EXPECT_EQ(s.n, 3);
  EXPECT_DOUBLE_EQ(s.mean, 3.0);
  // sample variance (4 + 1 + 9) / 2 = 7, standard error sqrt(7 / 3)
  EXPECT_NEAR(s.std_error, std::sqrt(7.0 / 3.0), 1e-14);
  EXPECT_EQ(s.unit, "N/m");
  EXPECT_EQ(s.values, (std::vector<double>{1.0, 2.0, 6.0}));
}

TEST(Replicates, EqualReplicatesAreExact) {
  const double v = 0.1 + 0.2;
  const auto stats = ReduceReplicates({Result({{"m", v}}), Result({{"m", v}}), Result({{"m", v}})});
  EXPECT_EQ(stats.at("m").mean, v);
  EXPECT_EQ(stats.at("m").std_error, 0.0);
}

TEST(Replicates, OneReplicateHasNoError) {
  const auto stats = ReduceReplicates({Result({{"strength", 4.5}, {"x", 1.0}})});
  EXPECT_DOUBLE_EQ(stats.at("strength").mean, 4.5);
  EXPECT_DOUBLE_EQ(stats.at("strength").std_error, 0.0);
  EXPECT_EQ(stats.at("x").unit, "1");
}

}  // namespace
}  // namespace fibrenet::optimizer
