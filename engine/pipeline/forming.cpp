#include "engine/pipeline/forming.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <fmt/format.h>

#include "engine/core/energy.h"
#include "engine/core/error.h"
#include "engine/core/morton.h"
#include "engine/core/simulation.h"
#include "engine/pipeline/pairs.h"

namespace fibrenet::pipeline {

namespace {

constexpr double kGravity = 9.81;  // [m/s^2]

// Uniformly distributed rotation (Shoemake's method).
Quat RandomRotation(std::mt19937_64& rng) {
  const double u1 = UniformUnit(rng), u2 = UniformUnit(rng), u3 = UniformUnit(rng);
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  return Quat(b * std::cos(2 * kPi * u3), a * std::sin(2 * kPi * u2), a * std::cos(2 * kPi * u2),
              b * std::sin(2 * kPi * u3));
}

Quat Orient(Orientation o, std::mt19937_64& rng) {
  if (o == Orientation::kIsotropic) return RandomRotation(rng);
  return Quat(Eigen::AngleAxisd(2 * kPi * UniformUnit(rng), Vec3::UnitZ()));
}

bool Overlaps(const World& w, const ParticleGrid& grid, const std::vector<Vec3>& x, double radius,
              std::vector<std::int32_t>& near) {
  for (const Vec3& c : x) {
    grid.Near(c, near);
    for (const std::int32_t j : near) {
      const double reach = radius + w.particles.radius[j];
      if (w.cell.Delta(c, w.particles.x[j]).squaredNorm() < reach * reach) return true;
    }
  }
  return false;
}

// The placed fibres again, laid out in memory in the Morton order of the tiles (half the
// longest fibre wide) that hold their centres. Fibres touch and bond where they lie near each
// other in the plane; with memory following the plane, the particles a contact or a bond joins
// are read from nearby memory, and each thread's range of particles is a patch of the sheet
// (docs/performance.md). Each fibre keeps its particles' positions exactly.
Network InSpatialOrder(const Network& placed, const std::vector<FibreProperties>& fibres,
                       const std::vector<Vec3>& centres, const FibreBondOptions& options) {
  double longest = 0.0;
  for (const FibreProperties& f : fibres) longest = std::max(longest, f.length);
  const Vec3 lo = placed.world.cell.lo;
  const double tile = std::max(0.5 * longest, 1e-12);
  std::vector<std::uint32_t> key(fibres.size());
  for (std::size_t f = 0; f < fibres.size(); ++f) {
    const auto tx = static_cast<std::uint32_t>(std::max(0.0, (centres[f].x() - lo.x()) / tile));
    const auto ty = static_cast<std::uint32_t>(std::max(0.0, (centres[f].y() - lo.y()) / tile));
    key[f] = MortonKey(tx, ty);
  }
  std::vector<std::size_t> order(fibres.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return key[a] < key[b]; });
  Network out;
  out.world.cell = placed.world.cell;
  out.world.contact = placed.world.contact;
  const Particles& p = placed.world.particles;
  for (const std::size_t f : order) {
    const FibreRecord& r = placed.fibres[f];
    const std::vector<Vec3> x(p.x.begin() + r.first_particle,
                              p.x.begin() + r.first_particle + r.particle_count);
    out.AddFibre(fibres[f], x, options);
  }
  return out;
}

}  // namespace

std::string SheetSpec::Validate() const {
  if (!(Lx > 0.0 && Ly > 0.0 && Lx <= 1.0 && Ly <= 1.0))
    return fmt::format("cell size {} x {} m: each side must lie in (0, 1] m", Lx, Ly);
  if (!(basis_weight > 0.0 && basis_weight <= 1.0))
    return fmt::format("basis_weight = {} kg/m^2: must lie in (0, 1]", basis_weight);
  if (std::string why = fibres.Validate(); !why.empty()) return "fibres." + why;
  if (fibres.length.Mean() >= std::min(Lx, Ly))
    return fmt::format("fibre length {} m: the mean fibre must be shorter than the cell side {} m",
                       fibres.length.Mean(), std::min(Lx, Ly));
  if (!(particle_spacing >= 0.25 && particle_spacing <= 10.0))
    return fmt::format("particle_spacing = {} diameters: must lie in [0.25, 10]", particle_spacing);
  if (!(inertia_scale >= 1.0 && inertia_scale <= 1e6))
    return fmt::format("inertia_scale = {}: must lie in [1, 1e6]", inertia_scale);
  if (!(time_step_safety > 0.0 && time_step_safety <= 1.0))
    return fmt::format("time_step_safety = {}: must lie in (0, 1]", time_step_safety);
  if (!(neighbour_skin > 0.0 && neighbour_skin <= 5.0))
    return fmt::format("neighbour_skin = {}: must lie in (0, 5] radii", neighbour_skin);
  if (std::string why = contact.Validate(); !why.empty()) return "contact: " + why;
  return {};
}

