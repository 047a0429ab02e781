// The beam validation cases (engine/validation/{axial_torsion,cantilever,buckling_frequency}.cpp)
// and the elastica reference they use. Each case runs all its fidelities, as
// `fibrenet validate --case NAME` does; the default one must meet the tolerance of issue 2.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/validation/cases.h"
#include "engine/validation/elastica.h"

namespace fibrenet::validation {
namespace {

TEST(Elastica, ReproducesTabulatedTipDeflections) {
  // Bisshopp & Drucker (1945): alpha = 1 gives 0.30172 L down and 0.05643 L back; the
  // vertical deflection at alpha = 10 is 0.8106 L.
  const ElasticaTip one = SolveElastica(1.0);
  EXPECT_NEAR(one.vertical, 0.30172, 1e-5);
  EXPECT_NEAR(one.horizontal, 0.05643, 1e-5);
  const ElasticaTip ten = SolveElastica(10.0);
  EXPECT_NEAR(ten.vertical, 0.81061, 1e-5);
  EXPECT_NEAR(ten.horizontal, 0.55500, 1e-5);
}

TEST(Elastica, SmallLoadGivesLinearBeamTheory) {
  const double alpha = 1e-4;
  const ElasticaTip tip = SolveElastica(alpha);
  EXPECT_NEAR(tip.vertical, alpha / 3.0, 1e-8 * alpha);   // P L^3 / (3 E I)
  EXPECT_NEAR(tip.tip_angle, alpha / 2.0, 1e-8 * alpha);  // P L^2 / (2 E I)
  EXPECT_EQ(SolveElastica(0.0).vertical, 0.0);
}

TEST(Elastica, SatisfiesFirstIntegral) {
  // theta'^2 / 2 = alpha (sin theta_tip - sin theta) integrates in closed form to
  // x_tip^2 = 2 sin(theta_tip) / alpha, independent of the shooting.
  for (double alpha : {0.5, 1.0, 3.0, 10.0, 30.0}) {
    const ElasticaTip tip = SolveElastica(alpha);
    const double x_tip = 1.0 - tip.horizontal;
    EXPECT_NEAR(x_tip * x_tip, 2.0 * std::sin(tip.tip_angle) / alpha, 1e-9) << alpha;
    EXPECT_NEAR(tip.root_curvature, alpha * x_tip, 1e-9 * alpha) << alpha;
    EXPECT_GT(tip.tip_angle, 0.0);
    EXPECT_LT(tip.tip_angle, 0.5 * 3.14159265358979);
  }
}

TEST(Elastica, ConvergesWithSteps) {
  const ElasticaTip coarse = SolveElastica(10.0, 100), fine = SolveElastica(10.0, 20000);
  EXPECT_NEAR(coarse.vertical, fine.vertical, 1e-7);
  EXPECT_NEAR(coarse.horizontal, fine.horizontal, 1e-7);
}

TEST(Elastica, ExtensibleVariantStretchesTheBeam) {
  const ElasticaTip rigid = SolveElastica(10.0);
  const ElasticaTip same = SolveExtensibleElastica(10.0, 0.0);
  EXPECT_EQ(rigid.vertical, same.vertical);
  // lambda = P / (E A) of the paper's fibre at alpha = 10, L = 1 mm: 10 R^2 / (4 L^2).
  const ElasticaTip stretched = SolveExtensibleElastica(10.0, 6.4e-4);
  EXPECT_NEAR(stretched.vertical, 0.81112, 1e-5);
  EXPECT_GT(stretched.vertical, rigid.vertical);
}

TEST(Elastica, RejectsOutOfRangeInput) {
  EXPECT_THROW(SolveExtensibleElastica(1.0, -0.1), InputError);
  EXPECT_THROW(SolveElastica(-1.0), InputError);
  EXPECT_THROW(SolveElastica(1.0, 2), InputError);
}

struct BeamCase {
  const char* name;
  CaseRunner run;
  double issue_tolerance;  // at the default fidelity (issue 2)
  // Exact for every chain (linear springs in series, Hermite beam element at the nodes):
  // the error is the relaxation's only. Otherwise the error shrinks as n grows.
  bool exact;
};

void PrintTo(const BeamCase& c, std::ostream* os) { *os << c.name; }

class BeamCases : public testing::TestWithParam<BeamCase> {};

TEST_P(BeamCases, EveryFidelityMeetsItsToleranceAndTheDefaultTheIssues) {
  const BeamCase& c = GetParam();
  const std::vector<CaseResult> results = c.run();
  ASSERT_GE(results.size(), 3u);
  int defaults = 0;
  // Error by particle count, for the rows at the default's time-step safety factor.
  std::map<int, double> error_by_n;
  double default_safety = 0.0;
  for (const CaseResult& r : results) {
    if (!r.is_default) continue;
    ++defaults;
    int n = 0;
    ASSERT_EQ(std::sscanf(r.fidelity.c_str(), "n=%d safety=%lf", &n, &default_safety), 2);
    EXPECT_NE(r.fidelity.find("(default)"), std::string::npos);
    EXPECT_LE(r.tolerance, c.issue_tolerance);
  }
  EXPECT_EQ(defaults, 1);
  for (const CaseResult& r : results) {
    SCOPED_TRACE(r.fidelity + ": " + r.detail);
    EXPECT_EQ(r.name, c.name);
    EXPECT_TRUE(r.passed);
    EXPECT_LE(r.error, r.tolerance);
    EXPECT_GT(r.wall_s, 0.0);
    EXPECT_FALSE(r.detail.empty());
    if (c.exact) {
      EXPECT_LT(r.error, 1e-5);
    }
    int n = 0;
    double safety = 0.0;
    ASSERT_EQ(std::sscanf(r.fidelity.c_str(), "n=%d safety=%lf", &n, &safety), 2);
    if (safety == default_safety) error_by_n[n] = r.error;
  }
  ASSERT_GE(error_by_n.size(), 3u);
  if (c.exact) return;
  double previous = 1.0;
  for (const auto& [n, error] : error_by_n) {
    EXPECT_LT(error, previous) << "n = " << n;
    previous = error;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Validation, BeamCases,
    testing::Values(BeamCase{"axial_stretch", &AxialStretch, 1e-3, true},
                    BeamCase{"torsion", &Torsion, 1e-3, true},
                    BeamCase{"cantilever_small", &CantileverSmall, 1e-2, true},
                    BeamCase{"cantilever_elastica", &CantileverElastica, 1e-2, false},
                    BeamCase{"euler_buckling", &EulerBuckling, 2e-2, false},
                    BeamCase{"bending_frequency", &BendingFrequency, 2e-2, false}),
    [](const testing::TestParamInfo<BeamCase>& info) { return std::string(info.param.name); });

TEST(BeamCases, AreRegisteredUnderTheirNames) {
  for (const char* name : {"axial_stretch", "torsion", "cantilever_small", "cantilever_elastica",
                           "euler_buckling", "bending_frequency"}) {
    bool found = false;
    for (const CaseEntry& e : Cases()) found = found || std::string(e.name) == name;
    EXPECT_TRUE(found) << name;
  }
}

}  // namespace
}  // namespace fibrenet::validation
