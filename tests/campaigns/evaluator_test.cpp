#include "campaigns/evaluator.h"

#include <gtest/gtest.h>

#include "campaigns/analytic_evaluator.h"
#include "engine/core/error.h"

namespace fibrenet::campaigns {
namespace {

TEST(AnalyticEvaluator, QuadraticMetrics) {
  const Evaluator f = MakeEvaluator("analytic:quadratic");
  optimizer::Fidelity fidelity;
  fidelity.overrides = {{"analytic.noise", 0.0}, {"analytic.bias", 0.25}};
  const auto r = f({{"a", 2.0}, {"b", 0.5}}, fidelity, 3);
  ASSERT_TRUE(r.ok);
  EXPECT_DOUBLE_EQ(r.metrics.at("quadratic"), 1.0 + 0.25 + 0.25);
  EXPECT_DOUBLE_EQ(r.metrics.at("sum"), 2.5);
  EXPECT_DOUBLE_EQ(r.metrics.at("product"), 1.0);
  EXPECT_DOUBLE_EQ(r.metrics.at("noisy_quadratic"), r.metrics.at("quadratic"));
  EXPECT_EQ(r.units.at("sum"), "1");
}

TEST(AnalyticEvaluator, NoiseFollowsTheSeed) {
  const Evaluator f = MakeEvaluator("analytic:quadratic");
  const optimizer::Fidelity fidelity;
  const double a = f({{"x", 1.0}}, fidelity, 1).metrics.at("noisy_quadratic");
  EXPECT_EQ(a, f({{"x", 1.0}}, fidelity, 1).metrics.at("noisy_quadratic"));
  EXPECT_NE(a, f({{"x", 1.0}}, fidelity, 2).metrics.at("noisy_quadratic"));
  EXPECT_LT(std::abs(a), 0.1);
}

TEST(AnalyticEvaluator, FailuresAndBadOverrides) {
  const Evaluator f = MakeEvaluator("analytic:softstrong");
  optimizer::Fidelity fidelity;
  fidelity.overrides = {{"analytic.fail_above", 1.0}};
  EXPECT_THROW(f({{"a", 1.0}, {"b", 0.5}}, fidelity, 1), RunError);
  EXPECT_NO_THROW(f({{"a", 0.25}, {"b", 0.5}}, fidelity, 1));
  fidelity.overrides = {{"analytic.nosie", 1.0}};
  try {
    f({{"a", 1.0}, {"b", 0.5}}, fidelity, 1);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'analytic.noise'"), std::string::npos);
  }
  EXPECT_THROW(f({{"a", 1.0}}, {}, 1), InputError);  // needs two variables
  EXPECT_THROW(MakeEvaluator("analytic:nope"), InputError);
}

TEST(SceneEvaluator, AMissingSceneIsBadInput) {
  EXPECT_THROW(MakeEvaluator("/nonexistent/scenes/tissue.toml"), InputError);
}

}  // namespace
}  // namespace fibrenet::campaigns
