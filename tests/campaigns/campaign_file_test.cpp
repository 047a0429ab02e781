#include "campaigns/campaign_file.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "campaigns/campaign_check.h"
#include "engine/core/error.h"

namespace fibrenet::campaigns {
namespace {

const char* kFull = R"(
name = "soft-strong"
base_scene = "analytic:softstrong"
seed = 42
replicates = 2

[[variables]]
key = "fibres.length_mm"
lower = 0.5
upper = 3
start = 1.5

[[variables]]
key = "pressing.target_thickness_um"
lower = 50.0
upper = 400.0
log = true

[[variables]]
key = "fibres.particles_per_fibre"
lower = 4
upper = 12
integer = true

[goals]
minimise = "basis_weight"
constraint_weight = 50
failure_penalty = 99

[goals.constraints]
softness_index = { min = 0.7 }
tensile_strength = { min = 80, max = 300, scale = 10 }

[algorithm]
name = "AUGLAG"
local = "LN_SBPLX"
initial_step = 0.2
population = 12

[budget]
max_evaluations = 60
max_wall_s = 600
xtol_rel = 1e-3
ftol_rel = 1e-5
ftol_abs = 1e-9

[[fidelity]]
name = "coarse"
replicates = 1
[fidelity.overrides]
analytic.bias = 0.5
"analytic.noise" = 0

[[fidelity]]
name = "fine"
top = 3

[doe]
method = "lhs"
points = 12
seed = 7
)";

const char* kMinimal = R"(
base_scene = "analytic:quadratic"
[[variables]]
key = "x"
lower = 0
upper = 2
[goals]
minimise = "quadratic"
[doe]
)";

CampaignSpec Parse(const std::string& text) { return ParseCampaign(text, "camp.toml", "/tmp"); }

