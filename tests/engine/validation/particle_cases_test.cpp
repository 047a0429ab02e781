// The particle and bond validation cases (engine/validation/{rigid_conservation,
// contact_cases,body_bond_cases}.cpp). Each case runs all its fidelities, as
// `fibrenet validate --case NAME` does; every fidelity must meet its tolerance, and the
// default one the figure of issue 2 (or the one the case documents).
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/validation/cases.h"

namespace fibrenet::validation {
namespace {

struct ParticleCase {
  const char* name;
  CaseRunner run;
  double default_tolerance;  // the most the default fidelity may allow
};

void PrintTo(const ParticleCase& c, std::ostream* os) { *os << c.name; }

class ParticleCases : public testing::TestWithParam<ParticleCase> {};

TEST_P(ParticleCases, DefaultFidelityPassesAndEveryFidelityMeetsItsTolerance) {
  const ParticleCase& c = GetParam();
  const std::vector<CaseResult> results = c.run();
  ASSERT_GE(results.size(), 3u);
  int defaults = 0;
  for (const CaseResult& r : results) {
    SCOPED_TRACE(r.fidelity + ": " + r.detail);
    EXPECT_EQ(r.name, c.name);
    EXPECT_TRUE(r.passed);
    EXPECT_LE(r.error, r.tolerance);
    EXPECT_GE(r.error, 0.0);
    EXPECT_GT(r.wall_s, 0.0);
    EXPECT_FALSE(r.detail.empty());
    if (!r.is_default) continue;
    ++defaults;
    EXPECT_NE(r.fidelity.find("(default)"), std::string::npos);
    EXPECT_LE(r.tolerance, c.default_tolerance);
  }
  EXPECT_EQ(defaults, 1);
}

INSTANTIATE_TEST_SUITE_P(
    Validation, ParticleCases,
    testing::Values(ParticleCase{"rigid_motion", &RigidMotion, 1e-6},
                    ParticleCase{"conservation", &Conservation, 1e-6},
                    ParticleCase{"van_wyk_compression", &VanWykCompression, 1e-3},
                    ParticleCase{"restitution", &Restitution, 0.03},
                    ParticleCase{"friction_incline", &FrictionIncline, 0.01},
                    ParticleCase{"drag_terminal_velocity", &DragTerminalVelocity, 1e-6},
                    ParticleCase{"maxwell_relaxation", &MaxwellRelaxation, 0.01},
                    ParticleCase{"hill_criterion", &HillCriterion, 1.001e-3}),
    [](const testing::TestParamInfo<ParticleCase>& info) { return std::string(info.param.name); });

TEST(ParticleCases, AreRegisteredUnderTheirNames) {
  for (const char* name : {"rigid_motion", "conservation", "van_wyk_compression", "restitution",
                           "friction_incline", "drag_terminal_velocity", "maxwell_relaxation",
                           "hill_criterion"}) {
    bool found = false;
    for (const CaseEntry& e : Cases()) found = found || std::string(e.name) == name;
    EXPECT_TRUE(found) << name;
  }
}

}  // namespace
}  // namespace fibrenet::validation
