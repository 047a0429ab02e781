#include "engine/pipeline/tensile_test.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "engine/core/error.h"
#include "engine/core/simulation.h"
#include "engine/pipeline/strain_energy.h"

namespace fibrenet::pipeline {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

const char* AxisName(LoadAxis a) { return a == LoadAxis::kMD ? "md" : "cd"; }

// Column order of the curve.
enum Col { kStrain, kStress };

}  // namespace

std::string TensileSettings::Validate() const {
  if (!(grip_length >= 0.0 && grip_length <= 1.0))
    return fmt::format("grip_length = {} m: must lie in [0, 1] (0 = 10% of the strip)", grip_length);
  if (!(strain_rate > 0.0 && strain_rate <= 1e4))
    return fmt::format("strain_rate = {} 1/s: must lie in (0, 1e4]", strain_rate);
  if (!(max_strain > 0.0 && max_strain <= 2.0))
    return fmt::format("max_strain = {}: must lie in (0, 2]", max_strain);
  if (!(failure_drop > 0.0 && failure_drop < 1.0))
    return fmt::format("failure_drop = {}: must lie in (0, 1)", failure_drop);
  double previous = 0.0;
  for (double c : cycle_strains) {
    if (!(c > previous && c < max_strain))
      return fmt::format("cycle_strains: {} must increase and lie in (0, max_strain = {})", c,
                         max_strain);
    previous = c;
  }
  if (!(modulus_window_lo >= 0.0 && modulus_window_lo < modulus_window_hi &&
        modulus_window_hi <= 1.0))
    return fmt::format("modulus_window = [{}, {}]: need 0 <= lo < hi <= 1 (fractions of the peak)",
                       modulus_window_lo, modulus_window_hi);
  return ValidateLoading(samples, max_steps, switches, quasi_static);
}

double TensileResult::Value(const std::string& name) const {
  if (const Metric* m = FindMetric(metrics, name)) return m->value;
  throw Error("tensile test: no metric " + name);
}

