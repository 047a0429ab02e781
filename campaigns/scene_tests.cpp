#include "campaigns/scene_tests.h"

#include <fmt/format.h>

namespace fibrenet::campaigns {

namespace {

using pipeline::LoadAxis;

// Keys every test table shares: the variant switches and the quasi-static control.
void ReadSwitches(TableReader& r, pipeline::MaterialSwitches& s) {
  s.bond_failure = r.Bool("bond_failure", true);
  s.viscoelastic = r.Bool("viscoelastic", true);
  s.maxwell_tau = r.Number("maxwell_tau_s", 0.0, Closed(0, 1e6), "s (0 = the network's)");
  const std::string friction = r.Choice("friction", "network", {"network", "on", "off"});
  if (friction != "network") s.friction = friction == "on";
}

void ReadQuasiStatic(TableReader& r, pipeline::QuasiStaticSettings& q) {
  q.mass_scale = r.Number("mass_scale", 0.0, Closed(0, 1e15), "(0 = automatic)");
  if (q.mass_scale > 0.0 && q.mass_scale < 1.0)
    r.Fail("mass_scale", fmt::format("{:g}: accepted 0 (automatic) or [1, 1e15]", q.mass_scale));
  q.loading_steps = r.Number("loading_steps", q.loading_steps, Closed(100, 1e8), "steps");
  q.bond_damping_ratio = r.Number("bond_damping_ratio", q.bond_damping_ratio, Closed(0, 1), "");
  q.drag_time_fraction =
      r.Number("drag_time_fraction", q.drag_time_fraction, Closed(0, 10), "of the loading time");
  q.local_damping = r.Number("local_damping", q.local_damping, ClosedOpen(0, 1), "(0 = off)");
  q.kinetic_work_tolerance =
      r.Number("kinetic_work_tolerance", q.kinetic_work_tolerance, OpenClosed(0, 1), "");
  q.time_step_safety =
      r.Number("time_step_safety", q.time_step_safety, OpenClosed(0, 1), "of dt_crit");
}

pipeline::TensileStage ReadTensile(TableReader& r) {
  pipeline::TensileStage t;
  const std::string direction = r.Choice("direction", "both", {"MD", "CD", "both"});
  if (direction == "MD") t.axes = {LoadAxis::kMD};
  if (direction == "CD") t.axes = {LoadAxis::kCD};
  pipeline::TensileSettings& s = t.settings;
  s.grip_length =
      r.Number("grip_length_mm", 0.0, Closed(0, 1000), "mm (0 = 10% of the cell)") * 1e-3;
  s.strain_rate = r.Number("strain_rate_per_s", s.strain_rate, OpenClosed(0, 1e4), "1/s");
  s.max_strain = r.Number("max_strain", s.max_strain, OpenClosed(0, 2), "");
  s.failure_drop = r.Number("failure_drop", s.failure_drop, Open(0, 1), "of the peak stress");
  const double cycle = r.Number("cycle_strain", 0.0, ClosedOpen(0, 2), "(0 = no cycle)");
  if (cycle > 0.0) s.cycle_strains = {cycle};
  s.modulus_window_lo =
      r.Number("modulus_window_lo", s.modulus_window_lo, ClosedOpen(0, 1), "of the peak");
  s.modulus_window_hi =
      r.Number("modulus_window_hi", s.modulus_window_hi, OpenClosed(0, 1), "of the peak");
  s.samples = static_cast<int>(r.Integer("samples", s.samples, 10, 100000));
  s.max_steps = r.Integer("max_steps", s.max_steps, 1, 10'000'000'000LL);
  ReadSwitches(r, s.switches);
  ReadQuasiStatic(r, s.quasi_static);
  r.Finish();
  if (cycle >= s.max_strain)
    r.Fail("cycle_strain",
           fmt::format("{:g} must be below max_strain = {:g}", cycle, s.max_strain));
  if (s.modulus_window_lo >= s.modulus_window_hi)
    r.Fail("modulus_window_lo", "must be below modulus_window_hi");
  return t;
}

pipeline::CompressionSettings ReadCompression(TableReader& r, pipeline::CompressionSettings c) {
  using Loading = pipeline::CompressionSettings::Loading;
  const bool was_stepped = c.loading == Loading::kStepped;
  c.loading = r.Choice("loading", was_stepped ? "stepped" : "continuous",
                       {"continuous", "stepped"}) == "stepped"
                  ? Loading::kStepped
                  : Loading::kContinuous;
  c.settle_max_steps = r.Integer("settle_max_steps", c.settle_max_steps, 0, 10'000'000'000LL);
  c.window_samples = static_cast<int>(r.Integer("window_samples", c.window_samples, 0, 1000));
  c.pressure_step_fraction = r.Number("pressure_step_fraction", c.pressure_step_fraction,
                                      OpenClosed(0, 10), "of the last rest's pressure");
  c.max_move_halvings =
      static_cast<int>(r.Integer("max_move_halvings", c.max_move_halvings, 0, 30));
  c.max_strain = r.Number("max_strain", c.max_strain, OpenClosed(0, 0.95), "");
  c.max_pressure =
      r.Number("max_pressure_kPa", c.max_pressure * 1e-3, Closed(0, 1e6), "kPa (0 = strain only)") *
      1e3;
  c.strain_rate = r.Number("strain_rate_per_s", c.strain_rate, OpenClosed(0, 1e5), "1/s");
  c.modulus_pressure_lo =
      r.Number("modulus_pressure_lo_kPa", c.modulus_pressure_lo * 1e-3, Closed(0, 1e5), "kPa") *
      1e3;
  c.modulus_pressure_hi =
      r.Number("modulus_pressure_hi_kPa", c.modulus_pressure_hi * 1e-3, OpenClosed(0, 1e5), "kPa") *
      1e3;
  c.min_speed_fraction = r.Number("min_speed_fraction", c.min_speed_fraction, OpenClosed(0, 1),
                                  "of the platen speed (1 = constant speed)");
  c.toe_kinetic_share = r.Number("toe_kinetic_share", c.toe_kinetic_share, OpenClosed(0, 1),
                                 "of the kinetic guard's tolerance");
  c.approach_speed_fraction = r.Number("approach_speed_fraction", c.approach_speed_fraction,
                                       Closed(0, 1), "of the platen speed (0 = no approach)");
  c.approach_pressure_fraction =
      r.Number("approach_pressure_fraction", c.approach_pressure_fraction, Closed(0, 1),
               "of modulus_pressure_lo_kPa");
  c.approach_taper = r.Bool("approach_taper", c.approach_taper);
  c.feedback_above_window = r.Bool("feedback_above_window", c.feedback_above_window);
  c.feedback_in_window = r.Bool("feedback_in_window", c.feedback_in_window);
  c.van_wyk_pressure_lo = r.Number("van_wyk_pressure_lo_kPa", c.van_wyk_pressure_lo * 1e-3,
                                   Closed(0, 1e6), "kPa (0 = 1% of the top fitted)") *
                          1e3;
  c.van_wyk_pressure_hi = r.Number("van_wyk_pressure_hi_kPa", c.van_wyk_pressure_hi * 1e-3,
                                   Closed(0, 1e6), "kPa (0 = up to the first bond failure)") *
                          1e3;
  c.residual_pressure_fraction = r.Number("residual_pressure_fraction",
                                          c.residual_pressure_fraction, Open(0, 1), "of the peak");
  c.samples = static_cast<int>(r.Integer("samples", c.samples, 10, 100000));
  c.attribution = r.Bool("attribution", c.attribution);
  c.max_steps = r.Integer("max_steps", c.max_steps, 1, 10'000'000'000LL);
  ReadSwitches(r, c.switches);
  ReadQuasiStatic(r, c.quasi_static);
  r.Finish();
  if (c.modulus_pressure_lo >= c.modulus_pressure_hi)
    r.Fail("modulus_pressure_lo_kPa", "must be below modulus_pressure_hi_kPa");
  if (c.feedback_in_window && !c.feedback_above_window)
    r.Fail("feedback_in_window", "needs feedback_above_window = true");
  if (c.van_wyk_pressure_hi > 0.0 && c.van_wyk_pressure_lo >= c.van_wyk_pressure_hi)
    r.Fail("van_wyk_pressure_lo_kPa", "must be below van_wyk_pressure_hi_kPa (or that 0)");
  if (c.approach_taper && !(c.approach_speed_fraction > c.min_speed_fraction))
    r.Fail("approach_taper", "needs approach_speed_fraction above min_speed_fraction");
  return c;
}

pipeline::SoftnessSettings ReadSoftness(TableReader& r, ReadContext& ctx) {
  pipeline::SoftnessSettings s;
  s.grid_pitch = r.Number("grid_pitch_um", 10, OpenClosed(0, 1000), "um") * 1e-6;
  s.probe_radius = r.Number("probe_radius_um", 100, Closed(0, 1e4), "um") * 1e-6;
  s.bending = r.Choice("bending", "pure", {"pure", "plate"}) == "plate"
                  ? pipeline::BendingMethod::kPlate
                  : pipeline::BendingMethod::kPureBending;
  pipeline::BendingSettings& b = s.bending_test;
  b.axis =
      r.Choice("bending_direction", "MD", {"MD", "CD"}) == "CD" ? LoadAxis::kCD : LoadAxis::kMD;
  b.max_curvature = r.Number("max_curvature_per_m", b.max_curvature, OpenClosed(0, 1e5), "1/m");
  b.fit_from = r.Number("fit_from", b.fit_from, ClosedOpen(0, 1), "of max_curvature_per_m");
  b.levels = static_cast<int>(r.Integer("curvature_levels", b.levels, 2, 100));
  b.ramp_steps = static_cast<int>(r.Integer("curvature_ramp_steps", b.ramp_steps, 0, 10'000'000));
  b.relax_steps = static_cast<int>(r.Integer("relax_steps", b.relax_steps, 10, 10'000'000));
  b.relax_tolerance = r.Number("relax_tolerance", b.relax_tolerance, Open(0, 1), "");
  b.relax_time_steps =
      r.Number("relax_time_steps", b.relax_time_steps, Closed(0, 1e6), "time steps (0 = no drag)");
  b.local_damping = r.Number("relax_local_damping", b.local_damping, ClosedOpen(0, 1), "(0 = off)");
  pipeline::SoftnessIndexSettings& i = s.index;
  i.w_bulk = r.Number("weight_bulk", i.w_bulk, Closed(0, 5), "");
  i.w_roughness = r.Number("weight_roughness", i.w_roughness, Closed(0, 5), "");
  i.w_bending = r.Number("weight_bending", i.w_bending, Closed(0, 5), "");
  i.bulk_ref_um_per_kPa =
      r.Number("bulk_ref_um_per_kPa", i.bulk_ref_um_per_kPa, OpenClosed(0, 1e6), "um/kPa");
  i.roughness_ref_um = r.Number("roughness_ref_um", i.roughness_ref_um, OpenClosed(0, 1e6), "um");
  i.bending_ref_mN_mm =
      r.Number("bending_ref_mN_mm", i.bending_ref_mN_mm, OpenClosed(0, 1e6), "mN mm");
  // [softness.compression]: the light compression for bulk softness when the scene has no
  // [compression] table; same keys as [compression].
  if (const toml::table* c = r.Table("compression")) {
    TableReader cr(c, r.Path("compression"), ctx);
    s.compression = ReadCompression(cr, s.compression);
  }
  r.Finish();
  return s;
}

}  // namespace

const std::vector<std::string>& SceneTestTables() {
  static const std::vector<std::string> tables = {"tensile", "compression", "softness"};
  return tables;
}

void ReadSceneTests(TableReader& root, ReadContext& ctx, pipeline::VirtualTestsSpec& tests) {
  if (const toml::table* t = root.Table("tensile")) {
    TableReader r(t, "tensile", ctx);
    tests.tensile = ReadTensile(r);
  }
  if (const toml::table* t = root.Table("compression")) {
    TableReader r(t, "compression", ctx);
    tests.compression = ReadCompression(r, pipeline::CompressionSettings{});
  }
  if (const toml::table* t = root.Table("softness")) {
    TableReader r(t, "softness", ctx);
    tests.softness = ReadSoftness(r, ctx);
  }
}

}  // namespace fibrenet::campaigns
