#include "optimizer/goals.h"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/core/error.h"
#include "optimizer/closest_match.h"

namespace fibrenet::optimizer {
namespace {

Goals MinimiseWeight() {
  Objective o;
  o.kind = ObjectiveKind::kMinimise;
  o.metric = "basis_weight";
  Constraint soft{"softness", 0.7, std::nullopt, std::nullopt};
  Constraint strong{"strength", 80.0, 300.0, 10.0};
  return Goals(o, {soft, strong}, 100.0);
}

TEST(Goals, MinimiseWithConstraints) {
  const Goals goals = MinimiseWeight();
  ASSERT_EQ(goals.validate(), "");
  EXPECT_EQ(goals.ConstraintLabels(),
            (std::vector<std::string>{"softness >= 0.7", "strength >= 80", "strength <= 300"}));
  EXPECT_EQ(goals.Metrics(), (std::vector<std::string>{"basis_weight", "softness", "strength"}));

  const GoalValues ok = goals.Evaluate({{"basis_weight", 20}, {"softness", 0.8}, {"strength", 90}});
  EXPECT_DOUBLE_EQ(ok.objective, 20.0);
  EXPECT_TRUE(ok.feasible);
  EXPECT_NEAR(ok.constraints[0], (0.7 - 0.8) / 0.7, 1e-15);
  EXPECT_NEAR(ok.constraints[1], (80.0 - 90.0) / 10.0, 1e-15);
  EXPECT_DOUBLE_EQ(goals.Merit(ok), 20.0);

  const GoalValues bad =
      goals.Evaluate({{"basis_weight", 15}, {"softness", 0.6}, {"strength", 75}});
  EXPECT_FALSE(bad.feasible);
  const double g0 = (0.7 - 0.6) / 0.7, g1 = (80.0 - 75.0) / 10.0;
  EXPECT_NEAR(bad.violation, g0 * g0 + g1 * g1, 1e-12);
  EXPECT_NEAR(goals.Merit(bad), 15.0 + 100.0 * (g0 * g0 + g1 * g1), 1e-9);
}

TEST(Goals, MaximiseStoresNegated) {
  Objective o;
  o.kind = ObjectiveKind::kMaximise;
  o.metric = "softness";
  const Goals goals(o, {}, 1e3);
  EXPECT_DOUBLE_EQ(goals.Evaluate({{"softness", 0.9}}).objective, -0.9);
}

TEST(Goals, DistanceToTargetsIsRelative) {
  Objective o;
  o.kind = ObjectiveKind::kTargets;
  o.targets = {{"a", 10.0, 1.0, std::nullopt}, {"b", 0.0, 4.0, 2.0}};
  const Goals goals(o, {}, 1e3);
  ASSERT_EQ(goals.validate(), "");
  const double expected = std::sqrt(0.1 * 0.1 + 4.0 * 0.5 * 0.5);
  EXPECT_NEAR(goals.Evaluate({{"a", 11.0}, {"b", 1.0}}).objective, expected, 1e-15);
  EXPECT_DOUBLE_EQ(goals.Evaluate({{"a", 10.0}, {"b", 0.0}}).objective, 0.0);
}

TEST(Goals, MissingMetricNamesTheClosestOne) {
  const Goals goals = MinimiseWeight();
  try {
    goals.Evaluate({{"basis_weight", 1}, {"softnes", 1}, {"strength", 1}});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("'softness'"), std::string::npos) << message;
    EXPECT_NE(message.find("did you mean 'softnes'"), std::string::npos) << message;
  }
}

TEST(Goals, ValidateRejectsBadGoals) {
  Objective o;
  o.metric = "m";
  EXPECT_NE(Goals(o, {{"c", std::nullopt, std::nullopt, std::nullopt}}, 1.0).validate(), "");
  EXPECT_NE(Goals(o, {{"c", 2.0, 1.0, std::nullopt}}, 1.0).validate(), "");
  EXPECT_NE(Goals(o, {{"c", 1.0, std::nullopt, -1.0}}, 1.0).validate(), "");
  EXPECT_NE(Goals(o, {}, -1.0).validate(), "");
  Objective t;
  t.kind = ObjectiveKind::kTargets;
  EXPECT_NE(Goals(t, {}, 1.0).validate(), "");
}

TEST(FailurePenalty, WorstPlusSpread) {
  FailurePenalty p;
  EXPECT_DOUBLE_EQ(p.Value(), FailurePenalty::kNoHistory);
  p.Observe(3.0);
  EXPECT_DOUBLE_EQ(p.Value(), 4.0);  // worst 3 + max(1, 0)
  p.Observe(-7.0);
  EXPECT_DOUBLE_EQ(p.Value(), 13.0);  // worst 3 + spread 10
  p.Observe(std::nan(""));
  EXPECT_DOUBLE_EQ(p.Value(), 13.0);
  FailurePenalty fixed(50.0);
  fixed.Observe(1e6);
  EXPECT_DOUBLE_EQ(fixed.Value(), 50.0);
}

TEST(ClosestMatch, SuggestsTyposAndPrefixes) {
  const std::vector<std::string> keys = {"max_evaluations", "max_wall_s", "xtol_rel"};
  EXPECT_EQ(ClosestMatch("max_evals", keys), "max_evaluations");
  EXPECT_EQ(ClosestMatch("xtol_rl", keys), "xtol_rel");
  EXPECT_EQ(ClosestMatch("colour", keys), "");
  EXPECT_EQ(DidYouMean("max_wall", keys), "; did you mean 'max_wall_s'?");
}

}  // namespace
}  // namespace fibrenet::optimizer
