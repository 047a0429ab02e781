// Scene files: the example scenes load; errors name file, key and accepted range;
// overrides by dotted path work and reject unknown paths.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "campaigns/scene.h"
#include "engine/core/error.h"
#include "engine/pipeline/creping.h"

namespace fibrenet::campaigns {
namespace {

const std::string kScenes = FIBRENET_SCENES_DIR;

const char* kMinimal = R"(
seed = 3
[cell]
size_x_mm = 1.0
size_y_mm = 1.0
basis_weight_gsm = 20
[fibres]
length_mm = 0.5
[forming]
consistency_percent = 1.0
[pressing]
target_thickness_um = 150
[pressing.bonding]
)";

// The message of the InputError that `f` throws ("" if none).
template <class F>
std::string InputErrorOf(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SceneFile, EverySceneInTheFolderLoadsAndValidates) {
  int scenes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kScenes)) {
    if (entry.path().extension() != ".toml") continue;
    EXPECT_EQ(LoadScene(entry.path().string()).Validate(), "") << entry.path();
    ++scenes;
  }
  EXPECT_GE(scenes, 8);
}

TEST(SceneFile, ExampleScenesLoad) {
  for (const char* name : {"generic-tissue.toml", "generic-tissue-10mm.toml", "tiny.toml"}) {
    const pipeline::PipelineSpec spec = LoadScene(kScenes + "/" + name);
    EXPECT_EQ(spec.Validate(), "") << name;
    EXPECT_TRUE(spec.pressing.has_value()) << name;
  }
  const pipeline::PipelineSpec tissue = LoadScene(kScenes + "/generic-tissue.toml");
  EXPECT_GE(tissue.sheet.Lx, 2.5e-3);
  EXPECT_DOUBLE_EQ(tissue.sheet.basis_weight, 0.020);
  EXPECT_DOUBLE_EQ(tissue.sheet.fibres.length.Mean(), 1.92e-3);
  EXPECT_DOUBLE_EQ(tissue.pressing->target_thickness, 200e-6);
  EXPECT_TRUE(tissue.tests.tensile && tissue.tests.compression && tissue.tests.softness);
  EXPECT_DOUBLE_EQ(LoadScene(kScenes + "/generic-tissue-10mm.toml").sheet.Lx, 10e-3);
}

TEST(SceneFile, UnitsAreConvertedToSI) {
  const pipeline::PipelineSpec s = ParseScene(kMinimal, "min.toml");
  EXPECT_EQ(s.seed, 3u);
  EXPECT_DOUBLE_EQ(s.sheet.Lx, 1e-3);
  EXPECT_DOUBLE_EQ(s.sheet.fibres.length.Mean(), 0.5e-3);
  EXPECT_DOUBLE_EQ(s.sheet.fibres.diameter.Mean(), 32e-6);
  EXPECT_DOUBLE_EQ(s.sheet.fibres.coarseness.Mean(), 25e-8);
  EXPECT_DOUBLE_EQ(s.forming.consistency, 0.01);
  EXPECT_DOUBLE_EQ(s.pressing->target_thickness, 150e-6);
  ASSERT_TRUE(s.pressing->bonding.has_value());
  EXPECT_DOUBLE_EQ(s.pressing->bonding->F_r0, 25e-3);
  EXPECT_DOUBLE_EQ(s.pressing->bonding->F_s0, 5e-3);
}

TEST(SceneFile, BondShareIsPerParticleUnlessTheSceneSaysPerCrossing) {
  EXPECT_EQ(ParseScene(kMinimal, "min.toml").pressing->bonding->share,
            pipeline::BondShare::kParticle);
  const std::string crossing = std::string(kMinimal) + "share = \"crossing\"\n";
  EXPECT_EQ(ParseScene(crossing, "c.toml").pressing->bonding->share,
            pipeline::BondShare::kCrossing);
  const std::string msg = InputErrorOf([] {
    ParseScene(std::string(kMinimal) + "share = \"fibre\"\n", "share.toml");
  });
  EXPECT_NE(msg.find("share.toml"), std::string::npos) << msg;
  EXPECT_NE(msg.find("pressing.bonding.share"), std::string::npos) << msg;
  EXPECT_NE(msg.find("crossing"), std::string::npos) << msg;
}

