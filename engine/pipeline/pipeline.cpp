#include "engine/pipeline/pipeline.h"

#include <random>

#include <fmt/format.h>

#include "engine/core/error.h"

namespace fibrenet::pipeline {

std::string PipelineSpec::Validate() const {
  if (std::string why = sheet.Validate(); !why.empty()) return why;
  if (std::string why = forming.Validate(); !why.empty()) return "forming." + why;
  if (pressing && through_air)
    return "through_air: a scene has one consolidation stage, [pressing] or [through_air], not both";
  if (pressing)
    if (std::string why = pressing->Validate(); !why.empty()) return "pressing." + why;
  if (through_air)
    if (std::string why = through_air->Validate(); !why.empty()) return "through_air." + why;
  if (creping) {
    if (!pressing && !through_air)
      return "creping: the sheet is creped after consolidation; add [pressing] or [through_air]";
    if (std::string why = creping->Validate(); !why.empty()) return "creping." + why;
  }
  if (std::string why = metrics.Validate(); !why.empty()) return "metrics." + why;
  return tests.Validate();
}

std::string PipelineSpec::Consolidation() const {
  if (pressing) return "pressing";
  if (through_air) return "through_air";
  return "";
}

namespace {

// The creping details that are also results a campaign may aim at, with their units.
const char* CrepingMetricUnit(const std::string& name) {
  static const std::vector<std::pair<std::string, const char*>> units = {
      {"crepe_frequency_per_mm", "1/mm"}, {"crepe_amplitude_um", "um"},
      {"bonds_broken_fraction", "-"},     {"dust_count", "-"},
      {"dust_mass_fraction", "-"},        {"bulk_gain", "-"},
      {"energy_balance_error", "-"}};
  for (const auto& [n, unit] : units)
    if (n == name) return unit;
  return nullptr;
}

}  // namespace

std::vector<Metric> PipelineReport::AllMetrics() const {
  std::vector<Metric> all;
  if (!stages.empty())
    for (const auto& [name, value] : Final().List()) all.push_back({name, value, NetworkMetricUnit(name)});
  for (const StageReport& stage : stages)
    if (stage.name == "creping")
      for (const auto& [name, value] : stage.details)
        if (const char* unit = CrepingMetricUnit(name)) all.push_back({name, value, unit});
  if (tests) all.insert(all.end(), tests->metrics.begin(), tests->metrics.end());
  return all;
}

PipelineReport RunPipeline(const PipelineSpec& spec, const Progress& progress,
                           const StageState* start, std::vector<StageState>* kept) {
  if (std::string why = spec.Validate(); !why.empty()) throw InputError(why);
  PipelineReport report;
  Stopwatch total;
  std::mt19937_64 rng(spec.seed);
  const std::size_t done = start ? start->stages.size() : 0;
  if (start) {
    const bool consolidated = done >= 2 && !spec.Consolidation().empty() &&
                              start->stages[1].name == spec.Consolidation();
    const bool creped = done == 3 && spec.creping && start->stages[2].name == "creping";
    const bool valid = (done == 1 && start->stages[0].name == "forming") ||
                       (consolidated && (done == 2 || creped));
    if (!valid) throw Error("RunPipeline: the start state does not match the scene's stages");
    report.stages = start->stages;
    report.network = start->network;
    progress.Say(fmt::format("starting after {} from an earlier run", report.stages.back().name));
  }
  // A stage's network is copied aside only when a later stage is about to change it, so the
  // last stage's state is the returned network itself, never a second copy of it. The kept
  // networks park their neighbour lists: a run that keeps every stage holds one network's
  // rows, not one per stage.
  bool unkept = false;
  auto keep = [&] { unkept = kept != nullptr; };
  auto set_aside = [&] {
    if (unkept) kept->push_back({report.stages, {KeptCopy(report.network.world), report.network.fibres}});
    unkept = false;
  };

  if (done < 1) {
    Stopwatch clock;
    StageReport stage;
    stage.name = "forming";
    PlacementStats placed;
    report.network = PlaceFibres(spec.sheet, spec.forming, rng, &placed);
    progress.Say(fmt::format("forming: {} fibres, {} particles in a {:.0f} um high box",
                             report.network.fibres.size(), report.network.world.particles.size(),
                             placed.box_height * 1e6));
    const FormingResult r = Settle(report.network, spec.sheet, spec.forming, progress);
    stage.steps = r.steps;
    stage.details = {{"box_height_um", placed.box_height * 1e6},
                     {"overlapping_fibres_placed", placed.overlapping_fibres},
                     {"dt_s", r.dt},
                     {"simulated_time_s", r.simulated_time},
                     {"settled", r.settled ? 1.0 : 0.0},
                     {"kinetic_ratio", r.kinetic_ratio},
                     {"neighbour_builds",
                      static_cast<double>(report.network.world.neighbours.builds())}};
    if (!r.dt_warning.empty()) stage.warnings.push_back(r.dt_warning);
    if (!r.settled)
      stage.warnings.push_back(fmt::format(
          "forming did not settle within max_steps = {} (kinetic ratio {:.3g})",
          spec.forming.max_steps, r.kinetic_ratio));
    if (placed.overlapping_fibres > 0)
      stage.warnings.push_back(fmt::format("{} fibres were placed overlapping others",
                                           placed.overlapping_fibres));
    if (spec.sheet.particle_spacing > 1.0)
      stage.warnings.push_back(fmt::format(
          "particle spacing {} diameters > 1: a crossing fibre can pass between a fibre's "
          "particles, so contacts and bonds are missed (docs/performance.md, speed against "
          "error); use it only where fibre-fibre contact does not matter",
          spec.sheet.particle_spacing));
    stage.metrics = Measure(report.network, spec.metrics);
    stage.wall_s = clock.Seconds();
    report.stages.push_back(std::move(stage));
    keep();
  }

  if (spec.pressing && done < 2) {
    Stopwatch clock;
    set_aside();
    StageReport stage;
    stage.name = "pressing";
    PressingResult r = Press(report.network, spec.sheet, *spec.pressing, spec.metrics, progress);
    stage.steps = r.steps;
    stage.details = {{"dt_s", r.dt},
                     {"plate_first_touch_um", r.first_touch * 1e6},
                     {"plate_press_start_um", r.press_start * 1e6},
                     {"plate_gap_at_hold_um", r.plate_gap_at_hold * 1e6},
                     {"thickness_at_hold_um", r.thickness_at_hold * 1e6},
                     {"max_pressure_Pa", r.max_pressure},
                     {"plate_work_J", r.plate_work},
                     {"kinetic_to_work_ratio", r.kinetic_to_work_ratio},
                     {"bonds_formed", static_cast<double>(r.bonds_formed)},
                     {"settled", r.settled ? 1.0 : 0.0}};
    if (spec.pressing->emboss) {
      stage.details.emplace_back("imprint_at_hold_um", r.imprint_at_hold * 1e6);
      stage.details.emplace_back("imprint_um", r.imprint * 1e6);
    }
    stage.warnings = std::move(r.warnings);
    stage.press_curve = std::move(r.curve);
    stage.metrics = Measure(report.network, spec.metrics);
    stage.wall_s = clock.Seconds();
    report.stages.push_back(std::move(stage));
    keep();
  }

  if (spec.through_air && done < 2) {
    Stopwatch clock;
    set_aside();
    StageReport stage;
    stage.name = "through_air";
    ThroughAirResult r = DryThroughAir(report.network, spec.sheet, *spec.through_air, progress);
    stage.steps = r.steps;
    stage.details = {{"dt_s", r.dt},
                     {"air_work_J", r.air_work},
                     {"imprint_moulded_um", r.imprint_moulded * 1e6},
                     {"imprint_um", r.imprint * 1e6},
                     {"bonds_formed", static_cast<double>(r.bonds_formed)},
                     {"settled", r.settled ? 1.0 : 0.0}};
    stage.warnings = std::move(r.warnings);
    stage.metrics = Measure(report.network, spec.metrics);
    stage.wall_s = clock.Seconds();
    report.stages.push_back(std::move(stage));
    keep();
  }

  if (spec.creping && done < 3) {
    Stopwatch clock;
    set_aside();
    StageReport stage;
    stage.name = "creping";
    const MetricsSettings& m = spec.metrics;
    CrepingResult r = Crepe(report.network, spec.sheet, *spec.creping, m, spec.seed, progress);
    stage.steps = r.steps;
    stage.details = {{"dt_s", r.dt},
                     {"simulated_time_us", r.simulated_time * 1e6},
                     {"crepe_frequency_per_mm", r.crepe_frequency * 1e-3},
                     {"crepe_amplitude_um", r.crepe_amplitude * 1e6},
                     {"crepe_fold_count", static_cast<double>(r.crepe_fold_count)},
                     {"crepe_min_amplitude_um", r.crepe_min_amplitude * 1e6},
                     {"crepe_profile_length_um", r.crepe_profile_length * 1e6},
                     {"crepe_gathered_ratio", r.crepe_gathered_ratio},
                     {"crepe_curl_ratio", r.crepe_curl_ratio},
                     {"crepe_fold_ratio", r.crepe_fold_ratio},
                     {"crepe_in_plane_ratio", r.crepe_in_plane_ratio},
                     {"bonds_broken_fraction", r.bonds_broken_fraction},
                     {"bonds_broken_fraction_all", r.bonds_broken_fraction_all},
                     {"fibre_bonds_broken", r.fibre_bonds_broken},
                     {"adhesive_bonds", static_cast<double>(r.adhesive_bonds)},
                     {"adhesive_broken_fraction", r.adhesive_broken_fraction},
                     {"dust_count", static_cast<double>(r.dust_count)},
                     {"dust_mass_fraction", r.dust_mass_fraction},
                     {"caliper_before_um", r.caliper_before * 1e6},
                     {"caliper_after_um", r.caliper_after * 1e6},
                     {"caliper_at_blade_um", r.caliper_at_blade * 1e6},
                     {"bulk_gain", r.bulk_gain},
                     {"energy_balance_error", r.energy_balance_error},
                     {"blade_work_J", r.blade_work},
                     {"overlap_regained_J", r.overlap_regained},
                     {"peak_blade_force_N_per_m", r.peak_blade_force},
                     {"delaminated_length_um", r.delaminated_length * 1e6},
                     {"delaminated_length_max_um", r.delaminated_length_max * 1e6},
                     {"coating_toughness_J_per_m2", r.coating_toughness},
                     {"momentum_flux_N_per_m", r.momentum_flux},
                     {"reel_tension_N_per_m", r.reel_tension},
                     {"peak_reel_tension_N_per_m", r.peak_reel_tension},
                     {"particles_past_blade", static_cast<double>(r.particles_past_blade)},
                     {"min_contact_ratio", r.min_contact_ratio},
                     {"bonds_cut_at_ends", static_cast<double>(r.bonds_cut)},
                     {"particles_removed", static_cast<double>(r.particles_removed)},
                     {"sheet_mass_fraction", r.sheet_mass_fraction},
                     {"relax_steps", static_cast<double>(r.relax_steps)},
                     {"relaxed", r.relaxed ? 1.0 : 0.0}};
    stage.warnings = std::move(r.warnings);
    stage.curves.push_back(std::move(r.bond_loss));
    if (!r.crepe_profile.rows.empty()) stage.curves.push_back(std::move(r.crepe_profile));
    stage.frames = std::move(r.impact_frames);
    stage.metrics = Measure(report.network, m);
    stage.wall_s = clock.Seconds();
    report.stages.push_back(std::move(stage));
    keep();
  }

  if (spec.tests.Any()) {
    // The sheet steps no more; each test steps a copy of it with rows of its own.
    report.network.world.neighbours = report.network.world.neighbours.Parked();
    report.tests = RunVirtualTests(report.network, spec.tests, progress);
    StageReport stage;
    stage.name = "tests";
    stage.steps = report.tests->steps;
    stage.wall_s = report.tests->wall_s;
    stage.metrics = report.stages.back().metrics;
    stage.warnings = report.tests->warnings;
    for (const Metric& m : report.tests->metrics) stage.details.emplace_back(m.name, m.value);
    report.stages.push_back(std::move(stage));
  }
  report.wall_s = total.Seconds();
  return report;
}

std::span<const StageReport> NetworkStages(const PipelineReport& report) {
  std::span<const StageReport> stages = report.stages;
  if (!stages.empty() && stages.back().name == "tests") stages = stages.first(stages.size() - 1);
  return stages;
}

void KeepFinalState(PipelineReport& report, const StageState* start,
                    std::vector<StageState>& kept) {
  const std::span<const StageReport> stages = NetworkStages(report);
  if (stages.size() <= (start ? start->stages.size() : 0)) return;
  kept.push_back({{stages.begin(), stages.end()}, std::move(report.network)});
}

}  // namespace fibrenet::pipeline