// The message of the InputError that parsing `text` throws ("" if none).
std::string ErrorOf(const std::string& text) {
  try {
    Parse(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(CampaignFile, ReadsEverySection) {
  const CampaignSpec s = Parse(kFull);
  EXPECT_EQ(s.name, "soft-strong");
  EXPECT_EQ(s.base_scene, "analytic:softstrong");
  EXPECT_EQ(s.seed, 42u);
  ASSERT_EQ(s.space.size(), 3u);
  const auto& v = s.space.variables();
  EXPECT_EQ(v[0].key, "fibres.length_mm");
  EXPECT_EQ(v[0].start, 1.5);
  EXPECT_TRUE(v[1].log);
  EXPECT_TRUE(v[2].integer);
  EXPECT_EQ(s.goals.objective().kind, optimizer::ObjectiveKind::kMinimise);
  EXPECT_EQ(s.goals.objective().metric, "basis_weight");
  EXPECT_EQ(s.goals.ConstraintLabels(),
            (std::vector<std::string>{"softness_index >= 0.7", "tensile_strength >= 80",
                                      "tensile_strength <= 300"}));
  EXPECT_DOUBLE_EQ(s.goals.constraint_weight(), 50.0);
  EXPECT_EQ(s.failure_penalty, 99.0);
  ASSERT_TRUE(s.algorithm);
  EXPECT_EQ(s.algorithm->name, "AUGLAG");
  EXPECT_EQ(s.algorithm->local, "LN_SBPLX");
  EXPECT_DOUBLE_EQ(s.algorithm->initial_step, 0.2);
  EXPECT_EQ(s.algorithm->population, 12);
  EXPECT_EQ(s.algorithm->seed, 42u);
  EXPECT_EQ(s.stop.max_evaluations, 60);
  EXPECT_DOUBLE_EQ(s.max_wall_s, 600.0);
  EXPECT_DOUBLE_EQ(s.stop.xtol_rel, 1e-3);
  EXPECT_DOUBLE_EQ(s.stop.ftol_abs, 1e-9);
  ASSERT_EQ(s.fidelities.size(), 2u);
  EXPECT_EQ(s.fidelities[0].name, "coarse");
  EXPECT_EQ(s.fidelities[0].replicates, 1);
  EXPECT_EQ(s.fidelities[0].overrides,
            (std::map<std::string, double>{{"analytic.bias", 0.5}, {"analytic.noise", 0.0}}));
  EXPECT_EQ(s.fidelities[1].replicates, 2);  // the campaign's
  EXPECT_EQ(s.fidelities[1].top, 3);
  ASSERT_TRUE(s.doe);
  EXPECT_EQ(s.doe->method, optimizer::DoeMethod::kLatinHypercube);
  EXPECT_EQ(s.doe->points, 12);
  EXPECT_EQ(s.doe->seed, 7u);
  EXPECT_EQ(s.text, kFull);
  EXPECT_EQ(s.spec_hash.size(), 16u);
}

TEST(CampaignFile, MinimalCampaignGetsDefaults) {
  const CampaignSpec s = Parse(kMinimal);
  EXPECT_EQ(s.name, "camp");  // the file name
  EXPECT_EQ(s.seed, 1u);
  EXPECT_FALSE(s.algorithm);
  ASSERT_TRUE(s.doe);
  EXPECT_EQ(s.doe->method, optimizer::DoeMethod::kSobol);
  EXPECT_EQ(s.doe->points, 16);
  ASSERT_EQ(s.fidelities.size(), 1u);
  EXPECT_EQ(s.fidelities[0].name, "default");
  EXPECT_EQ(s.fidelities[0].replicates, 1);
  EXPECT_EQ(s.stop.max_evaluations, 100);
  EXPECT_EQ(s.max_wall_s, 0.0);
  EXPECT_FALSE(s.failure_penalty);
}

TEST(CampaignFile, UnknownKeysAreRejectedWithASuggestion) {
  std::string m = ErrorOf(Replace(kFull, "max_evaluations = 60", "max_evals = 60"));
  EXPECT_NE(m.find("camp.toml:"), std::string::npos) << m;
  EXPECT_NE(m.find("budget.max_evals: unknown key; did you mean 'max_evaluations'?"),
            std::string::npos)
      << m;
  m = ErrorOf(Replace(kFull, "replicates = 2", "replicate = 2"));
  EXPECT_NE(m.find("replicate: unknown key; did you mean 'replicates'?"), std::string::npos) << m;
  m = ErrorOf(Replace(kFull, "upper = 3\n", "upper = 3\nlogg = true\n"));
  EXPECT_NE(m.find("variables[0].logg: unknown key; did you mean 'log'?"), std::string::npos) << m;
  m = ErrorOf(Replace(kFull, "minimise = \"basis_weight\"", "minimize = \"basis_weight\""));
  EXPECT_NE(m.find("goals.minimize: unknown key; did you mean 'minimise'?"), std::string::npos)
      << m;
  m = ErrorOf(Replace(kFull, "{ min = 0.7 }", "{ minimum = 0.7 }"));
  EXPECT_NE(m.find("goals.constraints.softness_index.minimum: unknown key"), std::string::npos)
      << m;
}

TEST(CampaignFile, ErrorsNameFileLineKeyAndRange) {
  std::string m = ErrorOf(Replace(kFull, "max_evaluations = 60", "max_evaluations = 0"));
  const std::string before =
      std::string(kFull).substr(0, std::string(kFull).find("max_evaluations"));
  const auto line = std::count(before.begin(), before.end(), '\n') + 1;
  EXPECT_NE(m.find(fmt::format("camp.toml:{}: budget.max_evaluations: must be an integer >= 1; "
                               "got 0",
                               line)),
            std::string::npos)
      << m;
  m = ErrorOf(Replace(kFull, "lower = 0.5", "lower = \"small\""));
  EXPECT_NE(m.find("variables[0].lower: must be a number; got a string"), std::string::npos) << m;
  m = ErrorOf(Replace(kFull, "lower = 50.0", "lower = 500.0"));
  EXPECT_NE(m.find("lower < upper"), std::string::npos) << m;
  m = ErrorOf(Replace(kFull, "initial_step = 0.2", "initial_step = 2"));
  EXPECT_NE(m.find("algorithm.initial_step: must lie in (0, 1]"), std::string::npos) << m;
  m = ErrorOf(Replace(kFull, "lower = 4", "lower = 4.5"));
  EXPECT_NE(m.find("integer bounds"), std::string::npos) << m;
  m = ErrorOf(Replace(kFull, "max_wall_s = 600", "max_wall_s = -1"));
  EXPECT_NE(m.find("budget.max_wall_s: must be a finite number > 0"), std::string::npos) << m;
}

TEST(CampaignFile, AlgorithmNamesAreChecked) {
  std::string m = ErrorOf(Replace(kFull, "name = \"AUGLAG\"", "name = \"LN_COBYLLA\""));
  EXPECT_NE(m.find("algorithm.name: unknown algorithm 'LN_COBYLLA'; did you mean 'LN_COBYLA'?"),
            std::string::npos)
      << m;
  EXPECT_NE(m.find("GN_ESCH"), std::string::npos) << m;  // the accepted list
  m = ErrorOf(Replace(kFull, "local = \"LN_SBPLX\"", "local = \"GN_DIRECT\""));
  EXPECT_NE(m.find("algorithm.local: unknown local algorithm"), std::string::npos) << m;
  m = ErrorOf(Replace(kFull, "name = \"AUGLAG\"", "name = \"LN_COBYLA\""));
  EXPECT_NE(m.find("only AUGLAG and G_MLSL* take a local algorithm"), std::string::npos) << m;
  for (const char* name : {"LN_COBYLA", "LN_BOBYQA", "LN_SBPLX", "LN_NELDERMEAD", "GN_DIRECT_L",
                           "GN_CRS2_LM", "GN_ISRES", "GN_ESCH", "G_MLSL_LDS", "AUGLAG"}) {
    const std::string text =
        Replace(Replace(kFull, "name = \"AUGLAG\"", std::string("name = \"") + name + "\""),
                "local = \"LN_SBPLX\"\n", "");
    EXPECT_EQ(ErrorOf(text), "") << name;
  }
}

TEST(CampaignFile, GoalsNeedExactlyOneObjective) {
  std::string m = ErrorOf(Replace(kFull, "minimise = \"basis_weight\"", ""));
  EXPECT_NE(m.find("needs exactly one objective"), std::string::npos) << m;
  m = ErrorOf(Replace(kFull, "minimise = \"basis_weight\"",
                      "minimise = \"basis_weight\"\nmaximise = \"softness_index\""));
  EXPECT_NE(m.find("got 2"), std::string::npos) << m;
  const CampaignSpec t = Parse(Replace(kMinimal, "minimise = \"quadratic\"",
                                       "targets = { sum = 1.5, product = { value = 2, weight = 3, "
                                       "scale = 0.5 } }"));
  ASSERT_EQ(t.goals.objective().kind, optimizer::ObjectiveKind::kTargets);
  ASSERT_EQ(t.goals.objective().targets.size(), 2u);
  EXPECT_EQ(t.goals.objective().targets[0].metric, "product");
  EXPECT_DOUBLE_EQ(t.goals.objective().targets[0].weight, 3.0);
  EXPECT_EQ(t.goals.objective().targets[0].scale, 0.5);
  m = ErrorOf(Replace(kFull, "{ min = 0.7 }", "0.7"));
  EXPECT_NE(m.find("goals.constraints.softness_index: must be a table"), std::string::npos) << m;
}

TEST(CampaignFile, StructureIsChecked) {
  std::string m = ErrorOf(Replace(kMinimal, "[doe]", ""));
  EXPECT_NE(m.find("needs an [algorithm] table, a [doe] table, or both"), std::string::npos) << m;
  m = ErrorOf(Replace(kFull, "name = \"fine\"", "name = \"coarse\""));
  EXPECT_NE(m.find("fidelity[1].name: 'coarse' is used twice"), std::string::npos) << m;
  m = ErrorOf(Replace(kFull, "analytic.bias = 0.5", "fibres.length_mm = 1"));
  EXPECT_NE(m.find("is a design variable"), std::string::npos) << m;
  m = ErrorOf(Replace(kFull, "replicates = 1\n", "replicates = 1\ntop = 2\n"));
  EXPECT_NE(m.find("fidelity[0].top: the first level explores"), std::string::npos) << m;
  m = ErrorOf(Replace(kFull, "method = \"lhs\"", "method = \"sobl\""));
  EXPECT_NE(m.find("doe.method: unknown method 'sobl'; did you mean 'sobol'?"), std::string::npos)
      << m;
  m = ErrorOf(Replace(kMinimal, "analytic:quadratic", "analytic:quadratc"));
  EXPECT_NE(m.find("did you mean 'quadratic'?"), std::string::npos) << m;
  m = ErrorOf(Replace(kMinimal, "analytic:quadratic", "scenes/none.toml"));
  EXPECT_NE(m.find("base_scene: scene file '/tmp/scenes/none.toml' does not exist"),
            std::string::npos)
      << m;
  m = ErrorOf("base_scene = \"analytic:quadratic\"\n[goals\n");
  EXPECT_NE(m.find("camp.toml:2: TOML syntax error"), std::string::npos) << m;
  m = ErrorOf(Replace(kMinimal, "[[variables]]", "[[variable]]"));
  EXPECT_NE(m.find("variable: unknown key; did you mean 'variables'?"), std::string::npos) << m;
}

TEST(CampaignFile, HashIgnoresTheBudgetOnly) {
  const std::string h = Parse(kFull).spec_hash;
  EXPECT_EQ(Parse(Replace(kFull, "max_evaluations = 60", "max_evaluations = 90")).spec_hash, h);
  EXPECT_NE(Parse(Replace(kFull, "{ min = 0.7 }", "{ min = 0.75 }")).spec_hash, h);
  EXPECT_NE(Parse(Replace(kFull, "seed = 42", "seed = 43")).spec_hash, h);
}

TEST(CampaignFile, LoadsFilesAndResolvesScenesNextToThem) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("fibrenet_campaign_file_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir / "scenes");
  std::ofstream(dir / "scenes" / "tissue.toml") << "# a scene\n";
  std::ofstream(dir / "c.toml") << Replace(kMinimal, "analytic:quadratic", "scenes/tissue.toml");
  const CampaignSpec s = LoadCampaignFile((dir / "c.toml").string());
  EXPECT_EQ(s.base_scene, (dir / "scenes" / "tissue.toml").string());
  EXPECT_EQ(s.name, "c");
  // The scene's content is part of the campaign's identity.
  const std::string before = s.spec_hash;
  std::ofstream(dir / "scenes" / "tissue.toml") << "# another scene\n";
  EXPECT_NE(LoadCampaignFile((dir / "c.toml").string()).spec_hash, before);
  try {
    LoadCampaignFile((dir / "missing.toml").string());
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.toml: cannot read campaign file (no such file)"),
              std::string::npos)
        << e.what();
  }
  std::filesystem::remove_all(dir);
}

// The examples a user starts from must stay valid as the scene keys change: each one loads,
// and its design variables at their bounds and its fidelity levels' overrides are accepted by
// its base scene's reader.
TEST(CampaignFile, EveryExampleCampaignLoadsAndChecksAgainstItsScene) {
  int campaigns = 0;
  for (const auto& entry : std::filesystem::directory_iterator(FIBRENET_EXAMPLES_DIR)) {
    if (entry.path().extension() != ".toml") continue;
    EXPECT_NO_THROW(CheckAgainstBaseScene(LoadCampaignFile(entry.path().string())))
        << entry.path();
    ++campaigns;
  }
  EXPECT_GE(campaigns, 4);
}

}  // namespace
}  // namespace fibrenet::campaigns