TEST(SceneFile, CompressionLoadsContinuouslyUnlessTheSceneSaysStepped) {
  const std::string table = std::string(kMinimal) + "[compression]\n";
  using Loading = pipeline::CompressionSettings::Loading;
  EXPECT_EQ(ParseScene(table, "c.toml").tests.compression->loading, Loading::kContinuous);
  const auto stepped = ParseScene(table +
                                      "loading = \"stepped\"\nsettle_max_steps = 3000\n"
                                      "window_samples = 12\npressure_step_fraction = 0.1\n"
                                      "max_move_halvings = 16\n",
                                  "s.toml");
  EXPECT_EQ(stepped.tests.compression->loading, Loading::kStepped);
  EXPECT_EQ(stepped.tests.compression->settle_max_steps, 3000);
  EXPECT_EQ(stepped.tests.compression->window_samples, 12);
  EXPECT_EQ(stepped.tests.compression->pressure_step_fraction, 0.1);
  EXPECT_EQ(stepped.tests.compression->max_move_halvings, 16);
  const std::string halvings =
      InputErrorOf([&] { ParseScene(table + "max_move_halvings = 31\n", "halvings.toml"); });
  EXPECT_NE(halvings.find("halvings.toml"), std::string::npos) << halvings;
  EXPECT_NE(halvings.find("compression.max_move_halvings"), std::string::npos) << halvings;
  EXPECT_NE(halvings.find("30"), std::string::npos) << halvings;
  const std::string msg =
      InputErrorOf([&] { ParseScene(table + "loading = \"pulsed\"\n", "loading.toml"); });
  EXPECT_NE(msg.find("loading.toml"), std::string::npos) << msg;
  EXPECT_NE(msg.find("compression.loading"), std::string::npos) << msg;
  EXPECT_NE(msg.find("stepped"), std::string::npos) << msg;
}

TEST(SceneFile, DistributionsAreRead) {
  const std::string text = std::string(kMinimal) + R"(
[fibres.coarseness_mg_per_100m]
distribution = "uniform"
min = 16
max = 35
)";
  // A distribution as a sub-table.
  EXPECT_EQ(ParseScene(text, "sub.toml").sheet.fibres.coarseness.kind,
            pipeline::DistributionKind::kUniform);
  // Distributions inline.
  const std::string inline_text = R"(
[fibres]
length_mm = { distribution = "normal", mean = 0.5, sd = 0.05, min = 0.3, max = 0.7 }
coarseness_mg_per_100m = { distribution = "uniform", min = 16, max = 35 }
bend_angle_deg = { distribution = "table", values = [0, 5, 10], weights = [1, 1, 2] }
[forming]
)";
  const pipeline::PipelineSpec s = ParseScene(inline_text, "d.toml");
  EXPECT_EQ(s.sheet.fibres.length.kind, pipeline::DistributionKind::kNormal);
  EXPECT_DOUBLE_EQ(s.sheet.fibres.length.min, 0.3e-3);
  EXPECT_DOUBLE_EQ(s.sheet.fibres.coarseness.max, 35e-8);
  EXPECT_EQ(s.sheet.fibres.bend_angle.values.size(), 3u);
}

TEST(SceneFile, UnknownKeyNamesFileKeyAndSuggestion) {
  const std::string msg = InputErrorOf([] {
    ParseScene("[fibres]\nlenght_mm = 1.0\n[forming]\n", "typo.toml");
  });
  EXPECT_NE(msg.find("typo.toml"), std::string::npos) << msg;
  EXPECT_NE(msg.find("fibres.lenght_mm"), std::string::npos) << msg;
  EXPECT_NE(msg.find("did you mean 'fibres.length_mm'"), std::string::npos) << msg;
  const std::string unit = InputErrorOf([] { ParseScene("[cell]\nsize_x = 1\n[forming]\n", "u.toml"); });
  EXPECT_NE(unit.find("did you mean 'cell.size_x_mm'"), std::string::npos) << unit;
}