TensileResult RunTensileTest(Network net, const TensileSettings& s, const Progress& progress) {
  if (std::string why = s.Validate(); !why.empty()) throw InputError("tensile." + why);
  World& w = net.world;
  ApplyTestPhysics(net, s.switches);
  if (s.axis == LoadAxis::kCD) QuarterTurn(net);
  for (std::size_t i = 0; i < w.particles.size(); ++i) {
    w.particles.v[i].setZero();
    w.particles.omega[i].setZero();
  }
  const StripEnds ends = FindStripEnds(w);
  const double width = w.cell.Ly(), length = ends.length;
  const double grip = GripLength(ends, s.grip_length, "tensile.grip_length");
  CutAlongX(net, 0.5 * s.max_strain * length + 4.0 * grip);
  const Grips g = MakeGrips(w, ends, grip);
  if (g.left.empty() || g.right.empty() || !(g.span > 0.0))
    throw RunError("tensile test: a grip holds no particles (empty sheet?)");
  std::vector<std::uint8_t> held(w.particles.size(), 0);
  for (auto i : g.left) held[i] = 1;
  for (auto i : g.right) held[i] = 1;

  TensileResult res;
  res.mass_scale = ChooseMassScale(w, s.quasi_static, s.max_strain / s.strain_rate);
  ApplyQuasiStaticDamping(w, s.quasi_static);
  const double V = s.strain_rate * g.span;
  DriveGrips(w, g, V, +1, true, 0.0);
  Simulation sim(w);
  if (std::string warn = sim.Prepare(); !warn.empty()) res.warnings.push_back(warn);
  const double dt = res.dt = w.settings.dt;
  const double d_strain = V * dt / g.span;
  const auto every = std::max<std::int64_t>(
      1, static_cast<std::int64_t>(s.max_strain / d_strain / s.samples));

  const std::vector<ModeEnergy> before = FibreEnergies(net);
  const Mat3 virial0 = InteractionVirial(w);
  res.curve.name = fmt::format("tensile_{}", AxisName(s.axis));
  res.curve.columns = {"strain", "stress_N_per_m", "lateral_stress_N_per_m",
                       "virial_axial_stress_N_per_m", "kinetic_J", "grip_work_J", "drag_load_ratio",
                       "energy_normal_J", "energy_shear_J", "energy_bending_J", "energy_twist_J",
                       "bonds_broken", "branch"};
  double strain = 0.0, work = 0.0, tension = 0.0, peak = 0.0, strain_at_peak = 0.0;
  std::size_t peak_row = 0;
  std::vector<ModeEnergy> at_peak = before;
  int branch = 0, sign = +1;
  std::size_t target = 0;  // index into the loading targets
  std::vector<double> targets = s.cycle_strains;
  targets.push_back(s.max_strain);

  const double loading_time = s.max_strain / s.strain_rate;
  const double tau = s.quasi_static.drag_time_fraction * loading_time;
  // The affine stretch the grips impose at the current strain and direction.
  auto field = [&] {
    return AffineField{0, 0.5 * (g.x_left + g.x_right), 0.5 * g.span * (1.0 + strain),
                       0.5 * sign * V};
  };
  // Share of the grip load carried by the drag: |drag virial| / (tension x current span).
  auto drag_share = [&] {
    const double lever = tension * g.span * (1.0 + strain);
    const double v = DragVirial(w, held, 0, 0.5 * (g.x_left + g.x_right));
    return lever > 0.0 ? std::abs(v) / lever : 0.0;
  };
  auto sample = [&] {
    const Mat3 virial = InteractionVirial(w) - virial0;
    const double area = g.span * (1.0 + strain) * width;
    const std::vector<ModeEnergy> now = FibreEnergies(net);
    const ModeEnergy inc = TotalEnergy(now) - TotalEnergy(before);
    const double stress = tension / width;
    res.curve.Add({strain, stress, virial(1, 1) / area, virial(0, 0) / area,
                   FluctuatingKineticEnergy(w, held, field()),
                   work, drag_share(), inc.normal, inc.shear, inc.bending, inc.twist,
                   static_cast<double>(w.bonds.events.size()), static_cast<double>(branch)});
    if (stress > peak) {
      peak = stress;
      strain_at_peak = strain;
      peak_row = res.curve.rows.size() - 1;
      at_peak = now;
    }
  };
  sample();

  Stopwatch clock;
  double next_report = progress.interval_s;
  std::int64_t step = 0;
  for (;;) {
    if (step >= s.max_steps) {
      res.warnings.push_back(fmt::format("tensile: stopped at max_steps = {} (strain {:.4g})",
                                         s.max_steps, strain));
      break;
    }
    if (tau > 0.0) ApplyAffineDrag(w, held, field(), tau);
    w.damping_reference = field();
    sim.Step();
    ++step;
    strain += sign * d_strain;
    tension = GripTension(w, g);
    work += GripPower(w, g) * dt;
    const bool last = target + 1 == targets.size();
    bool switch_branch = false, stop = false;
    if (sign > 0 && strain >= targets[target]) {
      if (last)
        stop = true;
      else
        switch_branch = true;
    } else if (sign < 0 && (tension <= 0.0 || strain <= 0.0)) {
      switch_branch = true;
    }
    if (step % every == 0 || switch_branch || stop) {
      sample();
      if (last && sign > 0 && peak > 0.0 && strain > strain_at_peak &&
          res.curve.rows.back()[kStress] < s.failure_drop * peak) {
        res.failed = true;
        stop = true;
      }
    }
    if (stop) break;
    if (switch_branch) {
      if (sign > 0) ++target;
      sign = -sign;
      ++branch;
      DriveGrips(w, g, V, sign, false, strain);
    }
    if (progress.report && clock.Seconds() >= next_report) {
      progress.Say(fmt::format("tensile {}: step {} strain {:.4g} stress {:.4g} N/m (peak {:.4g})",
                               AxisName(s.axis), step, strain, tension / width, peak));
      next_report = clock.Seconds() + progress.interval_s;
    }
  }
  res.steps = step;

  // Metrics from the curve.
  const Curve& c = res.curve;
  const std::vector<double> e = c.Values("strain"), st = c.Values("stress_N_per_m"),
                            lat = c.Values("lateral_stress_N_per_m"), br = c.Values("branch"),
                            ke = c.Values("kinetic_J"), wk = c.Values("grip_work_J"),
                            dw = c.Values("drag_load_ratio");
  std::size_t first_end = 0;  // end of the first loading branch, up to its peak
  double peak1 = 0.0;
  std::size_t peak1_row = 0;
  while (first_end < br.size() && br[first_end] == 0.0) {
    if (st[first_end] > peak1) {
      peak1 = st[first_end];
      peak1_row = first_end;
    }
    ++first_end;
  }
  const double lo = s.modulus_window_lo * peak1, hi = s.modulus_window_hi * peak1;
  const double modulus = FitSlope(e, st, st, lo, hi, 0, peak1_row + 1);
  const double lateral_ratio = FitSlope(st, lat, st, lo, hi, 0, peak1_row + 1);
  double guard = 0.0, drag_guard = 0.0;
  for (std::size_t k = 0; k <= peak_row; ++k)
    if (!(br[k] == 0.0 && st[k] < lo) && wk[k] > 0.0) {
      guard = std::max(guard, ke[k] / wk[k]);
      drag_guard = std::max(drag_guard, dw[k]);
    }
  res.quasi_static = guard <= s.quasi_static.kinetic_work_tolerance &&
                     drag_guard <= s.quasi_static.kinetic_work_tolerance;
  if (!res.quasi_static)
    res.warnings.push_back(fmt::format(
        "tensile {}: not quasi-static: kinetic / grip work reached {:.3g}, drag share of the load "
        "{:.3g} (tolerance {:.3g}); lower the strain rate or raise loading_steps",
        AxisName(s.axis), guard, drag_guard, s.quasi_static.kinetic_work_tolerance));
  if (s.switches.bond_failure && !res.failed)
    res.warnings.push_back(fmt::format(
        "tensile {}: the strip did not fail before max_strain = {}; strength is the largest "
        "stress reached", AxisName(s.axis), s.max_strain));

  const EnergyDistribution dist = DistributionOfIncrement(before, at_peak);
  res.fibre_energy_at_peak = dist.per_fibre;
  const double total = std::max(dist.total.normal, 0.0) + std::max(dist.total.shear, 0.0) +
                       std::max(dist.total.bending, 0.0) + std::max(dist.total.twist, 0.0);
  auto share = [&](double v) { return total > 0.0 ? std::max(v, 0.0) / total : kNaN; };
  std::size_t ff_bonds = 0;
  for (std::size_t b = 0; b < w.bonds.size(); ++b) ff_bonds += w.bonds.kind[b] == BondKind::kFibreFibre;
  std::size_t ff_broken = 0;
  for (const BondBreakEvent& ev : w.bonds.events) ff_broken += w.bonds.kind[ev.bond] == BondKind::kFibreFibre;

  res.metrics = {
      {"tensile_strength_N_per_m", peak, "N/m"},
      {"tensile_modulus_N_per_m", modulus, "N/m"},
      {"strain_at_break", strain_at_peak, "-"},
      {"tea_J_per_m2", Trapezoid(e, st, 0, peak_row + 1), "J/m^2"},
      {"strain_energy_per_fibre_nJ", dist.per_fibre_mean * 1e9, "nJ"},
      {"energy_share_normal", share(dist.total.normal), "-"},
      {"energy_share_shear", share(dist.total.shear), "-"},
      {"energy_share_bending", share(dist.total.bending), "-"},
      {"energy_share_twist", share(dist.total.twist), "-"},
      {"strain_energy_top10_share", dist.top10_share, "-"},
      {"strain_energy_gini", dist.gini, "-"},
      {"tensile_lateral_stress_ratio", lateral_ratio, "-"},
      {"tensile_bonds_broken_fraction",
       ff_bonds ? static_cast<double>(ff_broken) / static_cast<double>(ff_bonds) : 0.0, "-"},
      {"tensile_kinetic_work_ratio", guard, "-"},
      {"tensile_drag_load_ratio", drag_guard, "-"},
      {"tensile_mass_scale", res.mass_scale, "-"},
  };
  // Cycles: residual strain after the first unloading and the modulus of the reloading.
  if (!s.cycle_strains.empty()) {
    std::size_t k = first_end;
    while (k < br.size() && br[k] == 1.0) ++k;
    const std::size_t reload = k;
    std::size_t reload_end = reload;
    while (reload_end < br.size() && br[reload_end] == 2.0) ++reload_end;
    res.metrics.push_back({"cycle_residual_strain", k > 0 ? e[k - 1] : kNaN, "-"});
    res.metrics.push_back({"reload_modulus_N_per_m",
                           FitSlope(e, st, st, lo, hi, reload, reload_end), "N/m"});
  }
  return res;
}

