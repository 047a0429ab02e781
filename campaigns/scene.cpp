#include "campaigns/scene.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include <fmt/format.h>

#include "campaigns/scene_tests.h"
#include "campaigns/table_reader.h"
#include "engine/core/error.h"
#include "optimizer/closest_match.h"

namespace fibrenet::campaigns {

namespace {

using pipeline::PipelineSpec;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kDeg = 3.14159265358979323846 / 180.0;

// Tables an override may create when the file leaves them out (they only hold settings
// with defaults); stage tables are never created by an override.
const std::vector<std::string> kSettingTables = {"cell", "fidelity", "fibres", "contact",
                                                 "metrics", "forming"};
const std::vector<std::string> kRootKeys = {"seed",    "cell",     "fidelity", "fibres",
                                            "contact", "forming",  "pressing", "through_air",
                                            "creping", "metrics",
                                            "tensile", "compression", "softness"};

std::vector<std::string> Split(const std::string& path) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(path);
  while (std::getline(in, part, '.')) parts.push_back(part);
  if (!path.empty() && path.back() == '.') parts.push_back("");
  return parts;
}

void ApplyOverride(toml::table& root, const Override& o, const std::string& file) {
  auto fail = [&](const std::string& what) {
    throw InputError(fmt::format("{}: override '{}': {}", file, o.path, what));
  };
  const std::vector<std::string> parts = Split(o.path);
  if (parts.empty()) fail("empty key path");
  for (const auto& p : parts)
    if (p.empty()) fail("empty component in the dotted key path");
  if (!o.flag && !std::isfinite(o.value))
    fail(fmt::format("{} is not accepted; accepted: a finite number in the key's range", o.value));
  toml::table* t = &root;
  std::string prefix;
  for (std::size_t k = 0; k + 1 < parts.size(); ++k) {
    const std::string& c = parts[k];
    prefix = prefix.empty() ? c : prefix + "." + c;
    toml::node* n = t->get(c);
    if (!n) {
      const bool setting_table =
          std::find(kSettingTables.begin(), kSettingTables.end(), c) != kSettingTables.end();
      if (k > 0)
        fail(
            fmt::format("the scene has no [{}] table{}", prefix,
                        prefix == "pressing.bonding" ? ": an override cannot enable bonding" : ""));
      if (c == "pressing" || c == "through_air" || c == "creping" ||
          std::find(SceneTestTables().begin(), SceneTestTables().end(), c) !=
              SceneTestTables().end())
        fail(fmt::format("the scene has no [{}] table: an override cannot enable a stage", c));
      if (!setting_table) {
        const std::string near = optimizer::ClosestMatch(c, kRootKeys);
        fail(fmt::format("unknown scene table '{}'{}", c,
                         near.empty() ? "" : fmt::format("; did you mean '{}'?", near)));
      }
      t->insert(c, toml::table{});
      n = t->get(c);
    }
    if (!n->is_table())
      fail(fmt::format("'{}' is a single value, not a table (a fixed value has no '{}')", prefix,
                       parts[k + 1]));
    t = n->as_table();
  }
  const std::string& leaf = parts.back();
  const toml::node* old = t->get(leaf);
  if (old && old->is_table())
    fail(fmt::format("'{}' is a table; override one of its numbers (e.g. '{}.mean')", o.path,
                     o.path));
  if (o.flag) {
    if (old && !old->is_boolean())
      fail("the key is not a switch; accepted: a number (true and false set switches)");
    t->insert_or_assign(leaf, *o.flag);
    return;
  }
  if (old && old->is_boolean())
    fail("the key is a switch; accepted: true or false");
  if (old && !old->is_number())
    fail("the key holds a non-numeric value; only numbers and switches can be overridden");
  const bool integral = std::nearbyint(o.value) == o.value && std::abs(o.value) < 9e15;
  if ((!old || old->is_integer()) && integral)
    t->insert_or_assign(leaf, static_cast<std::int64_t>(o.value));
  else
    t->insert_or_assign(leaf, o.value);
}

pipeline::FibreSpec ReadFibres(TableReader& r) {
  pipeline::FibreSpec f;
  f.length = r.Dist("length_mm", 1.92, OpenClosed(0, 100), "mm").Scaled(1e-3);
  f.diameter = r.Dist("diameter_um", 32, OpenClosed(0, 1000), "um").Scaled(1e-6);
  f.coarseness = r.Dist("coarseness_mg_per_100m", 25, OpenClosed(0, 1000), "mg/100 m").Scaled(1e-8);
  f.youngs_modulus = r.Dist("youngs_modulus_GPa", 10, OpenClosed(0, 1000), "GPa").Scaled(1e9);
  f.shear_modulus = r.Dist("shear_modulus_GPa", 3, OpenClosed(0, 1000), "GPa").Scaled(1e9);
  f.strength = r.Dist("strength_mN", 100, OpenClosed(0, 1e6), "mN").Scaled(1e-3);
  f.segments = static_cast<int>(r.Integer("segments", 1, 1, 1000));
  f.bend_angle = r.Dist("bend_angle_deg", 0, Closed(-180, 180), "deg").Scaled(kDeg);
  f.twist_angle = r.Dist("twist_angle_deg", 0, Closed(-360, 360), "deg").Scaled(kDeg);
  f.maxwell_tau = r.Number("maxwell_tau_s", 0, Closed(0, 1e6), "s (0 = elastic)");
  if (r.Has("yield_moment_uN_m"))
    f.yield_moment = r.Number("yield_moment_uN_m", kInf, OpenClosed(0, 1e6), "uN m") * 1e-6;
  else
    r.Number("yield_moment_uN_m", 0, OpenClosed(0, 1e6), "uN m");  // known, absent: elastic
  r.Finish();
  if (f.diameter.Highest() >= f.length.Lowest())
    r.Fail("length_mm", fmt::format("the shortest fibre ({:g} mm) must be longer than the thickest "
                                    "fibre diameter ({:g} um); set a larger length (or its min)",
                                    f.length.Lowest() * 1e3, f.diameter.Highest() * 1e6));
  return f;
}

ContactParams ReadContact(TableReader& r) {
  ContactParams c;
  c.normal.C = r.Number("C_mN", 0.26, OpenClosed(0, 1e3), "mN") * 1e-3;
  c.normal.g = r.Number("exponent_g", 3.45, Closed(1, 20), "");
  c.normal.linear_below = r.Number("linear_below", 0.5, Open(0, 1), "of R_i + R_j");
  c.mu = r.Number("friction_mu", 0.3, Closed(0, 10), "");
  c.restitution = r.Number("restitution", 0.5, OpenClosed(0, 1), "");
  c.tangential_ratio = r.Number("tangential_ratio", 1.0, OpenClosed(0, 10), "");
  r.Finish();
  c.Derive();
  return c;
}

pipeline::FormingSettings ReadForming(TableReader& r) {
  pipeline::FormingSettings f;
  f.consistency = r.Number("consistency_percent", 1.0, Open(0, 100), "%") * 0.01;
  f.suspension_density =
      r.Number("suspension_density_kg_per_m3", 1000, OpenClosed(0, 1e5), "kg/m^3");
  f.drop_gap = r.Number("drop_gap_mm", 0, Closed(0, 1000), "mm") * 1e-3;
  f.orientation = r.Choice("orientation", "isotropic", {"isotropic", "planar"}) == "planar"
                      ? pipeline::Orientation::kPlanar
                      : pipeline::Orientation::kIsotropic;
  f.terminal_velocity = r.Number("terminal_velocity_m_per_s", 0.05, OpenClosed(0, 100), "m/s");
  f.air_velocity = r.Number("air_velocity_m_per_s", 0.0, Closed(0, 100), "m/s");
  f.mass_scale = r.Number("mass_scale", 1, Closed(1, 1e8), "");
  f.gravity_scale = r.Number("gravity_scale", 1, Closed(1, 1e8), "");
  f.stiffness_scale = r.Number("stiffness_scale", 1, OpenClosed(0, 1), "");
  f.settle_kinetic_ratio = r.Number("settle_kinetic_ratio", 1e-3, Open(0, 1), "");
  f.max_steps = r.Integer("max_steps", 5'000'000, 1, 10'000'000'000LL);
  f.placement_attempts = static_cast<int>(r.Integer("placement_attempts", 10000, 1, 10'000'000));
  r.Finish();
  return f;
}

pipeline::BondingSettings ReadBonding(TableReader& r) {
  pipeline::BondingSettings b;
  b.rest_length = r.Choice("rest_length", "current", {"current", "contact"}) == "contact"
                      ? pipeline::RestLength::kContact
                      : pipeline::RestLength::kCurrent;
  b.share = r.Choice("share", "particle", {"particle", "crossing"}) == "crossing"
                ? pipeline::BondShare::kCrossing
                : pipeline::BondShare::kParticle;
  b.transverse_modulus = r.Number("transverse_modulus_GPa", 1.0, OpenClosed(0, 1000), "GPa") * 1e9;
  b.transverse_shear_modulus =
      r.Number("transverse_shear_modulus_GPa", 0.3, OpenClosed(0, 1000), "GPa") * 1e9;
  b.bond_radius_fraction = r.Number("bond_radius_fraction", 0.5, OpenClosed(0, 1), "");
  b.F_r0 = r.Number("F_r0_mN", 25, OpenClosed(0, 1e6), "mN") * 1e-3;
  b.F_s0 = r.Number("F_s0_mN", 5, OpenClosed(0, 1e6), "mN") * 1e-3;
  b.gap_tolerance = r.Number("gap_tolerance", 0, Closed(-0.5, 0.5), "of R_i + R_j");
  r.Finish();
  return b;
}

// A relief pattern (embossing bosses, drying-fabric pockets); `height_key` names its height.
pipeline::ReliefPattern ReadRelief(TableReader& r, const std::string& height_key) {
  pipeline::ReliefPattern p;
  p.shape = r.Choice("pattern", "dots", {"dots", "lines"}) == "lines"
                ? pipeline::ReliefShape::kLines
                : pipeline::ReliefShape::kDots;
  p.pitch = r.Number("pitch_um", 500, OpenClosed(0, 1e5), "um") * 1e-6;
  p.size = r.Number("size_um", 250, OpenClosed(0, 1e5), "um") * 1e-6;
  p.height = r.RequiredNumber(height_key, OpenClosed(0, 1e4), "um") * 1e-6;
  p.flank = r.Number("flank_um", 50, OpenClosed(0, 1e5), "um") * 1e-6;
  if (p.size > p.pitch)
    r.Fail("size_um", fmt::format("{:g} um is wider than pitch_um = {:g} um; "
                                  "accepted (0, pitch_um]",
                                  p.size * 1e6, p.pitch * 1e6));
  if (p.flank > p.size)
    r.Fail("flank_um", fmt::format("{:g} um is wider than size_um = {:g} um; "
                                   "accepted (0, size_um]",
                                   p.flank * 1e6, p.size * 1e6));
  r.Finish();
  return p;
}

pipeline::ThroughAirSettings ReadThroughAir(TableReader& r, ReadContext& ctx) {
  pipeline::ThroughAirSettings t;
  const toml::table* fabric = r.Table("fabric");
  if (!fabric)
    r.Fail("fabric", "missing table: the drying fabric's pattern (pocket_depth_um, ...)");
  TableReader fr(fabric, r.Path("fabric"), ctx);
  t.fabric = ReadRelief(fr, "pocket_depth_um");
  t.pressure = r.Number("pressure_kPa", 20, OpenClosed(0, 1e4), "kPa") * 1e3;
  t.wet_stiffness_scale = r.Number("wet_stiffness_scale", 1, OpenClosed(0, 1), "");
  t.mass_scale = r.Number("mass_scale", 1, Closed(1, 1e8), "");
  t.damping_time = r.Number("damping_time_us", 10, OpenClosed(0, 1e6), "us") * 1e-6;
  t.settle_kinetic_ratio = r.Number("settle_kinetic_ratio", 1e-4, Open(0, 1), "");
  t.set_fibre_shape = r.Bool("set_fibre_shape", true);
  t.max_steps = r.Integer("max_steps", 5'000'000, 1, 10'000'000'000LL);
  if (const toml::table* b = r.Table("bonding")) {
    TableReader br(b, r.Path("bonding"), ctx);
    t.bonding = ReadBonding(br);
  }
  r.Finish();
  return t;
}

pipeline::PressingSettings ReadPressing(TableReader& r, ReadContext& ctx) {
  pipeline::PressingSettings p;
  const bool by_thickness = r.Has("target_thickness_um");
  const bool by_pressure = r.Has("target_pressure_kPa");
  if (by_thickness && by_pressure)
    r.Fail("target_pressure_kPa", "give target_thickness_um or target_pressure_kPa, not both");
  if (!by_thickness && !by_pressure)
    r.Fail("target_thickness_um", "missing; give target_thickness_um or target_pressure_kPa");
  p.target = by_pressure ? pipeline::PressTarget::kPressure : pipeline::PressTarget::kThickness;
  p.target_thickness = r.Number("target_thickness_um", 200, OpenClosed(0, 1e5), "um") * 1e-6;
  p.target_pressure = r.Number("target_pressure_kPa", 0, OpenClosed(0, 1e6), "kPa") * 1e3;
  p.control = r.Choice("thickness_control", "sheet", {"sheet", "plate"}) == "plate"
                  ? pipeline::ThicknessControl::kPlate
                  : pipeline::ThicknessControl::kSheet;
  p.control_tolerance = r.Number("control_tolerance", 0.01, OpenClosed(0, 0.5), "(relative)");
  p.max_corrections = static_cast<int>(r.Integer("max_corrections", 5, 0, 100));
  p.speed = r.Number("speed_m_per_s", 0.1, OpenClosed(0, 100), "m/s");
  p.approach_speed = r.Number("approach_speed_m_per_s", 1.0, OpenClosed(0, 100), "m/s");
  p.fast_speed = r.Number("fast_speed_m_per_s", 0.0, Closed(0, 100), "m/s (0 = one speed)");
  p.fast_until_ratio =
      r.Number("fast_until_thickness_ratio", 1.5, OpenClosed(1, 100), "of target_thickness_um");
  if (p.fast_speed > p.speed && by_pressure)
    r.Fail("fast_speed_m_per_s", "needs target_thickness_um (the plate presses fast down to "
                                 "fast_until_thickness_ratio x the target)");
  p.mass_scale = r.Number("mass_scale", 1, Closed(1, 1e8), "");
  p.damping_time = r.Number("damping_time_us", 10, OpenClosed(0, 1e6), "us") * 1e-6;
  p.min_hold_time = r.Number("min_hold_time_us", 0, Closed(0, 1e7), "us") * 1e-6;
  p.settle_kinetic_ratio = r.Number("settle_kinetic_ratio", 1e-4, Open(0, 1), "");
  p.kinetic_work_tolerance = r.Number("kinetic_work_tolerance", 0.01, OpenClosed(0, 1), "");
  p.set_fibre_shape = r.Bool("set_fibre_shape", true);
  p.max_steps = r.Integer("max_steps", 5'000'000, 1, 10'000'000'000LL);
  if (const toml::table* b = r.Table("bonding")) {
    TableReader br(b, r.Path("bonding"), ctx);
    p.bonding = ReadBonding(br);
  }
  if (const toml::table* e = r.Table("emboss")) {
    TableReader er(e, r.Path("emboss"), ctx);
    p.emboss = ReadRelief(er, "boss_height_um");
  }
  r.Finish();
  return p;
}

pipeline::CrepingSettings ReadCreping(TableReader& r, ReadContext& ctx) {
  pipeline::CrepingSettings c;
  c.yankee_speed = r.Number("yankee_speed_m_per_s", 30, OpenClosed(0, 200), "m/s");
  c.creping_angle = r.Number("creping_angle_deg", 85, Closed(30, 150), "deg") * kDeg;
  c.crepe_ratio = r.Number("crepe_ratio_percent", 15, Closed(0, 200), "%") * 1e-2;
  c.takeaway_height =
      r.Number("takeaway_height_um", 0, Closed(0, 1e5), "um (0 = 3 x the caliper)") * 1e-6;
  c.takeaway_time = r.Number("takeaway_time_us", 2, OpenClosed(0, 1e6), "us") * 1e-6;
  c.tip_clearance = r.Number("tip_clearance_um", 0, Closed(0, 1000), "um") * 1e-6;
  c.run_in_length = r.Number("run_in_length_um", 0, Closed(0, 1e5), "um (0 = off)") * 1e-6;
  c.blade_hard_stiffness = r.Number("blade_hard_stiffness_N_per_m", 1.2e5, Closed(0, 1e9), "N/m");
  c.fibre_hard_stiffness = r.Number("fibre_hard_stiffness_N_per_m", 1.5e4, Closed(0, 1e9), "N/m");
  if (r.Has("blade_friction_mu"))
    c.blade_friction_mu = r.Number("blade_friction_mu", 0.3, Closed(0, 10), "");
  c.relax_mass_scale = r.Number("relax_mass_scale", 1000, Closed(1, 1e8), "");
  c.relax_damping_time = r.Number("relax_damping_time_us", 10, OpenClosed(0, 1e6), "us") * 1e-6;
  c.relax_bond_damping_ratio =
      r.Number("relax_bond_damping_ratio", 0.5, Closed(0, 1), "of critical");
  c.relax_kinetic_ratio = r.Number("relax_kinetic_ratio", 1e-3, Open(0, 1), "");
  c.relax_energy_tolerance = r.Number("relax_energy_tolerance", 0.01, Open(0, 1), "");
  c.relax_max_steps = r.Integer("relax_max_steps", 50'000, 0, 10'000'000'000LL);
  c.end_zone_fraction = r.Number("end_zone_fraction", 0.2, Closed(0, 0.45), "of the strip length");
  c.crepe_cutoff = r.Number("crepe_cutoff_um", 800, Closed(100, 20000), "um") * 1e-6;
  c.crepe_shortest_wavelength = r.Number("crepe_shortest_wavelength_um", 0, Closed(0, 10000),
                                         "um (0 = 4 particle diameters)") * 1e-6;
  c.crepe_min_amplitude =
      r.Number("crepe_min_amplitude_um", 0, Closed(0, 10000), "um (0 = a particle radius)") * 1e-6;
  c.curve_samples = static_cast<int>(r.Integer("curve_samples", 200, 2, 100000));
  c.impact_frames = static_cast<int>(r.Integer("impact_frames", 0, 0, 1000));
  c.max_steps = r.Integer("max_steps", 20'000'000, 1, 10'000'000'000LL);
  if (const toml::table* a = r.Table("adhesion")) {
    TableReader ar(a, r.Path("adhesion"), ctx);
    pipeline::AdhesionSettings& ad = c.adhesion;
    ad.F_r0 = ar.Number("F_r0_mN", 7, OpenClosed(0, 1e6), "mN") * 1e-3;
    ad.F_s0 = ar.Number("F_s0_mN", 7, OpenClosed(0, 1e6), "mN") * 1e-3;
    ad.strength_cv = ar.Number("strength_cv", 0, Closed(0, 2), "");
    ad.modulus = ar.Number("modulus_MPa", 100, OpenClosed(0, 1e6), "MPa") * 1e6;
    ad.shear_modulus = ar.Number("shear_modulus_MPa", 30, OpenClosed(0, 1e6), "MPa") * 1e6;
    ad.coating_thickness = ar.Number("coating_thickness_um", 5, OpenClosed(0, 1000), "um") * 1e-6;
    ad.bond_radius_fraction = ar.Number("bond_radius_fraction", 0.5, OpenClosed(0, 1), "");
    ad.reach = ar.Number("reach_radii", 0.5, Closed(0, 1), "particle radii");
    ad.damping_ratio = ar.Number("damping_ratio", 0, Closed(0, 1), "of critical");
    ar.Finish();
  }
  r.Finish();
  return c;
}

pipeline::MetricsSettings ReadMetrics(TableReader& r) {
  pipeline::MetricsSettings m;
  m.fibre_density = r.Number("fibre_density_kg_per_m3", 1500, OpenClosed(0, 1e5), "kg/m^3");
  m.thickness_grid = r.Number("thickness_grid_um", 50, OpenClosed(0, 1e5), "um") * 1e-6;
  m.surface_percentile = r.Number("surface_percentile", 1, ClosedOpen(0, 50), "%");
  m.profile_bin = r.Number("profile_bin_um", 10, OpenClosed(0, 1e4), "um") * 1e-6;
  r.Finish();
  return m;
}

// Memory a scene needs per particle, with its bonds and neighbour lists (docs/performance.md
// measures about 600 bytes; 1 KiB leaves room for contacts in a pressed sheet).
constexpr double kBytesPerParticle = 1024.0;

std::string Bytes(double bytes) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int u = 0;
  for (; bytes >= 1024.0 && u < 6; ++u) bytes /= 1024.0;
  return fmt::format("{:.3g} {}", bytes, units[u]);
}

// Refuses a scene too big for this machine before anything is allocated, instead of failing
// with bad_alloc (or the OOM killer) deep in forming. The particle count is estimated from the
// sheet: fibre length = basis weight x cell area / coarseness, one particle per spacing.
void CheckMemory(const PipelineSpec& spec, const std::string& file) {
  const pipeline::FibreSpec& f = spec.sheet.fibres;
  const double fibre_length = spec.sheet.basis_weight * spec.sheet.Lx * spec.sheet.Ly /
                              f.coarseness.Mean();  // [m]
  const double spacing = spec.sheet.particle_spacing * f.diameter.Mean();
  const double particles = std::max(fibre_length / spacing, 2.0 * fibre_length / f.length.Mean());
  const double memory = static_cast<double>(sysconf(_SC_PHYS_PAGES)) *
                        static_cast<double>(sysconf(_SC_PAGESIZE));
  if (memory <= 0.0 || particles * kBytesPerParticle <= memory) return;
  throw InputError(fmt::format(
      "{}: cell: the scene would make about {:.3g} particles (cell.basis_weight_gsm x cell area / "
      "fibres.coarseness_mg_per_100m, one particle per fidelity.particle_spacing_diameters), "
      "about {} at {:g} bytes per particle, more than this machine's {} of memory; accepted: at "
      "most about {:.3g} particles here: reduce cell.size_x_mm, cell.size_y_mm or "
      "cell.basis_weight_gsm, or raise fidelity.particle_spacing_diameters",
      file, particles, Bytes(particles * kBytesPerParticle), kBytesPerParticle, Bytes(memory),
      memory / kBytesPerParticle));
}

PipelineSpec ReadScene(const toml::table& root_table, ReadContext& ctx) {
  PipelineSpec spec;
  TableReader root(&root_table, "", ctx);
  spec.seed = static_cast<std::uint64_t>(
      root.Integer("seed", 1, 0, std::numeric_limits<std::int64_t>::max()));

  TableReader cell(root.Table("cell"), "cell", ctx);
  spec.sheet.Lx = cell.Number("size_x_mm", 2.5, OpenClosed(0, 1000), "mm") * 1e-3;
  spec.sheet.Ly = cell.Number("size_y_mm", 2.5, OpenClosed(0, 1000), "mm") * 1e-3;
  spec.sheet.basis_weight =
      cell.Number("basis_weight_gsm", 20, OpenClosed(0, 1000), "g/m^2") * 1e-3;
  cell.Finish();

  TableReader fidelity(root.Table("fidelity"), "fidelity", ctx);
  spec.sheet.particle_spacing =
      fidelity.Number("particle_spacing_diameters", 1.0, Closed(0.25, 10), "diameters");
  spec.sheet.inertia_scale = fidelity.Number("inertia_scale", 1.0, Closed(1, 1e6), "");
  spec.sheet.time_step_safety =
      fidelity.Number("time_step_safety", 0.5, OpenClosed(0, 1), "of dt_crit");
  spec.sheet.neighbour_skin =
      fidelity.Number("neighbour_skin_radii", 0.5, OpenClosed(0, 5), "particle radii");
  fidelity.Finish();

  TableReader fibres(root.Table("fibres"), "fibres", ctx);
  spec.sheet.fibres = ReadFibres(fibres);
  TableReader contact(root.Table("contact"), "contact", ctx);
  spec.sheet.contact = ReadContact(contact);

  const toml::table* forming = root.Table("forming");
  if (!forming) root.Fail("forming", "missing table [forming]: the network is made by forming");
  TableReader fr(forming, "forming", ctx);
  spec.forming = ReadForming(fr);
  if (const toml::table* pressing = root.Table("pressing")) {
    TableReader pr(pressing, "pressing", ctx);
    spec.pressing = ReadPressing(pr, ctx);
  }
  if (const toml::table* through_air = root.Table("through_air")) {
    if (spec.pressing)
      root.Fail("through_air", "a scene has one consolidation stage: [pressing] or "
                               "[through_air], not both");
    TableReader tr(through_air, "through_air", ctx);
    spec.through_air = ReadThroughAir(tr, ctx);
  }
  if (const toml::table* creping = root.Table("creping")) {
    if (!spec.pressing && !spec.through_air)
      root.Fail("creping",
                "the sheet is creped after consolidation: add [pressing] or [through_air]");
    TableReader cr(creping, "creping", ctx);
    spec.creping = ReadCreping(cr, ctx);
  }
  TableReader metrics(root.Table("metrics"), "metrics", ctx);
  spec.metrics = ReadMetrics(metrics);
  ReadSceneTests(root, ctx, spec.tests);
  root.Finish();

  // Non-physical combinations, named by their scene keys.
  const double length = spec.sheet.fibres.length.Mean();
  if (length >= std::min(spec.sheet.Lx, spec.sheet.Ly))
    fibres.Fail("length_mm",
                fmt::format("the mean fibre length {:g} mm must be shorter than the "
                            "cell side {:g} mm (cell.size_x_mm, cell.size_y_mm)",
                            length * 1e3, std::min(spec.sheet.Lx, spec.sheet.Ly) * 1e3));
  if (spec.pressing && spec.pressing->target == pipeline::PressTarget::kThickness &&
      spec.pressing->target_thickness <= spec.sheet.fibres.diameter.Highest())
    throw InputError(fmt::format("{}: pressing.target_thickness_um: {:g} um is not above the "
                                 "thickest fibre ({:g} um); accepted ({:g}, 1e5] um",
                                 ctx.file, spec.pressing->target_thickness * 1e6,
                                 spec.sheet.fibres.diameter.Highest() * 1e6,
                                 spec.sheet.fibres.diameter.Highest() * 1e6));
  // Refused here, before hours of forming; the stage checks it again on the strip it gets,
  // which a run from another cell's snapshot may make longer or shorter.
  if (spec.creping && spec.creping->run_in_length >
                          spec.creping->end_zone_fraction * spec.sheet.Lx)
    throw InputError(fmt::format("{}: creping.run_in_length_um: {:g} um does not end within the "
                                 "leading end zone; accepted [0, {:g}] um (end_zone_fraction x "
                                 "cell.size_x_mm)",
                                 ctx.file, spec.creping->run_in_length * 1e6,
                                 spec.creping->end_zone_fraction * spec.sheet.Lx * 1e6));
  if (std::string why = spec.Validate(); !why.empty())
    throw InputError(fmt::format("{}: {}", ctx.file, why));
  CheckMemory(spec, ctx.file);
  return spec;
}

}  // namespace

KeyStage StageOfKey(const std::string& path) {
  const std::string table = path.substr(0, path.find('.'));
  if (table == "cell" || table == "fibres" || table == "contact" || table == "forming")
    return KeyStage::kForming;
  if (table == "pressing" || table == "through_air") return KeyStage::kConsolidation;
  if (table == "creping") return KeyStage::kCreping;
  if (table == "tensile" || table == "compression" || table == "softness") return KeyStage::kTests;
  return KeyStage::kEvery;
}

Override ParseOverride(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos)
    throw InputError(fmt::format("override '{}': no '='; accepted: KEY=NUMBER with a dotted scene "
                                 "key, e.g. pressing.target_thickness_um=150",
                                 text));
  Override o;
  o.path = text.substr(0, eq);
  const std::string value = text.substr(eq + 1);
  if (value == "true" || value == "false") {
    o.flag = value == "true";
    return o;
  }
  try {
    std::size_t used = 0;
    o.value = std::stod(value, &used);
    if (used != value.size()) throw std::invalid_argument(value);
  } catch (const std::exception&) {
    throw InputError(fmt::format("override '{}': '{}' is not a number; accepted: KEY=NUMBER, e.g. "
                                 "{}=1.5, or KEY=true / KEY=false for a switch",
                                 text, value, o.path));
  }
  return o;
}

PipelineSpec ParseScene(std::string_view text, const std::string& name,
                        const std::vector<Override>& overrides) {
  toml::table root;
  try {
    root = toml::parse(text, name);
  } catch (const toml::parse_error& e) {
    throw InputError(fmt::format("{}:{}:{}: TOML syntax error: {}", name, e.source().begin.line,
                                 e.source().begin.column, e.description()));
  }
  if (root.empty())
    throw InputError(fmt::format("{}: the file is empty; accepted: a scene with at least a "
                                 "[forming] table (docs/scene-files.md)",
                                 name));
  ReadContext ctx;
  ctx.file = name;
  for (const Override& o : overrides) {
    ApplyOverride(root, o, name);
    ctx.overrides.insert(o.path);
  }
  PipelineSpec spec = ReadScene(root, ctx);
  for (const Override& o : overrides)
    if (!ctx.known.count(o.path)) {
      const std::vector<std::string> known(ctx.known.begin(), ctx.known.end());
      const std::string near = optimizer::ClosestMatch(o.path, known);
      throw InputError(fmt::format("{}: override '{}': unknown scene key{}", name, o.path,
                                   near.empty() ? "" : fmt::format("; did you mean '{}'?", near)));
    }
  return spec;
}

std::string ReadSceneText(const std::string& path) {
  // An ifstream opens a folder without complaint and reads nothing from it.
  std::error_code ec;  // a name the system refuses (too long, say) is not a folder
  if (std::filesystem::is_directory(path, ec))
    throw InputError(fmt::format("{}: is a folder; accepted: a scene file (TOML)", path));
  std::ifstream in(path, std::ios::binary);
  if (!in && ec && ec != std::errc::no_such_file_or_directory)  // too long a name, say
    throw InputError(fmt::format("{}: cannot open the scene file ({})", path, ec.message()));
  if (!in)
    throw InputError(fmt::format("{}: cannot open the scene file (missing or unreadable)", path));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

PipelineSpec LoadScene(const std::string& path, const std::vector<Override>& overrides) {
  return ParseScene(ReadSceneText(path), path, overrides);
}

}  // namespace fibrenet::campaigns