TEST(SceneFile, WrongTypeNamesFileAndKey) {
  const std::string msg = InputErrorOf([] {
    ParseScene("[cell]\nbasis_weight_gsm = \"twenty\"\n[forming]\n", "type.toml");
  });
  EXPECT_NE(msg.find("type.toml"), std::string::npos) << msg;
  EXPECT_NE(msg.find("cell.basis_weight_gsm"), std::string::npos) << msg;
  EXPECT_NE(msg.find("expected a number"), std::string::npos) << msg;
  const std::string integer = InputErrorOf([] { ParseScene("seed = 1.5\n[forming]\n", "i.toml"); });
  EXPECT_NE(integer.find("expected an integer"), std::string::npos) << integer;
}

TEST(SceneFile, OutOfRangeNamesTheAcceptedRange) {
  const std::string msg = InputErrorOf([] {
    ParseScene("[forming]\nconsistency_percent = 150\n", "range.toml");
  });
  EXPECT_NE(msg.find("range.toml"), std::string::npos) << msg;
  EXPECT_NE(msg.find("forming.consistency_percent"), std::string::npos) << msg;
  EXPECT_NE(msg.find("(0, 100)"), std::string::npos) << msg;
  const std::string neg = InputErrorOf([] {
    ParseScene("[fibres]\ndiameter_um = -3\n[forming]\n", "neg.toml");
  });
  EXPECT_NE(neg.find("fibres.diameter_um"), std::string::npos) << neg;
  EXPECT_NE(neg.find("(0, 1000] um"), std::string::npos) << neg;
  // The coating's damping: a fraction of critical, within [0, 1].
  const std::string damping = InputErrorOf([] {
    ParseScene(std::string(kMinimal) + "[creping]\n[creping.adhesion]\ndamping_ratio = 1.5\n",
               "d.toml");
  });
  EXPECT_NE(damping.find("d.toml: creping.adhesion.damping_ratio"), std::string::npos) << damping;
  EXPECT_NE(damping.find("[0, 1]"), std::string::npos) << damping;
  EXPECT_DOUBLE_EQ(
      ParseScene(std::string(kMinimal) + "[creping]\n[creping.adhesion]\ndamping_ratio = 0.5\n",
                 "d.toml")
          .creping->adhesion.damping_ratio,
      0.5);
  // The blade's friction: unset, the contacts' mu; set, within [0, 10].
  const std::string blade_mu = InputErrorOf(
      [] { ParseScene(std::string(kMinimal) + "[creping]\nblade_friction_mu = 12\n", "b.toml"); });
  EXPECT_NE(blade_mu.find("b.toml: creping.blade_friction_mu"), std::string::npos) << blade_mu;
  EXPECT_NE(blade_mu.find("[0, 10]"), std::string::npos) << blade_mu;
  const auto blade_friction = [](const std::string& table) {
    return ParseScene(std::string(kMinimal) + "[creping]\n" + table, "b.toml")
        .creping->blade_friction_mu;
  };
  EXPECT_FALSE(blade_friction("").has_value());
  EXPECT_DOUBLE_EQ(blade_friction("blade_friction_mu = 0.8\n").value_or(-1.0), 0.8);
}