std::string FormingSettings::Validate() const {
  if (!(consistency > 0.0 && consistency < 1.0))
    return fmt::format("consistency = {}: must lie in (0, 1)", consistency);
  if (!(suspension_density > 0.0 && suspension_density <= 1e5))
    return fmt::format("suspension_density = {} kg/m^3: must lie in (0, 1e5]", suspension_density);
  if (!(drop_gap >= 0.0 && drop_gap <= 1.0))
    return fmt::format("drop_gap = {} m: must lie in [0, 1]", drop_gap);
  if (!(terminal_velocity > 0.0 && terminal_velocity <= 100.0))
    return fmt::format("terminal_velocity = {} m/s: must lie in (0, 100]", terminal_velocity);
  if (!(air_velocity >= 0.0 && air_velocity <= 100.0))
    return fmt::format("air_velocity = {} m/s: must lie in [0, 100]", air_velocity);
  if (!(mass_scale >= 1.0 && mass_scale <= 1e8))
    return fmt::format("mass_scale = {}: must lie in [1, 1e8]", mass_scale);
  if (!(gravity_scale >= 1.0 && gravity_scale <= 1e8))
    return fmt::format("gravity_scale = {}: must lie in [1, 1e8]", gravity_scale);
  if (!(stiffness_scale > 0.0 && stiffness_scale <= 1.0))
    return fmt::format("stiffness_scale = {}: must lie in (0, 1]", stiffness_scale);
  if (!(settle_kinetic_ratio > 0.0 && settle_kinetic_ratio < 1.0))
    return fmt::format("settle_kinetic_ratio = {}: must lie in (0, 1)", settle_kinetic_ratio);
  if (max_steps < 1) return fmt::format("max_steps = {}: must be >= 1", max_steps);
  if (placement_attempts < 1)
    return fmt::format("placement_attempts = {}: must be >= 1", placement_attempts);
  return {};
}

Network PlaceFibres(const SheetSpec& sheet, const FormingSettings& forming,
                    std::mt19937_64& rng, PlacementStats* stats) {
  Network net;
  World& w = net.world;
  w.cell.lo = Vec3::Zero();
  w.cell.hi = Vec3(sheet.Lx, sheet.Ly, 1.0);
  w.cell.periodic_x = w.cell.periodic_y = true;
  w.contact = sheet.contact;
  w.contact.Derive();

  // Sample fibres until their total mass is nearest the target.
  const double target = sheet.basis_weight * net.Area();
  std::vector<FibreProperties> fibres;
  double mass = 0.0;
  for (;;) {
    FibreProperties f = SampleFibre(sheet.fibres, rng);
    if (mass + 0.5 * f.Mass() > target) break;
    mass += f.Mass();
    fibres.push_back(std::move(f));
  }
  if (fibres.empty())
    throw InputError(fmt::format(
        "basis weight x cell area = {:.3g} kg holds less than half a fibre ({:.3g} kg): enlarge "
        "the cell or the basis weight", target, sheet.fibres.coarseness.Mean() * sheet.fibres.length.Mean()));

  const double box_height = mass / (forming.consistency * forming.suspension_density * net.Area());
  const double z_lo = forming.drop_gap;
  w.cell.hi.z() = z_lo + box_height;
  double d_max = 0.0;
  for (const auto& f : fibres) d_max = std::max(d_max, f.diameter);
  ParticleGrid grid(w.cell, d_max);

  const FibreBondOptions options{sheet.fibres.maxwell_tau, sheet.fibres.yield_moment,
                                 sheet.inertia_scale};
  int overlapping = 0;
  std::vector<std::int32_t> near;
  std::vector<Vec3> x, centres;
  for (const FibreProperties& f : fibres) {
    const int n = ParticlesPerFibre(f.length, sheet.particle_spacing * f.diameter);
    std::vector<Vec3> local = PointsAlong(Centreline(f), n);
    Vec3 centroid = Vec3::Zero();
    for (const Vec3& c : local) centroid += c;
    centroid /= n;
    for (Vec3& c : local) c -= centroid;
    const double r = 0.5 * f.diameter;
    bool clear = false;
    Vec3 at_placed = Vec3::Zero();
    for (int attempt = 0; attempt < forming.placement_attempts && !clear; ++attempt) {
      const Quat q = Orient(forming.orientation, rng);
      x.resize(n);
      double lo = 0.0, hi = 0.0;
      for (int k = 0; k < n; ++k) {
        x[k] = q * local[k];
        lo = std::min(lo, x[k].z());
        hi = std::max(hi, x[k].z());
      }
      // Centre height such that the whole fibre (with its radius) lies inside the box.
      const double z_min = z_lo + r - lo, z_max = z_lo + box_height - r - hi;
      const double ux = UniformUnit(rng), uy = UniformUnit(rng), uz = UniformUnit(rng);
      const Vec3 at(ux * sheet.Lx, uy * sheet.Ly,
                    z_max > z_min ? z_min + uz * (z_max - z_min) : 0.5 * (z_min + z_max));
      for (Vec3& c : x) c += at;
      at_placed = at;
      clear = !Overlaps(w, grid, x, r, near);
    }
    overlapping += !clear;
    centres.push_back(at_placed);
    const std::int32_t first = static_cast<std::int32_t>(w.particles.size());
    net.AddFibre(f, x, options);
    for (int k = 0; k < n; ++k) grid.Insert(first + k, w.particles.x[first + k]);
  }
  if (stats) {
    stats->box_height = box_height;
    stats->overlapping_fibres = overlapping;
  }
  return InSpatialOrder(net, fibres, centres, options);
}

