#include "engine/pipeline/consolidation.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "engine/core/energy.h"
#include "engine/core/error.h"
#include "engine/core/simulation.h"
#include "engine/pipeline/test_rig.h"

namespace fibrenet::pipeline {

namespace {

double TopSurface(const Particles& p) {
  double top = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) top = std::max(top, p.x[i].z() + p.radius[i]);
  return top;
}

}  // namespace

std::string PressingSettings::Validate() const {
  if (target == PressTarget::kThickness && !(target_thickness > 0.0 && target_thickness <= 0.1))
    return fmt::format("target_thickness = {} m: must lie in (0, 0.1]", target_thickness);
  if (target == PressTarget::kPressure && !(target_pressure > 0.0 && target_pressure <= 1e9))
    return fmt::format("target_pressure = {} Pa: must lie in (0, 1e9]", target_pressure);
  if (!(control_tolerance > 0.0 && control_tolerance <= 0.5))
    return fmt::format("control_tolerance = {}: must lie in (0, 0.5]", control_tolerance);
  if (max_corrections < 0 || max_corrections > 100)
    return fmt::format("max_corrections = {}: must lie in [0, 100]", max_corrections);
  if (!(speed > 0.0 && speed <= 100.0))
    return fmt::format("speed = {} m/s: must lie in (0, 100]", speed);
  if (!(approach_speed > 0.0 && approach_speed <= 100.0))
    return fmt::format("approach_speed = {} m/s: must lie in (0, 100]", approach_speed);
  if (!(fast_speed >= 0.0 && fast_speed <= 100.0))
    return fmt::format("fast_speed = {} m/s: must lie in [0, 100] (0 = one speed)", fast_speed);
  if (!(fast_until_ratio > 1.0 && fast_until_ratio <= 100.0))
    return fmt::format("fast_until_ratio = {}: must lie in (1, 100] of the target thickness",
                       fast_until_ratio);
  if (fast_speed > speed && target != PressTarget::kThickness)
    return fmt::format("fast_speed = {} m/s needs a target thickness (it presses fast down to "
                       "fast_until_ratio x the target)", fast_speed);
  if (!(mass_scale >= 1.0 && mass_scale <= 1e8))
    return fmt::format("mass_scale = {}: must lie in [1, 1e8]", mass_scale);
  if (!(damping_time > 0.0 && damping_time <= 1.0))
    return fmt::format("damping_time = {} s: must lie in (0, 1]", damping_time);
  if (!(min_hold_time >= 0.0 && min_hold_time <= 10.0))
    return fmt::format("min_hold_time = {} s: must lie in [0, 10]", min_hold_time);
  if (!(settle_kinetic_ratio > 0.0 && settle_kinetic_ratio < 1.0))
    return fmt::format("settle_kinetic_ratio = {}: must lie in (0, 1)", settle_kinetic_ratio);
  if (!(kinetic_work_tolerance > 0.0 && kinetic_work_tolerance <= 1.0))
    return fmt::format("kinetic_work_tolerance = {}: must lie in (0, 1]", kinetic_work_tolerance);
  if (bonding)
    if (std::string why = bonding->Validate(); !why.empty()) return "bonding." + why;
  if (emboss)
    if (std::string why = emboss->Validate(); !why.empty()) return "emboss." + why;
  if (max_steps < 1) return fmt::format("max_steps = {}: must be >= 1", max_steps);
  return {};
}