TEST(SceneFile, NonPhysicalCombinationsAreRejected) {
  // Fibres longer than the cell.
  const std::string longer = InputErrorOf([] {
    ParseScene("[cell]\nsize_x_mm = 1\nsize_y_mm = 1\n[fibres]\nlength_mm = 2\n[forming]\n", "l.toml");
  });
  EXPECT_NE(longer.find("fibres.length_mm"), std::string::npos) << longer;
  // Fibres thicker than long.
  const std::string thick = InputErrorOf([] {
    ParseScene("[fibres]\nlength_mm = 0.02\ndiameter_um = 32\n[forming]\n", "t.toml");
  });
  EXPECT_NE(thick.find("fibres.length_mm"), std::string::npos) << thick;
  // Both pressing targets.
  const std::string both = InputErrorOf([] {
    ParseScene("[forming]\n[pressing]\ntarget_thickness_um = 200\ntarget_pressure_kPa = 5\n", "b.toml");
  });
  EXPECT_NE(both.find("pressing.target_pressure_kPa"), std::string::npos) << both;
  // Two pressing speeds down to a multiple of a target thickness the scene does not set.
  const std::string fast = InputErrorOf([] {
    ParseScene("[forming]\n[pressing]\ntarget_pressure_kPa = 5\nfast_speed_m_per_s = 0.3\n",
               "f.toml");
  });
  EXPECT_NE(fast.find("pressing.fast_speed_m_per_s"), std::string::npos) << fast;
  EXPECT_NE(fast.find("target_thickness_um"), std::string::npos) << fast;
  // A tapered ZD approach without an approach.
  const std::string taper = InputErrorOf([] {
    ParseScene("[forming]\n[compression]\napproach_taper = true\n", "t.toml");
  });
  EXPECT_NE(taper.find("compression.approach_taper"), std::string::npos) << taper;
  // The feedback through the ZD window without the feedback above it.
  const std::string window = InputErrorOf([] {
    ParseScene("[forming]\n[compression]\nfeedback_in_window = true\n", "f.toml");
  });
  EXPECT_NE(window.find("compression.feedback_in_window"), std::string::npos) << window;
  // A van Wyk fit range upside down; a top of 0 (none) takes any bottom.
  const std::string range = InputErrorOf([] {
    ParseScene("[forming]\n[compression]\nvan_wyk_pressure_lo_kPa = 300\n"
               "van_wyk_pressure_hi_kPa = 250\n", "w.toml");
  });
  EXPECT_NE(range.find("compression.van_wyk_pressure_lo_kPa"), std::string::npos) << range;
  const pipeline::PipelineSpec open_top =
      ParseScene("[forming]\n[compression]\nvan_wyk_pressure_lo_kPa = 300\n", "w.toml");
  EXPECT_DOUBLE_EQ(open_top.tests.compression->van_wyk_pressure_lo, 3e5);
  EXPECT_EQ(open_top.tests.compression->van_wyk_pressure_hi, 0.0);
  // A creping run-in that ends beyond the leading end zone (0.2 x 1 mm), and one within it.
  const std::string run_in = InputErrorOf([] {
    ParseScene(std::string(kMinimal) + "[creping]\nrun_in_length_um = 250\n", "r.toml");
  });
  EXPECT_NE(run_in.find("r.toml: creping.run_in_length_um"), std::string::npos) << run_in;
  EXPECT_NE(run_in.find("accepted [0, 200] um"), std::string::npos) << run_in;
  EXPECT_DOUBLE_EQ(
      ParseScene(std::string(kMinimal) + "[creping]\nrun_in_length_um = 200\n", "r.toml")
          .creping->run_in_length,
      200e-6);
  // No forming stage.
  EXPECT_NE(InputErrorOf([] { ParseScene("seed = 1\n", "nf.toml"); }).find("[forming]"),
            std::string::npos);
}