FormingResult Settle(Network& net, const SheetSpec& sheet, const FormingSettings& forming,
                     const Progress& progress) {
  World& w = net.world;
  const SavedMasses masses = ScaleMasses(w, forming.mass_scale);
  const std::vector<BeamBondParams> types = ScaleFibreStiffness(net, forming.stiffness_scale);

  const double g = kGravity * forming.gravity_scale;
  const double v_t = forming.terminal_velocity * std::sqrt(forming.gravity_scale);
  const double total_mass = net.TotalMass();
  const double mean_mass = total_mass / static_cast<double>(w.particles.size());
  w.physics = Physics{};
  w.physics.gravity = true;
  w.physics.g = Vec3(0.0, 0.0, -g);
  w.physics.drag = true;
  w.physics.drag_coefficient = mean_mass * g / v_t;
  w.physics.air_velocity = Vec3(0.0, 0.0, -forming.air_velocity * std::sqrt(forming.gravity_scale));
  w.physics.contacts = true;
  w.physics.friction = w.contact.mu > 0.0;
  w.walls.assign(1, Wall{});  // the forming wire at z = 0
  UseSheetStepSettings(w, sheet);

  Simulation sim(w);
  FormingResult result;
  result.dt_warning = sim.Prepare();
  result.dt = w.settings.dt;
  const double t0 = w.time;
  const double tau = v_t / g;  // drag relaxation time
  const double v_fall = v_t + forming.air_velocity * std::sqrt(forming.gravity_scale);
  const double ke_ref = 0.5 * total_mass * v_fall * v_fall;
  const auto check_every = std::clamp<std::int64_t>(
      static_cast<std::int64_t>(0.1 * tau / w.settings.dt), 10, 2000);
  double ratio = 1.0;
  auto done = [&] {
    ratio = KineticEnergy(w) / ke_ref;
    return w.time - t0 > 3.0 * tau && ratio < forming.settle_kinetic_ratio;
  };
  auto status = [&] {
    double z_top = 0.0;
    for (const Vec3& x : w.particles.x) z_top = std::max(z_top, x.z());
    return fmt::format("forming: step {} t = {:.4g} s, kinetic ratio {:.3g} (settled below {:.3g}), "
                       "highest particle {:.0f} um",
                       w.step, w.time - t0, ratio, forming.settle_kinetic_ratio, z_top * 1e6);
  };
  result.steps = RunUntil(sim, forming.max_steps, check_every, done, status, progress);
  result.simulated_time = w.time - t0;
  result.kinetic_ratio = ratio;
  result.settled = w.time - t0 > 3.0 * tau && ratio < forming.settle_kinetic_ratio;

  RestoreMasses(w, masses);
  w.bonds.types = types;
  w.physics.gravity = false;
  w.physics.drag = false;
  w.physics.air_velocity = Vec3::Zero();
  return result;
}

}  // namespace fibrenet::pipeline