PressingResult Press(Network& net, const SheetSpec& sheet, const PressingSettings& s,
                     const MetricsSettings& metrics, const Progress& progress) {
  World& w = net.world;
  Particles& p = w.particles;
  const SavedMasses masses = ScaleMasses(w, s.mass_scale);
  const double mean_mass = net.TotalMass() / static_cast<double>(p.size());
  const double area = net.Area();
  double r_max = 0.0;
  for (double r : p.radius) r_max = std::max(r_max, r);

  w.physics = Physics{};
  w.physics.contacts = true;
  w.physics.friction = w.contact.mu > 0.0;
  // The background drag only acts while the plate approaches or rests (hold, springback):
  // during the compression it would resist the squeeze itself.
  w.physics.drag = true;  // on for Prepare, so that the time step allows for it
  w.physics.drag_coefficient = mean_mass / s.damping_time;
  w.walls.resize(1);  // keep the wire
  w.walls[0] = Wall{};
  Wall plate;
  plate.side = -1;
  const double boss = s.emboss ? s.emboss->height : 0.0;
  if (s.emboss) plate.relief = MakeRelief(*s.emboss, w.cell, +1.0);
  plate.z = TopSurface(p) + 0.5 * r_max + boss;
  plate.vz = -s.speed;
  w.walls.push_back(plate);
  UseSheetStepSettings(w, sheet);

  Simulation sim(w);
  PressingResult result;
  if (std::string warn = sim.Prepare(); !warn.empty()) result.warnings.push_back(warn);
  w.physics.drag = false;
  result.dt = w.settings.dt;
  const double t0 = w.time;
  const std::int64_t step0 = w.step;
  auto plate_ref = [&]() -> Wall& { return w.walls[1]; };
  auto pressure = [&] { return w.walls.size() > 1 ? plate_ref().reaction.z() / area : 0.0; };
  double kinetic = 0.0;
  auto sample = [&] {
    kinetic = KineticEnergy(w);
    const double z = w.walls.size() > 1 ? plate_ref().z : 0.0;
    result.curve.push_back({w.time - t0, z, pressure(), kinetic});
    result.max_pressure = std::max(result.max_pressure, pressure());
  };
  // Chunks of a quarter particle radius of plate travel.
  auto quarter_radius_steps = [&](double speed) {
    return std::max<std::int64_t>(
        1, static_cast<std::int64_t>(0.25 * r_max / (speed * w.settings.dt)));
  };
  const std::int64_t chunk = std::clamp<std::int64_t>(quarter_radius_steps(s.speed), 10, 2000);

  // 1. Compression to the target gap or pressure.
  const double floor_gap = 2.0 * r_max + boss;  // the plate never comes closer to the wire
  const double stop_z =
      s.target == PressTarget::kThickness ? std::max(s.target_thickness, floor_gap) : floor_gap;
  if (s.target == PressTarget::kThickness && s.target_thickness < floor_gap)
    result.warnings.push_back(fmt::format(
        "pressing: target {:.1f} um is below the boss height plus a fibre diameter; the plate "
        "stops at {:.1f} um", s.target_thickness * 1e6, stop_z * 1e6));
  const double travel = plate_ref().z - stop_z;
  if (travel > 0.0 && travel / (s.speed * w.settings.dt) > static_cast<double>(s.max_steps))
    throw RunError(fmt::format(
        "pressing would take {:.3g} steps to move the plate {:.0f} um at {} m/s with dt = {:.3g} s, "
        "more than max_steps = {}: raise pressing speed or mass scaling",
        travel / (s.speed * w.settings.dt), travel * 1e6, s.speed, w.settings.dt, s.max_steps));
  // 1a. Approach: the plate comes down fast to the web's top surface, the height the
  // thickness measure reads (docs/network.md). Fibres standing out of the web above it (a
  // formed web has a few, up to a fibre length high) are laid down on the way; pressing
  // proper starts at the surface. The background drag is on: it damps the fibres the plate
  // knocks down and the web's residual motion from forming (which the pressing mass scale
  // multiplies), and acts on nothing at rest.
  const double approach = std::max(s.approach_speed, s.speed);
  const std::int64_t approach_chunk = quarter_radius_steps(approach);
  const double web_surface =
      MeasureSurfaces(w, metrics.thickness_grid, metrics.surface_percentile).top;
  result.press_start = std::max(stop_z, web_surface + boss);
  auto note_touch = [&] {
    if (result.first_touch == 0.0 && plate_ref().reaction.z() > 0.0)
      result.first_touch = plate_ref().z;
  };
  plate_ref().vz = -approach;
  w.physics.drag = true;
  while (plate_ref().z > result.press_start + approach * w.settings.dt * approach_chunk) {
    sim.Run(approach_chunk);
    note_touch();
    sample();
  }
  w.physics.drag = false;
  // 1b. Pressing, at fast_speed down to slow_from if two speeds are set, then at speed.
  const bool two_speeds = s.fast_speed > s.speed;
  const double slow_from = two_speeds ? s.fast_until_ratio * stop_z : stop_z;
  const std::int64_t fast_chunk = two_speeds ? quarter_radius_steps(s.fast_speed) : chunk;
  Stopwatch clock;
  double next_report = progress.interval_s;
  while (plate_ref().z > stop_z) {
    const bool fast = two_speeds && plate_ref().z > slow_from;
    const double speed = fast ? s.fast_speed : s.speed;
    const double goal = fast ? slow_from : stop_z;
    plate_ref().vz = -speed;
    const auto left = static_cast<std::int64_t>(
        std::ceil((plate_ref().z - goal) / (speed * w.settings.dt)));
    sim.Run(std::min(fast ? fast_chunk : chunk, std::max<std::int64_t>(left, 1)));
    note_touch();
    sample();
    if (s.target == PressTarget::kPressure && pressure() >= s.target_pressure) break;
    if (clock.Seconds() >= next_report) {
      progress.Say(fmt::format("pressing: step {} plate at {:.1f} um, pressure {:.4g} Pa",
                               w.step, plate_ref().z * 1e6, pressure()));
      next_report = clock.Seconds() + progress.interval_s;
    }
  }
  // The guard counts the motion beyond the squeeze itself, the affine field from the wire at
  // rest to the plate at its speed, as the ZD compression's guard does (test_rig.h): a web
  // squeezed slowly enough moves with that field and has no other kinetic energy.
  const AffineField squeeze{2, w.walls[0].z, plate_ref().z - w.walls[0].z, plate_ref().vz};
  const double beyond_squeeze =
      FluctuatingKineticEnergy(w, std::vector<std::uint8_t>(p.size(), 0), squeeze);
  plate_ref().vz = 0.0;
  if (s.target == PressTarget::kPressure && pressure() < s.target_pressure)
    result.warnings.push_back(fmt::format(
        "target pressure {:.4g} Pa not reached: the plate stopped {:.1f} um above the wire at "
        "{:.4g} Pa", s.target_pressure, plate_ref().z * 1e6, pressure()));
  result.plate_work = plate_ref().work;
  result.kinetic_to_work_ratio =
      result.plate_work > 0.0 ? beyond_squeeze / result.plate_work : 0.0;
  if (result.kinetic_to_work_ratio > s.kinetic_work_tolerance)
    result.warnings.push_back(fmt::format(
        "pressing not quasi-static: kinetic / plate work = {:.3g} > {:.3g} at the end of the "
        "compression; lower the plate speed or the pressing mass scale",
        result.kinetic_to_work_ratio, s.kinetic_work_tolerance));
  const double energy_ref = std::max(result.plate_work, 1e-30);
  // A plate that never pressed the web (the web is thinner than the target) did no work:
  // there is nothing to hold or spring back, and no energy scale to settle against.
  const bool pressed = result.plate_work > 0.0;
  if (!pressed)
    result.warnings.push_back(fmt::format(
        "pressing: the plate stopped at {:.1f} um without pressing the web (thinner than the "
        "target); the web keeps its formed thickness", plate_ref().z * 1e6));

  // 2. Hold until at rest. With sheet thickness control, move the plate by the difference
  // between the sheet's thickness (metrics definition) and the target and hold again, until
  // they agree within control_tolerance.
  w.physics.drag = true;
  double t_hold = w.time;
  auto at_rest = [&] {
    sample();
    return w.time - t_hold >= s.min_hold_time && kinetic < s.settle_kinetic_ratio * energy_ref;
  };
  auto hold_status = [&] {
    return fmt::format("pressing: holding at {:.1f} um, pressure {:.4g} Pa, kinetic / work {:.3g}",
                       plate_ref().z * 1e6, pressure(), kinetic / energy_ref);
  };
  const bool control = s.target == PressTarget::kThickness &&
                       s.control == ThicknessControl::kSheet && !s.emboss;
  for (int correction = 0; pressed; ++correction) {
    t_hold = w.time;
    RunUntil(sim, s.max_steps, chunk, at_rest, hold_status, progress);
    if (!(kinetic < s.settle_kinetic_ratio * energy_ref))
      result.warnings.push_back("pressing: the web did not come to rest during the hold");
    result.thickness_at_hold = Thickness(w, metrics.thickness_grid, metrics.surface_percentile);
    const double error = result.thickness_at_hold - s.target_thickness;
    if (!control || std::abs(error) <= s.control_tolerance * s.target_thickness) break;
    if (correction == s.max_corrections) {
      result.warnings.push_back(fmt::format(
          "pressing: sheet thickness {:.1f} um still differs from the target {:.1f} um after {} "
          "plate corrections", result.thickness_at_hold * 1e6, s.target_thickness * 1e6,
          correction));
      break;
    }
    const double goal = std::max(floor_gap, plate_ref().z - error);
    const auto steps = static_cast<std::int64_t>(
        std::ceil(std::abs(goal - plate_ref().z) / (s.speed * w.settings.dt)));
    plate_ref().vz = (goal - plate_ref().z) / (static_cast<double>(std::max<std::int64_t>(steps, 1)) *
                                               w.settings.dt);
    sim.Run(std::max<std::int64_t>(steps, 1));
    plate_ref().vz = 0.0;
    progress.Say(fmt::format("pressing: sheet {:.1f} um, target {:.1f} um: plate moved to {:.1f} um",
                             result.thickness_at_hold * 1e6, s.target_thickness * 1e6,
                             plate_ref().z * 1e6));
  }
  result.plate_gap_at_hold = plate_ref().z;
  if (!pressed) result.thickness_at_hold = Thickness(w, metrics.thickness_grid, metrics.surface_percentile);

  if (s.emboss) result.imprint_at_hold = Imprint(w, *plate_ref().relief);

  // 3. Bonding in the pressed state.
  if (s.bonding) {
    result.bonds_formed = FormFibreFibreBonds(net, *s.bonding);
    if (s.set_fibre_shape) SetFibreShape(net);
    w.settings.dt = 0.0;
    if (std::string warn = sim.Prepare(); !warn.empty()) result.warnings.push_back(warn);
    progress.Say(fmt::format("pressing: {} fibre-fibre bonds formed at {:.1f} um",
                             result.bonds_formed, plate_ref().z * 1e6));
  } else if (s.set_fibre_shape) {
    SetFibreShape(net);
  }

  // 4. Lift the plate until it has left the sheet, then let the sheet spring back.
  plate_ref().vz = s.speed;
  auto lifted = [&] {
    sample();
    return plate_ref().reaction.z() <= 0.0 && plate_ref().z - boss > TopSurface(p) + 0.5 * r_max;
  };
  auto lift_status = [&] {
    return fmt::format("pressing: lifting, plate at {:.1f} um, pressure {:.4g} Pa",
                       plate_ref().z * 1e6, pressure());
  };
  if (pressed) RunUntil(sim, s.max_steps, chunk, lifted, lift_status, progress);
  const std::shared_ptr<const Relief> relief = plate_ref().relief;
  w.walls.pop_back();
  const double t_free = w.time;
  auto relaxed = [&] {
    sample();
    return w.time - t_free >= 5.0 * s.damping_time && kinetic < s.settle_kinetic_ratio * energy_ref;
  };
  auto relax_status = [&] {
    return fmt::format("pressing: springback, top surface {:.1f} um, kinetic / work {:.3g}",
                       TopSurface(p) * 1e6, kinetic / energy_ref);
  };
  if (pressed) RunUntil(sim, s.max_steps, chunk, relaxed, relax_status, progress);
  result.settled = !pressed || kinetic < s.settle_kinetic_ratio * energy_ref;
  if (relief) result.imprint = Imprint(w, *relief);
  if (!result.settled) result.warnings.push_back("pressing: the springback did not come to rest");

  result.steps = w.step - step0;
  RestoreMasses(w, masses);
  w.physics.drag = false;
  return result;
}

}  // namespace fibrenet::pipeline