// The scene reader writes each creping default again in the file's units: an empty table
// must give the engine's defaults, or a default changed in one place only goes unnoticed.
TEST(SceneFile, AnEmptyCrepingTableGivesTheEngineDefaults) {
  const pipeline::PipelineSpec spec =
      ParseScene(std::string(kMinimal) + "[creping]\n[creping.adhesion]\n", "c.toml");
  const pipeline::CrepingSettings& c = *spec.creping;
  const pipeline::CrepingSettings d;
  EXPECT_DOUBLE_EQ(c.yankee_speed, d.yankee_speed);
  EXPECT_DOUBLE_EQ(c.creping_angle, d.creping_angle);
  EXPECT_DOUBLE_EQ(c.crepe_ratio, d.crepe_ratio);
  EXPECT_DOUBLE_EQ(c.takeaway_height, d.takeaway_height);
  EXPECT_DOUBLE_EQ(c.takeaway_time, d.takeaway_time);
  EXPECT_DOUBLE_EQ(c.tip_clearance, d.tip_clearance);
  EXPECT_DOUBLE_EQ(c.run_in_length, d.run_in_length);
  EXPECT_DOUBLE_EQ(c.blade_hard_stiffness, d.blade_hard_stiffness);
  EXPECT_DOUBLE_EQ(c.fibre_hard_stiffness, d.fibre_hard_stiffness);
  EXPECT_EQ(c.blade_friction_mu, d.blade_friction_mu);
  EXPECT_DOUBLE_EQ(c.relax_mass_scale, d.relax_mass_scale);
  EXPECT_DOUBLE_EQ(c.relax_damping_time, d.relax_damping_time);
  EXPECT_DOUBLE_EQ(c.relax_bond_damping_ratio, d.relax_bond_damping_ratio);
  EXPECT_DOUBLE_EQ(c.relax_kinetic_ratio, d.relax_kinetic_ratio);
  EXPECT_DOUBLE_EQ(c.relax_energy_tolerance, d.relax_energy_tolerance);
  EXPECT_EQ(c.relax_max_steps, d.relax_max_steps);
  EXPECT_DOUBLE_EQ(c.end_zone_fraction, d.end_zone_fraction);
  EXPECT_DOUBLE_EQ(c.crepe_cutoff, d.crepe_cutoff);
  EXPECT_DOUBLE_EQ(c.crepe_shortest_wavelength, d.crepe_shortest_wavelength);
  EXPECT_DOUBLE_EQ(c.crepe_min_amplitude, d.crepe_min_amplitude);
  EXPECT_EQ(c.curve_samples, d.curve_samples);
  EXPECT_EQ(c.impact_frames, d.impact_frames);
  EXPECT_EQ(c.max_steps, d.max_steps);
  const pipeline::AdhesionSettings &a = c.adhesion, &ad = d.adhesion;
  EXPECT_DOUBLE_EQ(a.F_r0, ad.F_r0);
  EXPECT_DOUBLE_EQ(a.F_s0, ad.F_s0);
  EXPECT_DOUBLE_EQ(a.strength_cv, ad.strength_cv);
  EXPECT_DOUBLE_EQ(a.modulus, ad.modulus);
  EXPECT_DOUBLE_EQ(a.shear_modulus, ad.shear_modulus);
  EXPECT_DOUBLE_EQ(a.coating_thickness, ad.coating_thickness);
  EXPECT_DOUBLE_EQ(a.bond_radius_fraction, ad.bond_radius_fraction);
  EXPECT_DOUBLE_EQ(a.reach, ad.reach);
  EXPECT_DOUBLE_EQ(a.damping_ratio, ad.damping_ratio);
}

TEST(SceneFile, MissingFileAndSyntaxErrorsNameTheFile) {
  const std::string missing = InputErrorOf([] { LoadScene("/nonexistent/scene.toml"); });
  EXPECT_NE(missing.find("/nonexistent/scene.toml"), std::string::npos) << missing;
  const std::string syntax = InputErrorOf([] { ParseScene("[cell\n", "syntax.toml"); });
  EXPECT_NE(syntax.find("syntax.toml:1"), std::string::npos) << syntax;
}

TEST(SceneFile, OverrideByDottedPathSetsTheValue) {
  const pipeline::PipelineSpec s = ParseScene(
      kMinimal, "min.toml",
      {{"pressing.target_thickness_um", 120}, {"fibres.diameter_um", 20}, {"seed", 9},
       {"contact.friction_mu", 0.5}, {"pressing.bonding.F_r0_mN", 30}});
  EXPECT_DOUBLE_EQ(s.pressing->target_thickness, 120e-6);
  EXPECT_DOUBLE_EQ(s.sheet.fibres.diameter.Mean(), 20e-6);
  EXPECT_EQ(s.seed, 9u);
  EXPECT_DOUBLE_EQ(s.sheet.contact.mu, 0.5);
  EXPECT_DOUBLE_EQ(s.pressing->bonding->F_r0, 30e-3);
  // A distribution parameter.
  const std::string dist = R"(
[fibres]
length_mm = { distribution = "normal", mean = 0.5, sd = 0.05, min = 0.3, max = 0.7 }
[forming]
)";
  EXPECT_DOUBLE_EQ(ParseScene(dist, "d.toml", {{"fibres.length_mm.mean", 0.6}}).sheet.fibres.length.mean,
                   0.6e-3);
  // ParseOverride reads KEY=VALUE.
  const Override o = ParseOverride("pressing.target_thickness_um=150");
  EXPECT_EQ(o.path, "pressing.target_thickness_um");
  EXPECT_DOUBLE_EQ(o.value, 150.0);
  EXPECT_FALSE(o.flag.has_value());
}

