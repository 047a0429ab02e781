#include "optimizer/nlopt_driver.h"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/core/error.h"

namespace fibrenet::optimizer {
namespace {

ProblemValues Bowl(const std::vector<double>& u) {
  const double c[3] = {0.3, 0.7, 0.45};
  const double w[3] = {1.0, 2.0, 3.0};
  double f = 0.0;
  for (std::size_t i = 0; i < u.size(); ++i) f += w[i] * (u[i] - c[i]) * (u[i] - c[i]);
  return {f, {}};
}

struct Case {
  std::string name;
  int budget;
  double tolerance;  // on the objective reached (minimum 0)
};

// Names the case by its algorithm in test output (instead of its bytes).
void PrintTo(const Case& c, std::ostream* out) { *out << c.name; }

class EveryAlgorithm : public ::testing::TestWithParam<Case> {};

TEST_P(EveryAlgorithm, FindsTheBottomOfABowl) {
  const Case& c = GetParam();
  AlgorithmOptions options;
  options.name = c.name;
  options.seed = 3;
  StopCriteria stop;
  stop.max_evaluations = c.budget;
  stop.xtol_rel = 1e-6;
  stop.ftol_rel = 1e-10;
  const OptimiseResult r =
      Minimise(options, stop, {0.9, 0.1, 0.9}, 0, 0.0, &Bowl, [] { return false; });
  EXPECT_LE(r.value, c.tolerance) << r.status;
  EXPECT_LE(r.calls, c.budget);
  EXPECT_GT(r.calls, 0);
  EXPECT_FALSE(r.stopped);
}

INSTANTIATE_TEST_SUITE_P(
    NLopt, EveryAlgorithm,
    ::testing::Values(Case{"LN_COBYLA", 300, 1e-8}, Case{"LN_BOBYQA", 300, 1e-8},
                      Case{"LN_SBPLX", 600, 1e-8}, Case{"LN_NELDERMEAD", 600, 1e-8},
                      Case{"LN_NEWUOA_BOUND", 300, 1e-8}, Case{"LN_PRAXIS", 600, 1e-8},
                      Case{"GN_DIRECT", 600, 1e-3}, Case{"GN_DIRECT_L", 600, 1e-3},
                      Case{"GN_DIRECT_L_RAND", 600, 1e-3}, Case{"GN_ORIG_DIRECT", 600, 1e-3},
                      Case{"GN_ORIG_DIRECT_L", 600, 1e-3}, Case{"GN_CRS2_LM", 1500, 1e-4},
                      Case{"GN_ISRES", 3000, 1e-2}, Case{"GN_ESCH", 3000, 1e-2},
                      Case{"G_MLSL_LDS", 1500, 1e-6}, Case{"G_MLSL", 1500, 1e-6},
                      Case{"AUGLAG", 600, 1e-8}),
    [](const ::testing::TestParamInfo<Case>& info) { return info.param.name; });

// minimise u0 + u1 subject to u0 u1 >= 0.25: the optimum is u = (0.5, 0.5), value 1.
ProblemValues Hyperbola(const std::vector<double>& u) {
  return {u[0] + u[1], {0.25 - u[0] * u[1]}};
}

class ConstrainedAlgorithm : public ::testing::TestWithParam<std::string> {};

TEST_P(ConstrainedAlgorithm, MeetsAnInequality) {
  AlgorithmOptions options;
  options.name = GetParam();
  StopCriteria stop;
  stop.max_evaluations = 2000;
  stop.xtol_rel = 1e-7;
  stop.ftol_rel = 1e-10;
  const OptimiseResult r =
      Minimise(options, stop, {0.9, 0.9}, 1, 1e4, &Hyperbola, [] { return false; });
  const ProblemValues at = Hyperbola(r.u);
  EXPECT_LE(at.constraints[0], 1e-3) << r.status;
  EXPECT_NEAR(at.objective, 1.0, 5e-2) << r.status;
}

INSTANTIATE_TEST_SUITE_P(NLopt, ConstrainedAlgorithm,
                         ::testing::Values("LN_COBYLA", "AUGLAG", "LN_SBPLX", "LN_BOBYQA",
                                           "GN_ISRES"));

TEST(NloptDriver, StochasticRunsRepeatForOneSeed) {
  auto run = [](std::uint64_t seed) {
    std::vector<std::vector<double>> points;
    AlgorithmOptions options;
    options.name = "GN_CRS2_LM";
    options.seed = seed;
    StopCriteria stop;
    stop.max_evaluations = 60;
    Minimise(
        options, stop, {0.5, 0.5}, 0, 0.0,
        [&](const std::vector<double>& u) {
          points.push_back(u);
          return Bowl(u);
        },
        [] { return false; });
    return points;
  };
  EXPECT_EQ(run(11), run(11));
  EXPECT_NE(run(11), run(12));
}

TEST(NloptDriver, ProblemExceptionsComeBack) {
  struct Crash {};
  int calls = 0;
  AlgorithmOptions options;
  options.name = "LN_COBYLA";
  EXPECT_THROW(Minimise(
                   options, StopCriteria{}, {0.5, 0.5}, 1, 0.0,
                   [&](const std::vector<double>& u) {
                     if (++calls == 4) throw Crash{};
                     return Hyperbola(u);
                   },
                   [] { return false; }),
               Crash);
  EXPECT_EQ(calls, 4);
}

TEST(NloptDriver, CallerCanStop) {
  int calls = 0;
  AlgorithmOptions options;
  options.name = "LN_NELDERMEAD";
  const OptimiseResult r = Minimise(
      options, StopCriteria{}, {0.5, 0.5}, 0, 0.0,
      [&](const std::vector<double>& u) {
        ++calls;
        return Bowl(u);
      },
      [&] { return calls >= 3; });
  EXPECT_TRUE(r.stopped);
  EXPECT_EQ(r.calls, 3);
  EXPECT_EQ(r.status, "FORCED_STOP");
}

TEST(NloptDriver, RejectsUnknownNames) {
  AlgorithmOptions options;
  options.name = "LN_COBYLLA";
  try {
    Minimise(options, StopCriteria{}, {0.5}, 0, 0.0, &Bowl, [] { return false; });
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'LN_COBYLA'"), std::string::npos);
  }
  options.name = "AUGLAG";
  options.local = "GN_DIRECT";
  EXPECT_THROW(Minimise(options, StopCriteria{}, {0.5, 0.5}, 0, 0.0, &Bowl, [] { return false; }),
               InputError);
  EXPECT_NE(FindAlgorithm("G_MLSL_LDS"), nullptr);
  EXPECT_TRUE(FindAlgorithm("AUGLAG")->needs_local);
  EXPECT_EQ(FindAlgorithm("nope"), nullptr);
}

}  // namespace
}  // namespace fibrenet::optimizer
