#include "engine/pipeline/creping.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <random>
#include <utility>

#include <fmt/format.h>

#include "engine/core/energy.h"
#include "engine/core/error.h"
#include "engine/core/parallel.h"
#include "engine/core/simulation.h"
#include "engine/pipeline/crepe_profile.h"
#include "engine/pipeline/peel_front.h"
#include "engine/pipeline/percentile.h"
#include "engine/pipeline/reel.h"
#include "engine/pipeline/test_rig.h"

namespace fibrenet::pipeline {

namespace {

constexpr int kStrengthClasses = 16;

// x with Phi(x) = q for the standard normal distribution, by bisection on erfc.
double NormalQuantile(double q) {
  double lo = -10.0, hi = 10.0;
  for (int k = 0; k < 100; ++k) {
    const double mid = 0.5 * (lo + hi);
    (0.5 * std::erfc(-mid / std::sqrt(2.0)) < q ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// Strength factors of equiprobable classes of a lognormal distribution of mean 1.
std::vector<double> StrengthClasses(double cv) {
  if (cv <= 0.0) return {1.0};
  const double sigma2 = std::log1p(cv * cv), sigma = std::sqrt(sigma2);
  std::vector<double> f(kStrengthClasses);
  for (int k = 0; k < kStrengthClasses; ++k)
    f[k] = std::exp(-0.5 * sigma2 + sigma * NormalQuantile((k + 0.5) / kStrengthClasses));
  return f;
}

// Pieces of the sheet: connected components of the first n particles over intact fibre and
// fibre-fibre bonds. Returns each particle's piece label.
std::vector<std::int32_t> Pieces(const World& w, std::size_t n) {
  std::vector<std::int32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](std::int32_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  const Bonds& b = w.bonds;
  for (std::size_t k = 0; k < b.size(); ++k) {
    if (b.broken[k] || b.kind[k] == BondKind::kAdhesive) continue;
    const std::int32_t a = find(b.i[k]), c = find(b.j[k]);
    if (a != c) parent[std::max(a, c)] = std::min(a, c);
  }
  for (std::size_t i = 0; i < n; ++i) parent[i] = find(static_cast<std::int32_t>(i));
  return parent;
}

// The sheet seen from a frame with origin `origin` and axes (e_u, y, e_h).
std::vector<FramePoint> InFrame(const Particles& p, const std::vector<std::size_t>& which,
                                const Vec3& origin, const Vec3& e_u, const Vec3& e_h) {
  std::vector<FramePoint> pts;
  pts.reserve(which.size());
  for (std::size_t i : which) {
    const Vec3 rel = p.x[i] - origin;
    pts.push_back({Vec3(rel.dot(e_u), p.x[i].y(), rel.dot(e_h)), p.radius[i]});
  }
  return pts;
}

// The crepe band of the settings, its automatic limits from the creped sheet's particles. The
// texture filter needs a few profile bins per wavelength.
CrepeBand CrepeBandOf(const CrepingSettings& s, const Particles& p,
                      const std::vector<std::size_t>& sheet, double bin) {
  double radius = 0.0;
  for (std::size_t i : sheet) radius += p.radius[i] / static_cast<double>(sheet.size());
  CrepeBand band;
  band.cutoff = s.crepe_cutoff;
  band.shortest_wavelength =
      s.crepe_shortest_wavelength > 0.0 ? s.crepe_shortest_wavelength : 8.0 * radius;
  band.shortest_wavelength =
      std::min(std::max(band.shortest_wavelength, 4.0 * bin), 0.5 * band.cutoff);
  band.min_amplitude = s.crepe_min_amplitude > 0.0 ? s.crepe_min_amplitude : radius;
  return band;
}

// Drops the particles from n on and the bonds and bond types from the given counts on (the
// anchors and their adhesive bonds, all appended after the sheet's).
void DropAnchors(World& w, std::size_t n, std::size_t bonds, std::size_t types) {
  Particles& p = w.particles;
  for (auto* v : {&p.x, &p.v, &p.omega, &p.force, &p.torque}) v->resize(n);
  p.q.resize(n);
  for (auto* v : {&p.radius, &p.mass, &p.inv_mass, &p.inertia, &p.inv_inertia}) v->resize(n);
  p.fibre.resize(n);
  Bonds& b = w.bonds;
  b.i.resize(bonds);
  b.j.resize(bonds);
  b.type.resize(bonds);
  b.kind.resize(bonds);
  b.state.resize(bonds);
  b.broken.resize(bonds);
  if (!b.damping_factors.empty()) b.damping_factors.resize(bonds);
  b.types.resize(types);
  std::erase_if(b.events, [&](const BondBreakEvent& e) {
    return e.bond >= static_cast<std::int32_t>(bonds);
  });
}

// The creped sheet, free of blade and coating, comes to rest on the floor (dynamic relaxation
// with scaled masses and background drag, as the pressing's springback).
void RelaxCrepedSheet(Network& net, const SheetSpec& sheet, const CrepingSettings& s,
                      const Progress& progress, CrepingResult& out) {
  World& w = net.world;
  const double strain = MeasureEnergy(w).strain.Total();
  out.relaxed = !(strain > 0.0);  // nothing stored, nothing to release
  if (s.relax_max_steps == 0 || out.relaxed) return;
  const SavedMasses masses = ScaleMasses(w, s.relax_mass_scale);
  // The drag acts on translation only: bond dashpots take out the particles' rotational
  // ringing, which would otherwise trade energy with the bonds for ever.
  const std::vector<BeamBondParams> bond_types = w.bonds.types;
  AddBondDamping(w, s.relax_bond_damping_ratio);
  w.physics.drag = true;
  w.physics.drag_coefficient = net.TotalMass() / double(w.particles.size()) / s.relax_damping_time;
  UseSheetStepSettings(w, sheet);
  w.neighbours.Invalidate();
  Simulation sim(w);
  if (std::string warning = sim.Prepare(); !warning.empty()) out.warnings.push_back(warning);
  // At rest: the kinetic energy is a small fraction of the strain energy, or the strain
  // energy has stopped changing (within relax_energy_tolerance over 50 damping times): the
  // folds that friction holds may keep creeping without ever quite stopping.
  const double t0 = w.time, window = 50.0 * s.relax_damping_time;
  double kinetic = 0.0, energy = strain, window_start = t0, window_energy = strain, change = 1.0;
  auto at_rest = [&] {
    kinetic = KineticEnergy(w);
    if (w.time - window_start >= window) {
      energy = MeasureEnergy(w).strain.Total();
      change = std::abs(energy - window_energy) / std::max(window_energy, 1e-300);
      window_start = w.time;
      window_energy = energy;
      if (change < s.relax_energy_tolerance) return true;
    }
    return w.time - t0 >= 5.0 * s.relax_damping_time && kinetic < s.relax_kinetic_ratio * energy;
  };
  auto status = [&] {
    return fmt::format("creping: the creped sheet relaxes, kinetic / strain energy {:.3g} "
                       "(at rest below {:.3g}), strain energy change {:.3g} over the last "
                       "window (at rest below {:.3g})",
                       kinetic / energy, s.relax_kinetic_ratio, change, s.relax_energy_tolerance);
  };
  const std::int64_t chunk = std::clamp<std::int64_t>(
      static_cast<std::int64_t>(0.5 * s.relax_damping_time / w.settings.dt), 10, 2000);
  out.relax_steps = RunUntil(sim, s.relax_max_steps, chunk, at_rest, status, progress);
  out.relaxed = change < s.relax_energy_tolerance || kinetic < s.relax_kinetic_ratio * energy;
  if (!out.relaxed)
    out.warnings.push_back(fmt::format(
        "creping: the creped sheet did not come to rest in {} steps (kinetic / strain energy "
        "{:.3g}, strain energy change {:.3g} over the last {:.3g} s); raise "
        "creping.relax_max_steps", out.relax_steps, kinetic / energy, change, window));
  RestoreMasses(w, masses);
  w.bonds.types = bond_types;
  w.bonds.damping_factors.clear();
  w.physics.drag = false;
  for (std::size_t i = 0; i < w.particles.size(); ++i) {
    w.particles.v[i].setZero();
    w.particles.omega[i].setZero();
  }
}

// The rotation that lays the creped sheet along x: rows its MD axis (the principal axis of
// its mass in the x-z plane, pointing up the face like `face_up`), y, and the normal that
// makes the rotation proper. A sheet the reel drew up the face lies along the face; one
// thrown off the Yankee at a tilt is laid along its own length, not foreshortened onto the
// face's direction.
Mat3 SheetAxes(const Particles& p, const std::vector<std::size_t>& sheet, const Vec3& face_up) {
  double m = 0.0, cx = 0.0, cz = 0.0;
  for (std::size_t i : sheet) {
    m += p.mass[i];
    cx += p.mass[i] * p.x[i].x();
    cz += p.mass[i] * p.x[i].z();
  }
  cx /= m;
  cz /= m;
  double xx = 0.0, xz = 0.0, zz = 0.0;
  for (std::size_t i : sheet) {
    const double dx = p.x[i].x() - cx, dz = p.x[i].z() - cz;
    xx += p.mass[i] * dx * dx;
    xz += p.mass[i] * dx * dz;
    zz += p.mass[i] * dz * dz;
  }
  const double angle = 0.5 * std::atan2(2.0 * xz, xx - zz);
  Vec3 axis(std::cos(angle), 0.0, std::sin(angle));
  if (axis.dot(face_up) < 0.0) axis = -axis;
  Mat3 R;
  R.row(0) = axis.transpose();
  R.row(1) = Vec3::UnitY().transpose();
  R.row(2) = Vec3(-axis.z(), 0.0, axis.x()).transpose();
  return R;
}

// Plate caliper of the whole sheet in its own frame (x along MD, z up) over [x0, x1], as
// the crepe profile reads it: the same measure before creping and at rest after.
double SheetCaliper(const World& w, double x0, double x1, const MetricsSettings& metrics) {
  std::vector<std::size_t> all(w.particles.size());
  std::iota(all.begin(), all.end(), std::size_t{0});
  return MeasureCrepeProfile(InFrame(w.particles, all, Vec3::Zero(), Vec3::UnitX(), Vec3::UnitZ()),
                             x0, x1, metrics.profile_bin, w.cell.lo.y(), w.cell.hi.y(),
                             metrics.thickness_grid, metrics.surface_percentile)
      .caliper;
}

}  // namespace

std::string CrepingSettings::Validate() const {
  if (!(yankee_speed > 0.0 && yankee_speed <= 200.0))
    return fmt::format("yankee_speed = {} m/s: must lie in (0, 200]", yankee_speed);
  const double deg = 180.0 / 3.14159265358979323846;
  if (!(creping_angle * deg >= 30.0 && creping_angle * deg <= 150.0))
    return fmt::format("creping_angle = {} deg: must lie in [30, 150]", creping_angle * deg);
  if (!(crepe_ratio >= 0.0 && crepe_ratio <= 2.0))
    return fmt::format("crepe_ratio = {}: must lie in [0, 2]", crepe_ratio);
  if (!(takeaway_height >= 0.0 && takeaway_height <= 0.1))
    return fmt::format("takeaway_height = {} m: must lie in [0, 0.1] (0 = 3 x the caliper)", takeaway_height);
  if (!(takeaway_time > 0.0 && takeaway_time <= 1.0))
    return fmt::format("takeaway_time = {} s: must lie in (0, 1]", takeaway_time);
  if (!(tip_clearance >= 0.0 && tip_clearance <= 1e-3))
    return fmt::format("tip_clearance = {} m: must lie in [0, 1e-3]", tip_clearance);
  if (!(run_in_length >= 0.0 && run_in_length <= 0.1))
    return fmt::format("run_in_length = {} m: must lie in [0, 0.1] (0 = off)", run_in_length);
  if (!(crepe_cutoff >= 1e-4 && crepe_cutoff <= 0.02))
    return fmt::format("crepe_cutoff = {} m: must lie in [1e-4, 0.02]", crepe_cutoff);
  if (!(crepe_shortest_wavelength >= 0.0 && crepe_shortest_wavelength <= 0.5 * crepe_cutoff))
    return fmt::format(
        "crepe_shortest_wavelength = {} m: must lie in [0, {}] (0 = 4 particle "
        "diameters; at most half the crepe cutoff)",
        crepe_shortest_wavelength, 0.5 * crepe_cutoff);
  if (!(crepe_min_amplitude >= 0.0 && crepe_min_amplitude <= 1e-2))
    return fmt::format("crepe_min_amplitude = {} m: must lie in [0, 0.01] (0 = a particle radius)",
                       crepe_min_amplitude);
  if (curve_samples < 2 || curve_samples > 100000)
    return fmt::format("curve_samples = {}: must lie in [2, 100000]", curve_samples);
  if (impact_frames < 0 || impact_frames > 1000)
    return fmt::format("impact_frames = {}: must lie in [0, 1000]", impact_frames);
  if (max_steps < 1) return fmt::format("max_steps = {}: must be >= 1", max_steps);
  if (!(relax_mass_scale >= 1.0 && relax_mass_scale <= 1e8))
    return fmt::format("relax_mass_scale = {}: must lie in [1, 1e8]", relax_mass_scale);
  if (!(relax_damping_time > 0.0 && relax_damping_time <= 1.0))
    return fmt::format("relax_damping_time = {} s: must lie in (0, 1]", relax_damping_time);
  if (!(relax_kinetic_ratio > 0.0 && relax_kinetic_ratio < 1.0))
    return fmt::format("relax_kinetic_ratio = {}: must lie in (0, 1)", relax_kinetic_ratio);
  if (!(end_zone_fraction >= 0.0 && end_zone_fraction <= 0.45))
    return fmt::format("end_zone_fraction = {}: must lie in [0, 0.45]", end_zone_fraction);
  if (!(relax_bond_damping_ratio >= 0.0 && relax_bond_damping_ratio <= 1.0))
    return fmt::format("relax_bond_damping_ratio = {}: must lie in [0, 1]", relax_bond_damping_ratio);
  if (!(relax_energy_tolerance > 0.0 && relax_energy_tolerance < 1.0))
    return fmt::format("relax_energy_tolerance = {}: must lie in (0, 1)", relax_energy_tolerance);
  if (relax_max_steps < 0) return fmt::format("relax_max_steps = {}: must be >= 0", relax_max_steps);
  if (!(blade_hard_stiffness >= 0.0 && blade_hard_stiffness <= 1e9))
    return fmt::format("blade_hard_stiffness = {} N/m: must lie in [0, 1e9]", blade_hard_stiffness);
  if (!(fibre_hard_stiffness >= 0.0 && fibre_hard_stiffness <= 1e9))
    return fmt::format("fibre_hard_stiffness = {} N/m: must lie in [0, 1e9]", fibre_hard_stiffness);
  if (blade_friction_mu && !(*blade_friction_mu >= 0.0 && *blade_friction_mu <= 10.0))
    return fmt::format("blade_friction_mu = {}: must lie in [0, 10]", *blade_friction_mu);
  if (std::string why = adhesion.Validate(); !why.empty()) return "adhesion." + why;
  return {};
}

CrepingResult Crepe(Network& net, const SheetSpec& sheet, const CrepingSettings& s,
                    const MetricsSettings& metrics, std::uint64_t seed, const Progress& progress) {
  if (std::string why = s.Validate(); !why.empty()) throw InputError("creping." + why);
  World& w = net.world;
  Particles& p = w.particles;
  CrepingResult out;
  const std::size_t n_sheet = p.size(), n_bonds = w.bonds.size(), n_types = w.bonds.types.size();
  if (n_sheet == 0) throw Error("Crepe: empty network");

  // The sheet before creping, as a finite strip along MD.
  const double x0 = w.cell.lo.x(), x1 = w.cell.hi.x(), Ly = w.cell.Ly();
  const double y_bin = metrics.thickness_grid, u_bin = metrics.profile_bin;
  out.caliper_before = SheetCaliper(w, x0, x1, metrics);
  const double takeaway = s.takeaway_height > 0.0 ? s.takeaway_height : 3.0 * out.caliper_before;
  const double run_out = 2.0 * takeaway * (1.0 + s.crepe_ratio);
  const double cot = std::cos(s.creping_angle) / std::sin(s.creping_angle);
  out.bonds_cut = CutAlongX(net, run_out + takeaway + std::abs(cot) * (x1 - x0) + 1e-4);

  // Fibre-fibre bonds of the whole strip, and of its middle: the strip's cut ends (the
  // blade's first blow on the leading end, the last glued stretch of the trailing end) have
  // no counterpart in a continuous sheet.
  std::vector<std::size_t> fibre_fibre, fibre_fibre_middle;
  std::size_t fibre_bonds_intact = 0;
  const double end_zone = s.end_zone_fraction * (x1 - x0);
  if (s.run_in_length > end_zone)
    throw InputError(fmt::format(
        "creping.run_in_length_um = {:.4g}: the run-in must end within the leading end zone, "
        "whose bonds the metrics leave out; accepted: [0, {:.4g}] um (end_zone_fraction x the "
        "{:.4g} um strip)", s.run_in_length * 1e6, end_zone * 1e6, (x1 - x0) * 1e6));
  for (std::size_t b = 0; b < n_bonds; ++b) {
    if (w.bonds.broken[b]) continue;
    if (w.bonds.kind[b] == BondKind::kFibreFibre) {
      fibre_fibre.push_back(b);
      const double x = p.x[w.bonds.i[b]].x();
      if (x >= x0 + end_zone && x <= x1 - end_zone) fibre_fibre_middle.push_back(b);
    }
    fibre_bonds_intact += w.bonds.kind[b] == BondKind::kFibre;
  }

  // Physics of the impact: contacts and friction, no body loads but the reel's draw.
  w.physics.gravity = false;
  w.physics.drag = false;
  w.physics.contacts = true;
  w.physics.friction = w.contact.mu > 0.0;
  w.physics.applied_loads = true;
  const double hard_stiffness_before = w.contact.normal.hard_stiffness;
  w.contact.normal.hard_stiffness = s.fibre_hard_stiffness;
  w.walls.assign(1, Wall{});  // the Yankee surface, at rest in its own frame, steel like the blade
  w.walls[0].hard_stiffness = s.blade_hard_stiffness;
  w.blades.clear();

  // Glue the bottom particles to anchors, their mirror images under the surface.
  const AdhesionSettings& a = s.adhesion;
  const std::vector<double> classes = StrengthClasses(a.strength_cv);
  std::mt19937_64 rng(seed ^ 0x6372657065ULL);
  std::uniform_int_distribution<int> pick(0, static_cast<int>(classes.size()) - 1);
  struct GlueType {
    std::int32_t id;
    double mass, inertia;  // of the particle its dashpots are sized for
  };
  std::map<std::pair<double, int>, GlueType> types;
  // With the coating's damping each glue bond carries its own particle's factors; the
  // factors this stage adds go with its anchors.
  const bool damped_glue = a.damping_ratio > 0.0;
  const bool added_factors = damped_glue && w.bonds.damping_factors.empty();
  if (damped_glue) w.bonds.damping_factors.resize(w.bonds.size());
  double r_max = 0.0, x_front = -1e300;
  const double sheet_mass = net.TotalMass();  // before the anchors join the particles
  std::vector<GlueSite> glue_sites;
  double glue_energy = 0.0;  // what the glued particles store when they fail in peel [J]
  for (std::size_t i = 0; i < n_sheet; ++i) {
    r_max = std::max(r_max, p.radius[i]);
    x_front = std::max(x_front, p.x[i].x() + p.radius[i] + std::abs(cot) * p.x[i].z());
    const double z = p.x[i].z(), R = p.radius[i];
    if (!(z > 0.0 && z - R <= a.reach * R)) continue;
    const int c = pick(rng);
    auto it = types.find({R, c});
    if (it == types.end()) {
      const BeamBondParams glue = GlueBond(a, R, p.mass[i], p.inertia[i], classes[c]);
      const GlueType type{w.bonds.AddType(glue), p.mass[i], p.inertia[i]};
      it = types.emplace(std::make_pair(R, c), type).first;
    }
    const std::size_t anchor =
        p.Add(Vec3(p.x[i].x(), p.x[i].y(), -z), R, p.mass[i], -1, sheet.inertia_scale);
    p.Fix(anchor);
    const std::size_t bond =
        w.bonds.Add(static_cast<std::int32_t>(i), static_cast<std::int32_t>(anchor), it->second.id,
                    BondKind::kAdhesive, MakeBondState(p.x[anchor] - p.x[i], p.q[i], p.q[anchor]));
    if (damped_glue)
      w.bonds.damping_factors[bond] =
          GlueDampingFactors(p.mass[i], p.inertia[i], it->second.mass, it->second.inertia);
    glue_sites.push_back({p.x[i].x(), bond});
    const BeamBondParams& glue = w.bonds.types[it->second.id];
    glue_energy += glue.F_r0 * glue.F_r0 / (2.0 * glue.k_n);
    ++out.adhesive_bonds;
  }
  if (out.adhesive_bonds == 0)
    throw InputError("creping.adhesion.reach: no particle of the sheet lies within reach of the "
                     "Yankee surface; accepted: a larger reach (up to 1)");
  w.applied_force.assign(p.size(), Vec3::Zero());
  w.applied_torque.assign(p.size(), Vec3::Zero());
  // The coating's toughness and the momentum flux of the sheet the blade turns up the face,
  // reported side by side: which of them sets the delaminated length is measured in
  // docs/creping.md (the toughness).
  const double strip_area = (x1 - x0) * Ly;
  out.coating_toughness = glue_energy / strip_area;
  out.momentum_flux = sheet_mass / strip_area * s.yankee_speed * s.yankee_speed;
  const PeelFront peel_front(std::move(glue_sites), metrics.thickness_grid, x0);
  std::vector<double> delaminated_middle;  // at the samples with the tip over the middle

  Blade blade = Blade::AtAngle(Vec3(x_front + 0.1 * r_max, 0.0, s.tip_clearance), s.creping_angle);
  blade.velocity = Vec3(-s.yankee_speed, 0.0, 0.0);
  blade.hard_stiffness = s.blade_hard_stiffness;
  blade.mu = s.blade_friction_mu;
  w.blades.push_back(blade);
  const Vec3 face_up = blade.face_up, face_normal = blade.face_normal;
  Reel reel;
  reel.velocity = blade.velocity + s.yankee_speed / (1.0 + s.crepe_ratio) * face_up;
  reel.face_up = face_up;
  reel.takeaway = takeaway;
  reel.rate = 1.0 / s.takeaway_time;
  reel.x_on_yankee.resize(n_sheet);
  for (std::size_t i = 0; i < n_sheet; ++i) reel.x_on_yankee[i] = p.x[i].x();

  UseSheetStepSettings(w, sheet);
  w.neighbours.Invalidate();
  Simulation sim(w);
  if (std::string warning = sim.Prepare(); !warning.empty()) out.warnings.push_back(warning);
  out.dt = w.settings.dt;
  const double travel = (blade.tip.x() - x0) + run_out;
  // A run-in at constant acceleration covers its length in twice the time at full speed.
  const double run_in_time = 2.0 * s.run_in_length / s.yankee_speed;
  const std::int64_t steps = static_cast<std::int64_t>(
      std::ceil((travel + s.run_in_length) / (s.yankee_speed * out.dt)));
  if (steps > s.max_steps)
    throw InputError(fmt::format("creping.max_steps: the blade needs {} steps of {:.3g} s to pass "
                                 "the {:.3g} mm sheet; accepted: max_steps >= {}",
                                 steps, out.dt, (x1 - x0) * 1e3, steps));

  const double accounted0 = MeasureEnergy(w).Accounted(w.energy);
  const double regained0 = w.energy.overlap_regained;
  w.min_contact_ratio = 1.0;  // report the impact's own closest approach
  const double t0 = w.time;
  const std::int64_t every = std::max<std::int64_t>(1, steps / s.curve_samples);
  const std::int64_t frame_every =
      s.impact_frames > 0 ? std::max<std::int64_t>(1, steps / s.impact_frames) : 0;
  out.bond_loss.name = "creping_bond_loss";
  out.bond_loss.columns = {"time_us", "fibre_fibre_broken_fraction",
                           "fibre_fibre_broken_fraction_all", "adhesive_broken_fraction",
                           "fibre_bonds_broken", "blade_force_N_per_m", "reel_force_N_per_m",
                           "kinetic_J", "energy_balance_error", "delaminated_length_um"};
  const std::int64_t n_all = static_cast<std::int64_t>(p.size());
  std::int64_t reel_samples = 0;
  // The adhesive bonds are the ones appended after the sheet's.
  auto adhesive_broken = [&] {
    std::size_t broken = 0;
    for (std::size_t b = n_bonds; b < w.bonds.size(); ++b) broken += w.bonds.broken[b];
    return double(broken) / double(out.adhesive_bonds);
  };
  auto broken_among = [&](const std::vector<std::size_t>& bonds) {
    std::size_t broken = 0;
    for (std::size_t b : bonds) broken += w.bonds.broken[b];
    return bonds.empty() ? 0.0 : double(broken) / double(bonds.size());
  };
  auto fibre_broken = [&] {
    std::size_t intact = 0;
    for (std::size_t b = 0; b < n_bonds; ++b)
      intact += w.bonds.kind[b] == BondKind::kFibre && !w.bonds.broken[b];
    return static_cast<double>(fibre_bonds_intact - intact);
  };
  Stopwatch clock;
  double next_report = progress.interval_s;
  const Vec3 full_blade_velocity = blade.velocity, full_reel_velocity = reel.velocity;
  for (std::int64_t step = 1; step <= steps; ++step) {
    if (run_in_time > 0.0) {
      // The speed at the step's middle: the tip then covers the run-in length exactly.
      const double share = std::min(1.0, (static_cast<double>(step) - 0.5) * out.dt / run_in_time);
      w.blades[0].velocity = share * full_blade_velocity;
      reel.velocity = share * full_reel_velocity;
    }
    const Vec3 tip = w.blades[0].tip;
#pragma omp parallel for schedule(static) if (ThreadsPay(p.size()))
    for (std::int64_t i = 0; i < n_all; ++i)
      w.applied_force[i] = reel.Force(p, static_cast<std::size_t>(i), tip);
    sim.Step();
    out.peak_blade_force = std::max(out.peak_blade_force, w.blades[0].reaction.x() / Ly);
    if (frame_every > 0 && step % frame_every == 0 &&
        static_cast<int>(out.impact_frames.size()) < s.impact_frames)
      out.impact_frames.push_back(KeptCopy(w));
    if (step % every != 0 && step != steps) continue;
    std::size_t past = 0;
    const Blade& bl = w.blades[0];
    for (std::size_t i = 0; i < n_sheet; ++i)
      past += (p.x[i] - bl.tip).dot(face_normal) < 0.0;
    out.particles_past_blade = std::max(out.particles_past_blade, past);
    const double blade_work = bl.work;
    const double error = blade_work > 0.0
                             ? std::abs(MeasureEnergy(w).Accounted(w.energy) - accounted0) / blade_work
                             : 0.0;
    const double ff = broken_among(fibre_fibre_middle);
    // The reel's pull on the sheet along the face (negative: it holds back what the blade
    // threw up faster than the reel runs).
    double reel = 0.0;
    for (std::size_t i = 0; i < n_sheet; ++i) reel += w.applied_force[i].dot(face_up);
    reel /= Ly;
    if (reel != 0.0) {
      out.reel_tension += reel;
      ++reel_samples;
      out.peak_reel_tension = std::max(out.peak_reel_tension, reel);
    }
    const double delaminated = peel_front.DelaminatedLength(bl.tip.x(), w.bonds.broken);
    out.delaminated_length_max = std::max(out.delaminated_length_max, delaminated);
    if (bl.tip.x() >= x0 + end_zone && bl.tip.x() <= x1 - end_zone)
      delaminated_middle.push_back(delaminated);
    out.bond_loss.Add({(w.time - t0) * 1e6, ff, broken_among(fibre_fibre), adhesive_broken(),
                       fibre_broken(), bl.reaction.x() / Ly, reel, KineticEnergy(w), error,
                       delaminated * 1e6});
    if (progress.report && clock.Seconds() >= next_report) {
      progress.Say(fmt::format("creping: {:.0f}% of the sheet scraped, t = {:.1f} us, fibre-fibre "
                               "bonds broken {:.1f}%",
                               100.0 * std::min(1.0, double(step) / double(steps)), (w.time - t0) * 1e6,
                               100.0 * ff));
      next_report = clock.Seconds() + progress.interval_s;
    }
  }
  if (reel_samples > 0) out.reel_tension /= static_cast<double>(reel_samples);
  out.steps = steps;
  out.simulated_time = steps * out.dt;
  out.blade_work = w.blades[0].work;
  out.overlap_regained = w.energy.overlap_regained - regained0;
  out.energy_balance_error = out.bond_loss.Values("energy_balance_error").back();
  out.bonds_broken_fraction = broken_among(fibre_fibre_middle);
  out.bonds_broken_fraction_all = broken_among(fibre_fibre);
  out.fibre_bonds_broken = fibre_broken();
  out.adhesive_broken_fraction = adhesive_broken();
  out.min_contact_ratio = w.min_contact_ratio;
  out.delaminated_length = Percentile(delaminated_middle, 0.5);

  // Pieces: the creped sheet is the heaviest; pieces still glued stay on the Yankee; the rest
  // is dust.
  const std::vector<std::int32_t> piece = Pieces(w, n_sheet);
  std::vector<double> mass(n_sheet, 0.0);
  std::vector<std::uint8_t> glued(n_sheet, 0);
  for (std::size_t i = 0; i < n_sheet; ++i) mass[piece[i]] += p.mass[i];
  for (std::size_t b = n_bonds; b < w.bonds.size(); ++b)
    if (!w.bonds.broken[b]) glued[piece[w.bonds.i[b]]] = 1;
  const std::int32_t sheet_piece =
      static_cast<std::int32_t>(std::max_element(mass.begin(), mass.end()) - mass.begin());
  const double total_mass = std::accumulate(mass.begin(), mass.end(), 0.0);
  double dust_mass = 0.0;
  for (std::size_t k = 0; k < n_sheet; ++k) {
    if (piece[k] != static_cast<std::int32_t>(k) || static_cast<std::int32_t>(k) == sheet_piece ||
        glued[k])
      continue;
    ++out.dust_count;
    dust_mass += mass[k];
  }
  out.dust_mass_fraction = dust_mass / total_mass;
  out.sheet_mass_fraction = mass[sheet_piece] / total_mass;

  // The creped sheet beyond the takeaway height along the face (nearer the tip the pocket is
  // still folding it), read in its own frame from the blade tip: u along its MD axis (up the
  // face for a sheet the reel draws along it, along its own length for one that stands off
  // the face at a tilt, which the face's frame would read as a steep slope), h normal to it
  // on the face's side.
  const Vec3 tip = w.blades[0].tip;
  std::vector<std::size_t> creped, drawn;
  for (std::size_t i = 0; i < n_sheet; ++i) {
    if (piece[i] != sheet_piece) continue;
    creped.push_back(i);
    if ((p.x[i] - tip).dot(face_up) >= takeaway) drawn.push_back(i);
  }
  std::vector<FramePoint> pts;
  double u_lo = 0.0, u_hi = 0.0;
  if (!drawn.empty()) {
    const Mat3 axes = SheetAxes(p, drawn, face_up);
    const Vec3 normal = axes.row(2).transpose();
    pts = InFrame(p, drawn, tip, axes.row(0).transpose(),
                  normal.dot(face_normal) < 0.0 ? Vec3(-normal) : normal);
    u_lo = 1e300;
    u_hi = -1e300;
    for (const FramePoint& f : pts) {
      u_lo = std::min(u_lo, f.x.x());
      u_hi = std::max(u_hi, f.x.x());
    }
    // The first tenth of it (its leading end) is left out: it crept before the folding
    // settled into its rhythm.
    u_hi -= 0.1 * (u_hi - u_lo);
  }
  if (u_hi - u_lo < 10.0 * u_bin) {
    out.warnings.push_back(fmt::format(
        "creping: only {:.0f} um of creped sheet beyond the takeaway height ({:.0f} um): too "
        "short for a crepe spectrum; use a longer cell (cell.size_x_mm)",
        std::max(0.0, u_hi - u_lo) * 1e6, takeaway * 1e6));
  } else {
    const CrepeProfile profile = MeasureCrepeProfile(
        pts, u_lo, u_hi, u_bin, w.cell.lo.y(), w.cell.hi.y(), y_bin, metrics.surface_percentile);
    const CrepeBand band = CrepeBandOf(s, p, drawn, u_bin);
    const CrepeSpectrum spectrum = AnalyseCrepe(profile.height, u_bin, band);
    out.crepe_frequency = spectrum.frequency;
    out.crepe_amplitude = spectrum.amplitude;
    out.caliper_at_blade = profile.caliper;
    const double length = profile.height.size() * u_bin;
    out.crepe_profile_length = length;
    out.crepe_min_amplitude = band.min_amplitude;
    out.crepe_fold_count = spectrum.fold_count;
    double window_mass = 0.0;
    for (std::size_t k = 0; k < drawn.size(); ++k) {
      const double u = pts[k].x.x();
      if (u >= profile.u0 && u < profile.u0 + length) window_mass += p.mass[drawn[k]];
    }
    std::vector<double> shape = spectrum.waviness;
    for (std::size_t k = 0; k < shape.size(); ++k) shape[k] += spectrum.folds[k];
    out.crepe_gathered_ratio = window_mass / (length * Ly) / (sheet_mass / strip_area);
    out.crepe_curl_ratio = ContourRatio(spectrum.waviness, u_bin);
    out.crepe_fold_ratio = ContourRatio(shape, u_bin) / out.crepe_curl_ratio;
    out.crepe_in_plane_ratio =
        out.crepe_gathered_ratio / (out.crepe_curl_ratio * out.crepe_fold_ratio);
    if (spectrum.frequency == 0.0 && 0.5 * length < band.shortest_wavelength)
      out.warnings.push_back(fmt::format(
          "creping: no crepe read: the {:.0f} um of creped sheet cannot hold two folds of the "
          "shortest wavelength counted ({:.0f} um; crepe_frequency 0); use a longer cell "
          "(cell.size_x_mm)",
          length * 1e6, band.shortest_wavelength * 1e6));
    else if (spectrum.frequency == 0.0 && spectrum.peak_amplitude >= band.min_amplitude)
      out.warnings.push_back(fmt::format(
          "creping: no crepe fold train on the {:.2f} mm of creped sheet: its crepe band rises "
          "from below -{:.1f} um to above +{:.1f} um only {} time(s), fewer than {} "
          "(crepe_frequency 0)",
          length * 1e3, band.min_amplitude * 1e6, band.min_amplitude * 1e6,
          spectrum.fold_count, kFoldsInATrain));
    else if (spectrum.frequency == 0.0)
      out.warnings.push_back(fmt::format(
          "creping: no crepe folds on the {:.2f} mm of creped sheet: its profile has no peak "
          "of {:.1f} um or more at wavelengths from {:.0f} to {:.0f} um (crepe_frequency 0)",
          length * 1e3, band.min_amplitude * 1e6, band.shortest_wavelength * 1e6,
          std::min(band.cutoff, 0.5 * length) * 1e6));
    out.crepe_profile.name = "crepe_profile";
    out.crepe_profile.columns = {"u_um", "height_um", "waviness_um", "folds_um"};
    for (std::size_t k = 0; k < profile.height.size(); ++k)
      out.crepe_profile.Add({(profile.u0 + (k + 0.5) * u_bin) * 1e6, profile.height[k] * 1e6,
                             spectrum.waviness[k] * 1e6, spectrum.folds[k] * 1e6});
  }
  if (out.particles_past_blade > 0)
    out.warnings.push_back(fmt::format("creping: {} particles got behind the blade face",
                                       out.particles_past_blade));

  // Lay the creped sheet flat: (u, y, h) -> (x, y, z), its base on z = 0, at rest.
  DropAnchors(w, n_sheet, n_bonds, n_types);
  if (added_factors) w.bonds.damping_factors.clear();
  w.blades.clear();
  w.applied_force.clear();
  w.applied_torque.clear();
  w.physics.applied_loads = false;
  const Mat3 R = SheetAxes(p, creped, face_up);
  double base = 1e300;
  for (std::size_t i : creped) base = std::min(base, (R * p.x[i]).z() - p.radius[i]);
  TransformRigidly(w, R, -Vec3(0.0, 0.0, base));
  double lo = 1e300, hi = -1e300;
  for (std::size_t i : creped) {
    lo = std::min(lo, p.x[i].x() - p.radius[i]);
    hi = std::max(hi, p.x[i].x() + p.radius[i]);
  }
  for (std::size_t i = 0; i < n_sheet; ++i) {
    p.v[i].setZero();
    p.omega[i].setZero();
    w.cell.Wrap(p.x[i]);
  }
  w.cell.lo.x() = lo - r_max;
  w.cell.hi.x() = hi + r_max;
  w.walls.assign(1, Wall{});
  std::vector<std::uint8_t> keep(n_sheet, 0);
  for (std::size_t i : creped) keep[i] = 1;
  out.particles_removed = KeepParticles(net, keep);
  RelaxCrepedSheet(net, sheet, s, progress, out);
  w.contact.normal.hard_stiffness = hard_stiffness_before;
  // The bulk is the creped sheet's at rest, read as the sheet's before: at the blade it still
  // holds what springs back (loops thrown up by the impact) and the tilt of a band thrown off
  // the Yankee, which the face's frame reads as height.
  out.caliper_after = SheetCaliper(w, w.cell.lo.x(), w.cell.hi.x(), metrics);
  out.bulk_gain = out.caliper_before > 0.0 ? out.caliper_after / out.caliper_before : 0.0;
  return out;
}

}  // namespace fibrenet::pipeline
