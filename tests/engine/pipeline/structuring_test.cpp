// Structuring on the tiny scene: an embossing plate and a through-air-drying fabric leave
// their pattern in the sheet (against the same measure on a flat-pressed sheet), the fabric
// deeper for a stronger air pressure, and bonds form in the structured state.
#include <gtest/gtest.h>

#include "engine/pipeline/pipeline.h"
#include "tests/engine/pipeline/tiny_spec.h"

namespace fibrenet::pipeline {
namespace {

using testing::TinySpec;

double Detail(const StageReport& stage, const std::string& name) {
  for (const auto& [key, value] : stage.details)
    if (key == name) return value;
  ADD_FAILURE() << "no detail " << name << " in stage " << stage.name;
  return 0.0;
}

ReliefPattern Pattern(double height) {
  ReliefPattern p;
  p.pitch = 300e-6;
  p.size = 180e-6;
  p.height = height;
  p.flank = 60e-6;
  return p;
}

// Pressing to a land gap of 120 um with a plate that is flat, or carries 70 um bosses.
PipelineReport Press(bool emboss) {
  PipelineSpec spec = TinySpec();
  spec.pressing->target_thickness = 120e-6;
  spec.pressing->control = ThicknessControl::kPlate;
  if (emboss) spec.pressing->emboss = Pattern(70e-6);
  return RunPipeline(spec, Progress{});
}

TEST(Embossing, BossesPressTheirPatternIntoTheSheet) {
  const PipelineReport embossed = Press(true);
  const PipelineReport flat = Press(false);
  ASSERT_EQ(embossed.stages.at(1).name, "pressing");
  const double imprint = Detail(embossed.stages[1], "imprint_um");
  // The same measure on the flat-pressed sheet: the pattern-free noise of this small cell.
  const double noise = Imprint(flat.network.world, *MakeRelief(Pattern(70e-6), flat.network.world.cell, 1.0)) * 1e6;
  EXPECT_GT(imprint, noise + 5.0);
  // Fibres 0.4 mm long bridge the 180 um bosses: the sheet takes a fraction of their height.
  EXPECT_LT(imprint, 70.0);
  EXPECT_NEAR(imprint, Detail(embossed.stages[1], "imprint_at_hold_um"), 0.5 * imprint);
  EXPECT_GT(Detail(embossed.stages[1], "bonds_formed"), 0.0);
  EXPECT_NEAR(embossed.Final().basis_weight_gsm, embossed.stages[0].metrics.basis_weight_gsm, 1e-9);
  EXPECT_EQ(embossed.network.CheckInvariants(), "");
}

PipelineReport Dry(double pressure) {
  PipelineSpec spec = TinySpec();
  spec.pressing.reset();
  ThroughAirSettings t;
  t.fabric = Pattern(80e-6);
  t.pressure = pressure;
  // Wet fibres soft enough to bend into 180 um pockets: a 0.4 mm fibre at the dry stiffness
  // sags well under a micrometre there (deflection ~ q L^4 / EI).
  t.wet_stiffness_scale = 1e-4;
  t.mass_scale = 100;
  t.damping_time = 30e-6;
  t.settle_kinetic_ratio = 1e-3;
  t.bonding = BondingSettings{};
  spec.through_air = t;
  return RunPipeline(spec, Progress{});
}

TEST(ThroughAir, AirMouldsTheWebIntoTheFabricDeeperAtHigherPressure) {
  const PipelineReport weak = Dry(2e3);
  const PipelineReport strong = Dry(20e3);
  ASSERT_EQ(strong.stages.at(1).name, "through_air");
  const double moulded = Detail(strong.stages[1], "imprint_moulded_um");
  const double kept = Detail(strong.stages[1], "imprint_um");
  EXPECT_GT(moulded, 0.3 * 80.0);  // drawn well into the 80 um pockets
  EXPECT_LT(moulded, 80.0 + 32.0);
  // Bonds formed in the moulded state keep most of the shape after the air stops.
  EXPECT_GT(kept, 0.5 * moulded);
  EXPECT_LE(kept, moulded * 1.05);
  EXPECT_GT(Detail(strong.stages[1], "bonds_formed"), 0.0);
  EXPECT_GT(moulded, Detail(weak.stages[1], "imprint_moulded_um") + 5.0);
  EXPECT_NEAR(strong.Final().basis_weight_gsm, strong.stages[0].metrics.basis_weight_gsm, 1e-9);
  EXPECT_EQ(strong.network.CheckInvariants(), "");
  for (const StageReport& s : strong.stages) EXPECT_TRUE(s.warnings.empty()) << s.warnings.at(0);
}

}  // namespace
}  // namespace fibrenet::pipeline
