#include "engine/pipeline/through_air.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "engine/core/energy.h"
#include "engine/core/error.h"
#include "engine/core/simulation.h"

namespace fibrenet::pipeline {

std::string ThroughAirSettings::Validate() const {
  if (std::string why = fabric.Validate(); !why.empty()) return "fabric." + why;
  if (!(pressure > 0.0 && pressure <= 1e7))
    return fmt::format("pressure = {} Pa: must lie in (0, 1e7]", pressure);
  if (!(wet_stiffness_scale > 0.0 && wet_stiffness_scale <= 1.0))
    return fmt::format("wet_stiffness_scale = {}: must lie in (0, 1]", wet_stiffness_scale);
  if (!(mass_scale >= 1.0 && mass_scale <= 1e8))
    return fmt::format("mass_scale = {}: must lie in [1, 1e8]", mass_scale);
  if (!(damping_time > 0.0 && damping_time <= 1.0))
    return fmt::format("damping_time = {} s: must lie in (0, 1]", damping_time);
  if (!(settle_kinetic_ratio > 0.0 && settle_kinetic_ratio < 1.0))
    return fmt::format("settle_kinetic_ratio = {}: must lie in (0, 1)", settle_kinetic_ratio);
  if (bonding)
    if (std::string why = bonding->Validate(); !why.empty()) return "bonding." + why;
  if (max_steps < 1) return fmt::format("max_steps = {}: must be >= 1", max_steps);
  return {};
}

ThroughAirResult DryThroughAir(Network& net, const SheetSpec& sheet, const ThroughAirSettings& s,
                               const Progress& progress) {
  World& w = net.world;
  Particles& p = w.particles;
  ThroughAirResult result;
  const double total_mass = net.TotalMass();
  const double basis_weight = total_mass / net.Area();  // [kg/m^2]
  const double mean_mass = total_mass / static_cast<double>(p.size());
  // The air load from the true masses, before mass scaling.
  const std::shared_ptr<const Relief> fabric = MakeRelief(s.fabric, w.cell, -1.0);
  std::vector<Vec3> air(p.size());
  for (std::size_t i = 0; i < p.size(); ++i)
    air[i] = Vec3(0.0, 0.0, -s.pressure * ReliefLevel(*fabric, p.x[i].x(), p.x[i].y()) *
                                p.mass[i] / basis_weight);
  const SavedMasses masses = ScaleMasses(w, s.mass_scale);
  const std::vector<BeamBondParams> dry_types = ScaleFibreStiffness(net, s.wet_stiffness_scale);

  w.physics = Physics{};
  w.physics.contacts = true;
  w.physics.friction = w.contact.mu > 0.0;
  w.physics.drag = true;
  w.physics.drag_coefficient = mean_mass * s.mass_scale / s.damping_time;
  w.physics.applied_loads = true;
  w.applied_force = air;
  w.applied_torque.assign(p.size(), Vec3::Zero());
  w.walls.resize(1);
  w.walls[0] = Wall{};
  w.walls[0].relief = fabric;
  UseSheetStepSettings(w, sheet);

  Simulation sim(w);
  if (std::string warn = sim.Prepare(); !warn.empty()) result.warnings.push_back(warn);
  result.dt = w.settings.dt;
  const std::int64_t step0 = w.step;
  // At rest: kinetic energy below settle_kinetic_ratio x the kinetic energy of the web
  // drifting freely under the air load against the drag (v_i = f_i / c). A creeping,
  // overdamped web has kinetic / work ~ damping_time / t however far it still has to go, so
  // the air's work is no scale to settle against; the free drift is.
  double drift_energy = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double v = air[i].norm() / w.physics.drag_coefficient;
    drift_energy += 0.5 * p.mass[i] * v * v;
  }
  drift_energy = std::max(drift_energy, 1e-300);
  double kinetic = 0.0;
  const double work0 = w.energy.work_applied;
  const std::int64_t chunk = 200;
  auto at_rest = [&](double t_start) {
    return [&, t_start] {
      kinetic = KineticEnergy(w);
      return w.time - t_start >= 5.0 * s.damping_time &&
             kinetic < s.settle_kinetic_ratio * drift_energy;
    };
  };
  auto status = [&](const char* phase) {
    return [&, phase] {
      return fmt::format("through-air drying: {}, step {}, kinetic / free drift {:.3g}", phase,
                         w.step, kinetic / drift_energy);
    };
  };

  // 1. Moulding: the air draws the web into the fabric's pockets until it is at rest.
  RunUntil(sim, s.max_steps, chunk, at_rest(w.time), status("moulding"), progress);
  if (!(kinetic < s.settle_kinetic_ratio * drift_energy))
    result.warnings.push_back("through-air drying: the web did not come to rest on the fabric");
  result.air_work = w.energy.work_applied - work0;
  result.imprint_moulded = Imprint(w, *fabric);

  // 2. Bonds form in the moulded state (the sheet dries there).
  if (s.bonding) {
    result.bonds_formed = FormFibreFibreBonds(net, *s.bonding);
    if (s.set_fibre_shape) SetFibreShape(net);
    progress.Say(fmt::format("through-air drying: {} fibre-fibre bonds formed",
                             result.bonds_formed));
  } else if (s.set_fibre_shape) {
    SetFibreShape(net);
  }
  // 3. Dry: the fibres take their dry stiffness (the fibre-fibre bond types added above
  // stay), the air stops, and the sheet leaves the fabric for a flat support at z = 0 (the
  // whole sheet moved so that its lowest particle just touches it) and springs back.
  std::copy(dry_types.begin(), dry_types.end(), w.bonds.types.begin());
  w.physics.applied_loads = false;
  double lowest = INFINITY;
  for (std::size_t i = 0; i < p.size(); ++i) lowest = std::min(lowest, p.x[i].z() - p.radius[i]);
  for (Vec3& x : p.x) x.z() -= lowest;
  w.walls[0] = Wall{};
  w.settings.dt = 0.0;  // the dry fibres are stiffer: a new time step
  if (std::string warn = sim.Prepare(); !warn.empty()) result.warnings.push_back(warn);
  RunUntil(sim, s.max_steps, chunk, at_rest(w.time), status("springback"), progress);
  result.settled = kinetic < s.settle_kinetic_ratio * drift_energy;
  if (!result.settled)
    result.warnings.push_back("through-air drying: the springback did not come to rest");
  result.imprint = Imprint(w, *fabric);

  result.steps = w.step - step0;
  RestoreMasses(w, masses);
  w.physics = Physics{};
  w.applied_force.clear();
  w.applied_torque.clear();
  return result;
}

}  // namespace fibrenet::pipeline