AffineReference AffineStiffness(const Network& net, LoadAxis axis) {
  const World& w = net.world;
  const Particles& p = w.particles;
  AffineReference r;
  double weighted_E = 0.0, volume = 0.0, stiffness = 0.0;
  for (std::size_t b = 0; b < w.bonds.size(); ++b) {
    if (w.bonds.broken[b] || w.bonds.kind[b] != BondKind::kFibre) continue;
    const std::int32_t i = w.bonds.i[b], j = w.bonds.j[b];
    const Vec3 d = w.cell.Delta(p.x[i], p.x[j]);
    const double L0 = w.bonds.state[b].L0;
    const double cosine = (axis == LoadAxis::kMD ? d.x() : d.y()) / d.norm();
    const double k_n = w.bonds.types[w.bonds.type[b]].k_n;
    const double R = 0.5 * (p.radius[i] + p.radius[j]);
    const double A = kPi * R * R;
    stiffness += k_n * L0 * L0 * std::pow(cosine, 4);
    volume += A * L0;
    weighted_E += k_n * L0 / A * (A * L0);
  }
  const double area = w.cell.Lx() * w.cell.Ly();
  r.uniaxial_strain_N_per_m = stiffness / area;
  r.fibre_volume_per_area = volume / area;
  r.mean_youngs_modulus = volume > 0.0 ? weighted_E / volume : 0.0;
  return r;
}

}  // namespace fibrenet::pipeline