// A switch is overridden by true or false, and only a switch.
TEST(SceneFile, OverrideSetsSwitches) {
  const std::string scene = std::string(kMinimal) + "[compression]\nfeedback_above_window = true\n";
  const Override off = ParseOverride("compression.feedback_above_window=false");
  ASSERT_TRUE(off.flag.has_value());
  EXPECT_FALSE(*off.flag);
  EXPECT_FALSE(ParseScene(scene, "s.toml", {off}).tests.compression->feedback_above_window);
  // A switch the scene does not write takes the override too.
  const Override on = ParseOverride("compression.attribution=true");
  EXPECT_TRUE(ParseScene(scene, "s.toml", {on}).tests.compression->attribution);
  const std::string number = InputErrorOf([&] {
    ParseScene(scene, "s.toml", {ParseOverride("compression.feedback_above_window=1")});
  });
  EXPECT_NE(number.find("accepted: true or false"), std::string::npos) << number;
  const std::string flag = InputErrorOf([&] {
    ParseScene(scene, "s.toml", {ParseOverride("compression.max_strain=true")});
  });
  EXPECT_NE(flag.find("compression.max_strain"), std::string::npos) << flag;
  EXPECT_NE(flag.find("expected a number"), std::string::npos) << flag;
  // A number the scene writes is not turned into a switch either.
  const std::string written = InputErrorOf([&] {
    ParseScene(scene, "s.toml", {ParseOverride("pressing.target_thickness_um=false")});
  });
  EXPECT_NE(written.find("not a switch"), std::string::npos) << written;
}

TEST(SceneFile, OverrideRejectsUnknownPathsAndBadValues) {
  const std::string unknown = InputErrorOf([] {
    ParseScene(kMinimal, "min.toml", {{"pressing.target_thicknes_um", 150}});
  });
  EXPECT_NE(unknown.find("pressing.target_thicknes_um"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("did you mean 'pressing.target_thickness_um'"), std::string::npos) << unknown;
  const std::string table = InputErrorOf([] { ParseScene(kMinimal, "min.toml", {{"foo.bar", 1}}); });
  EXPECT_NE(table.find("unknown scene table 'foo'"), std::string::npos) << table;
  const std::string range = InputErrorOf([] {
    ParseScene(kMinimal, "min.toml", {{"pressing.target_thickness_um", -5}});
  });
  EXPECT_NE(range.find("(override)"), std::string::npos) << range;
  EXPECT_NE(range.find("out of range"), std::string::npos) << range;
  const std::string stage = InputErrorOf([] {
    ParseScene("[forming]\n", "ns.toml", {{"pressing.target_thickness_um", 150}});
  });
  EXPECT_NE(stage.find("cannot enable a stage"), std::string::npos) << stage;
  const std::string fixed = InputErrorOf([] {
    ParseScene(kMinimal, "min.toml", {{"fibres.length_mm.mean", 0.6}});
  });
  EXPECT_NE(fixed.find("fibres.length_mm"), std::string::npos) << fixed;
  EXPECT_NE(InputErrorOf([] { ParseOverride("seed"); }), "");
  EXPECT_NE(InputErrorOf([] { ParseOverride("seed=abc"); }), "");
}

}  // namespace
}  // namespace fibrenet::campaigns
