#include "engine/pipeline/compression_test.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "engine/core/error.h"
#include "engine/core/simulation.h"
#include "engine/pipeline/compression_rig.h"

namespace fibrenet::pipeline {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// One loading-unloading run of a variant.
struct Run {
  Curve curve;
  double h0 = 0.0, area = 0.0, mass_scale = 1.0, dt = 0.0;
  std::int64_t steps = 0;
  std::vector<std::string> warnings;
};

// Figures of one run's curve.
struct LoopFigures {
  double peak = 0.0, strain_at_peak = 0.0;
  double modulus = kNaN, window_lo = 0.0, window_hi = 0.0;
  double energy_in = 0.0, energy_out = 0.0, hysteresis = kNaN, residual = kNaN;
  double guard = 0.0, drag_guard = 0.0;
  int snap_throughs = 0;
};

// The continuous loading: the platen comes down without stopping, slowly in the toe (and the
// approach), and goes back up at the speed it had at the turn. Returns the steps run.
std::int64_t LoadContinuous(CompressionRig& rig, const CompressionSettings& s,
                            const Progress& progress) {
  World& w = rig.w;
  Particles& p = w.particles;
  const double speed = rig.speed;
  // Kinetic energy of the affine field at the full speed (masses scaled): the platen comes
  // down no faster than keeps it within toe_kinetic_share of the guard's tolerance of the
  // work done so far (the motion beyond the affine field is of the same order).
  double kinetic_full = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
    kinetic_full += 0.5 * p.mass[i] * std::pow(speed * (p.x[i].z() - rig.z_lo) / rig.h0, 2);
  const double allowed = s.toe_kinetic_share * s.quasi_static.kinetic_work_tolerance;
  auto loading_speed = [&](double work) {
    if (!(kinetic_full > 0.0)) return speed;  // every particle on the floor: nothing to move
    const double rule = speed * std::sqrt(allowed * std::max(work, 0.0) / kinetic_full);
    return std::clamp(rule, s.min_speed_fraction * speed, speed);
  };
  // The approach ends for good the first time the pressure reaches its end.
  const double approach_end = s.approach_pressure_fraction * s.modulus_pressure_lo;
  bool approaching = s.approach_speed_fraction > s.min_speed_fraction;
  const double approach_speed = std::max(loading_speed(0.0), s.approach_speed_fraction * speed);
  // Tapered: the speed squared in inverse proportion to the pressure, so that the kinetic
  // energy put into the sheet per unit of its pressure stays as at the approach's end.
  auto tapered_speed = [&](double pressure) {
    if (!(pressure > 0.0)) return speed;
    return std::clamp(approach_speed * std::sqrt(approach_end / pressure), approach_speed, speed);
  };
  w.walls[1].vz = -(!approaching               ? loading_speed(0.0)
                    : s.approach_taper          ? tapered_speed(0.0)
                                                : approach_speed);
  for (std::size_t i = 0; i < p.size(); ++i) p.v[i] = rig.Field().At(p.x[i]);
  rig.Prepare();
  const auto every = std::max<std::int64_t>(
      1, static_cast<std::int64_t>(rig.loading_time / rig.dt / s.samples));
  // Feedback above the window: its control interval, 1/400 of the loading at the full speed.
  const auto control_every =
      std::max<std::int64_t>(1, static_cast<std::int64_t>(rig.loading_time / rig.dt / 400.0));
  bool feedback = false;  // on once the pressure has passed the window's top (or start)
  const double feedback_from =
      s.feedback_in_window ? s.modulus_pressure_lo : s.modulus_pressure_hi;

  double strain = 0.0, pressure = 0.0, peak = 0.0, strain_at_peak = 0.0;
  int sign = -1;  // -1 platen down (loading), +1 up
  rig.Sample(false);
  Stopwatch clock;
  double next_report = progress.interval_s;
  std::int64_t step = 0;
  for (;;) {
    if (step >= s.max_steps) {
      rig.warnings.push_back(fmt::format("{}: stopped at max_steps = {} (strain {:.4g})",
                                         rig.name, s.max_steps, strain));
      break;
    }
    rig.Step();
    ++step;
    strain = rig.Strain();
    pressure = rig.Pressure();
    if (approaching && pressure >= approach_end) {
      approaching = false;
      rig.SetPlatenVelocity(-loading_speed(rig.PlatenWork()));
    } else if (approaching && s.approach_taper) {
      // Never faster again: a pressure that falls back as a fibre slips does not speed it up.
      const double slower = tapered_speed(pressure);
      if (slower < 0.99 * rig.PlatenSpeed()) rig.SetPlatenVelocity(-slower);
    }
    if (sign < 0 && !approaching && rig.PlatenSpeed() < speed) {
      const double faster = loading_speed(rig.PlatenWork());
      if (faster > 1.01 * rig.PlatenSpeed()) rig.SetPlatenVelocity(-faster);
    }
    if (s.feedback_above_window && sign < 0 && !approaching) {
      feedback = feedback || pressure > feedback_from;
      if (feedback && step % control_every == 0) {
        const double work = rig.PlatenWork();
        const double ratio = work > 0.0 ? rig.FluctuatingKinetic() / work : 0.0;
        const double gain = ratio > 0.0 ? std::clamp(std::sqrt(allowed / ratio), 0.5, 1.05) : 1.05;
        const double now = rig.PlatenSpeed();
        const double next = std::min(std::max(now * gain, loading_speed(work)), speed);
        if (next != now) rig.SetPlatenVelocity(-next);
      }
    }
    if (sign < 0 && pressure > peak) {
      peak = pressure;
      strain_at_peak = strain;
    }
    bool turn = false, stop = false;
    if (sign < 0) {
      turn = strain >= s.max_strain || (s.max_pressure > 0.0 && pressure >= s.max_pressure);
    } else {
      stop = strain <= 0.0 ||
             (pressure <= 0.0 && strain_at_peak - strain > 0.02 * strain_at_peak);
    }
    if (step % every == 0 || turn || stop) rig.Sample(sign > 0);
    if (stop) break;
    if (turn) {
      // Back up at the speed it came down with, as the instruments do (KES-FB3): a jump to the
      // full speed after a slow toe would throw the sheet's scaled mass at the platen.
      rig.SetPlatenVelocity(rig.PlatenSpeed());
      sign = +1;
    }
    if (progress.report && clock.Seconds() >= next_report) {
      progress.Say(fmt::format("{}: step {} strain {:.4g} pressure {:.4g} Pa ({})", rig.name,
                               step, strain, pressure, sign < 0 ? "loading" : "unloading"));
      next_report = clock.Seconds() + progress.interval_s;
    }
  }
  return step;
}

Run RunOnce(Network net, const CompressionSettings& s, const MaterialSwitches& switches,
            const std::string& name, const Progress& progress) {
  const bool stepped = s.loading == CompressionSettings::Loading::kStepped;
  CompressionRig rig(net, s, switches, name, !stepped);
  Run run;
  run.steps = stepped ? LoadStepped(rig, s, progress) : LoadContinuous(rig, s, progress);
  run.curve = std::move(rig.curve);
  run.h0 = rig.h0;
  run.area = rig.area;
  run.mass_scale = rig.mass_scale;
  run.dt = rig.dt;
  run.warnings = std::move(rig.warnings);
  return run;
}

LoopFigures Analyse(const Curve& c, const CompressionSettings& s, double h0) {
  LoopFigures f;
  const std::vector<double> e = c.Values("strain"), p = c.Values("pressure_Pa"),
                            br = c.Values("branch"), ke = c.Values("kinetic_J"),
                            wk = c.Values("platen_work_J"), dw = c.Values("drag_load_ratio");
  std::size_t turn = 0;
  while (turn < br.size() && br[turn] == 0.0) ++turn;
  std::size_t peak_row = 0;
  for (std::size_t k = 0; k < turn; ++k)
    if (p[k] > f.peak) {
      f.peak = p[k];
      f.strain_at_peak = e[k];
      peak_row = k;
    }
  f.window_lo = s.modulus_pressure_lo;
  f.window_hi = s.modulus_pressure_hi;
  if (f.peak < f.window_hi) {
    f.window_lo = 0.25 * f.peak;
    f.window_hi = f.peak;
  }
  f.modulus = FitSlope(e, p, p, f.window_lo, f.window_hi, 0, peak_row + 1);
  // Counted from 1% of the window's start on, below which a few fibres decide.
  f.snap_throughs = CountSnapThroughs(std::vector<double>(p.begin(), p.begin() + turn),
                                      0.01 * s.modulus_pressure_lo);
  f.energy_in = h0 * Trapezoid(e, p, 0, turn);
  // Unloading runs from the last loading sample on, with decreasing strain.
  const std::size_t unload_begin = turn > 0 ? turn - 1 : 0;
  f.energy_out = -h0 * Trapezoid(e, p, unload_begin, e.size());
  if (f.energy_in > 0.0) f.hysteresis = (f.energy_in - f.energy_out) / f.energy_in;
  const double level = s.residual_pressure_fraction * f.peak;
  for (std::size_t k = std::max<std::size_t>(unload_begin, 1); k < e.size(); ++k) {
    if (p[k] > level) continue;
    const double span = p[k - 1] - p[k];
    const double a = span > 0.0 ? std::clamp((p[k - 1] - level) / span, 0.0, 1.0) : 1.0;
    f.residual = e[k - 1] + a * (e[k] - e[k - 1]);
    break;
  }
  if (std::isnan(f.residual) && !e.empty()) f.residual = e.back();
  for (std::size_t k = 0; k <= peak_row && k < e.size(); ++k)
    if (p[k] >= f.window_lo && wk[k] > 0.0) {
      f.guard = std::max(f.guard, ke[k] / wk[k]);
      f.drag_guard = std::max(f.drag_guard, dw[k]);
    }
  // The hysteresis and the residual strain are read on the unloading branch: its kinetic
  // energy is bounded too, against the work the loading put in, down to the window start.
  const double work_in = turn > 0 ? wk[turn - 1] : 0.0;
  for (std::size_t k = turn; k < e.size() && work_in > 0.0; ++k)
    if (p[k] >= f.window_lo) f.guard = std::max(f.guard, ke[k] / work_in);
  return f;
}

}  // namespace

std::string CompressionSettings::Validate() const {
  if (!(max_strain > 0.0 && max_strain <= 0.95))
    return fmt::format("max_strain = {}: must lie in (0, 0.95]", max_strain);
  if (!(max_pressure >= 0.0 && max_pressure <= 1e9))
    return fmt::format("max_pressure = {} Pa: must lie in [0, 1e9] (0 = strain target only)",
                       max_pressure);
  if (!(strain_rate > 0.0 && strain_rate <= 1e5))
    return fmt::format("strain_rate = {} 1/s: must lie in (0, 1e5]", strain_rate);
  if (!(modulus_pressure_lo >= 0.0 && modulus_pressure_lo < modulus_pressure_hi &&
        modulus_pressure_hi <= 1e8))
    return fmt::format("modulus window [{}, {}] Pa: need 0 <= lo < hi <= 1e8",
                       modulus_pressure_lo, modulus_pressure_hi);
  if (!(van_wyk_pressure_lo >= 0.0 && van_wyk_pressure_hi >= 0.0 &&
        (van_wyk_pressure_hi == 0.0 || van_wyk_pressure_lo < van_wyk_pressure_hi)))
    return fmt::format("van Wyk fit range [{}, {}] Pa: need 0 <= lo and lo < hi (hi = 0: no top)",
                       van_wyk_pressure_lo, van_wyk_pressure_hi);
  if (!(residual_pressure_fraction > 0.0 && residual_pressure_fraction < 1.0))
    return fmt::format("residual_pressure_fraction = {}: must lie in (0, 1)",
                       residual_pressure_fraction);
  if (!(min_speed_fraction > 0.0 && min_speed_fraction <= 1.0))
    return fmt::format("min_speed_fraction = {}: must lie in (0, 1] (1 = constant speed)",
                       min_speed_fraction);
  if (!(toe_kinetic_share > 0.0 && toe_kinetic_share <= 1.0))
    return fmt::format("toe_kinetic_share = {}: must lie in (0, 1]", toe_kinetic_share);
  if (!(approach_speed_fraction >= 0.0 && approach_speed_fraction <= 1.0))
    return fmt::format("approach_speed_fraction = {}: must lie in [0, 1] (0 = no approach)",
                       approach_speed_fraction);
  if (!(approach_pressure_fraction >= 0.0 && approach_pressure_fraction <= 1.0))
    return fmt::format("approach_pressure_fraction = {}: must lie in [0, 1] of "
                       "modulus_pressure_lo", approach_pressure_fraction);
  if (approach_taper && !(approach_speed_fraction > min_speed_fraction))
    return fmt::format("approach_taper needs an approach: approach_speed_fraction = {} must lie "
                       "above min_speed_fraction = {}", approach_speed_fraction,
                       min_speed_fraction);
  if (feedback_in_window && !feedback_above_window)
    return "feedback_in_window needs feedback_above_window";
  if (settle_max_steps < 0)
    return fmt::format("settle_max_steps = {}: must be >= 0 (0 = 100 x a move's steps)",
                       settle_max_steps);
  if (!(window_samples >= 0 && window_samples <= 1000))
    return fmt::format("window_samples = {}: must lie in [0, 1000] (0 = moves of one size)",
                       window_samples);
  if (!(pressure_step_fraction > 0.0 && pressure_step_fraction <= 10.0))
    return fmt::format("pressure_step_fraction = {}: must lie in (0, 10]", pressure_step_fraction);
  if (!(max_move_halvings >= 0 && max_move_halvings <= 30))
    return fmt::format("max_move_halvings = {}: must lie in [0, 30]", max_move_halvings);
  return ValidateLoading(samples, max_steps, switches, quasi_static);
}

double CompressionResult::Value(const std::string& name) const {
  if (const Metric* m = FindMetric(metrics, name)) return m->value;
  throw Error("compression test: no metric " + name);
}

CompressionResult RunCompressionTest(const Network& net, const CompressionSettings& s,
                                     const Progress& progress) {
  if (std::string why = s.Validate(); !why.empty()) throw InputError("compression." + why);
  CompressionResult res;
  Run base = RunOnce(net, s, s.switches, "compression", progress);
  const LoopFigures f = Analyse(base.curve, s, base.h0);
  res.h0 = base.h0;
  res.mass_scale = base.mass_scale;
  res.dt = base.dt;
  res.steps = base.steps;
  res.warnings = base.warnings;
  res.quasi_static = f.guard <= s.quasi_static.kinetic_work_tolerance &&
                     f.drag_guard <= s.quasi_static.kinetic_work_tolerance;
  if (!res.quasi_static)
    res.warnings.push_back(fmt::format(
        "compression: not quasi-static: kinetic / platen work reached {:.3g}, drag share of the "
        "load {:.3g} (tolerance {:.3g}); lower the strain rate or raise loading_steps", f.guard,
        f.drag_guard, s.quasi_static.kinetic_work_tolerance));
  if (f.peak < s.modulus_pressure_hi)
    res.warnings.push_back(fmt::format(
        "compression: peak pressure {:.4g} Pa below the modulus window top {:.4g} Pa; the "
        "modulus is fitted over 25-100% of the peak", f.peak, s.modulus_pressure_hi));
  res.metrics = {
      {"zd_modulus_kPa", f.modulus * 1e-3, "kPa"},
      {"zd_hysteresis_fraction", f.hysteresis, "-"},
      {"zd_residual_strain", f.residual, "-"},
      {"zd_thickness_um", base.h0 * 1e6, "um"},
      {"zd_compression_energy_J_per_m2", f.energy_in, "J/m^2"},
      {"zd_peak_pressure_kPa", f.peak * 1e-3, "kPa"},
      {"zd_max_strain", f.strain_at_peak, "-"},
      {"zd_kinetic_work_ratio", f.guard, "-"},
      {"zd_drag_load_ratio", f.drag_guard, "-"},
      {"zd_mass_scale", base.mass_scale, "-"},
      {"zd_snap_throughs", static_cast<double>(f.snap_throughs), "-"},
  };
  // The loading branch up to the first bond failure against the van Wyk form p = k (phi^n -
  // phi0^n): its exponent, how much of the curve the form explains, and how far it reaches.
  // Through the breaking beyond (a bonded sheet's curve softens there) the best n fell
  // below the grid, and the fit read the grid's end, 1. An exponent at either end of the
  // grid, with a low r2, says the form does not describe the curve (a buckling column's).
  const VanWykFit wyk = FitVanWyk(base.curve, FibreVolume(net) / (base.area * base.h0),
                                  s.van_wyk_pressure_lo, s.van_wyk_pressure_hi);
  res.metrics.push_back({"zd_van_wyk_exponent", wyk.n, "-"});
  res.metrics.push_back({"zd_van_wyk_r2", wyk.r2, "-"});
  res.metrics.push_back({"zd_van_wyk_bottom_kPa", wyk.p_bottom * 1e-3, "kPa"});
  res.metrics.push_back({"zd_van_wyk_top_kPa", wyk.p_top * 1e-3, "kPa"});
  res.curves.push_back(std::move(base.curve));
  if (!s.attribution) return res;

  struct Variant {
    const char* mechanism;
    MaterialSwitches switches;
  };
  std::vector<Variant> variants(3, Variant{"", s.switches});
  variants[0].mechanism = "bond_breakage";
  variants[0].switches.bond_failure = false;
  variants[1].mechanism = "slippage";
  variants[1].switches.friction = false;
  variants[2].mechanism = "viscous";
  variants[2].switches.viscoelastic = false;
  for (const Variant& v : variants) {
    Run run = RunOnce(net, s, v.switches, std::string("compression_without_") + v.mechanism,
                      progress);
    const LoopFigures g = Analyse(run.curve, s, run.h0);
    res.steps += run.steps;
    for (auto& warn : run.warnings) res.warnings.push_back(std::move(warn));
    auto share = [](double base_value, double without) {
      return base_value > 0.0 ? (base_value - without) / base_value : kNaN;
    };
    res.metrics.push_back({fmt::format("zd_hysteresis_share_{}", v.mechanism),
                           share(f.hysteresis, g.hysteresis), "-"});
    res.metrics.push_back({fmt::format("zd_residual_share_{}", v.mechanism),
                           share(f.residual, g.residual), "-"});
    res.curves.push_back(std::move(run.curve));
  }
  return res;
}

int CountSnapThroughs(const std::vector<double>& loading_pressure, double from_pressure) {
  int count = 0;
  double high = 0.0, low = 0.0;
  bool falling = false;  // one fall lasts until the pressure rises again
  for (double p : loading_pressure) {
    if (falling) {
      if (p <= low) {
        low = p;
        continue;
      }
      falling = false;
      high = p;
    }
    if (p > high) {
      high = p;
    } else if (high > from_pressure && p < 0.9 * high) {
      ++count;
      falling = true;
      low = p;
    }
  }
  return count;
}

VanWykFit FitVanWyk(const Curve& c, double phi_h0, double p_lo, double p_hi) {
  const std::vector<double> e = c.Values("strain"), p = c.Values("pressure_Pa"),
                            br = c.Values("branch");
  // The loading samples up to the first bond failure.
  std::size_t end = 0;
  while (end < p.size() && br[end] == 0.0) ++end;
  if (std::find(c.columns.begin(), c.columns.end(), "bonds_broken") != c.columns.end()) {
    const std::vector<double> broken = c.Values("bonds_broken");
    for (std::size_t k = 1; k < end; ++k)
      if (broken[k] > broken[0]) {
        end = k;
        break;
      }
  }
  VanWykFit best;
  const bool topped = p_hi > 0.0;
  double peak = 0.0;
  for (std::size_t k = 0; k < end; ++k)
    if (!topped || p[k] <= p_hi) peak = std::max(peak, p[k]);
  const double bottom = p_lo > 0.0 ? p_lo : 0.01 * peak;
  std::vector<double> phi, pr;
  best.p_bottom = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < end; ++k) {
    if (p[k] < bottom || (topped && p[k] > p_hi) || e[k] >= 1.0) continue;
    phi.push_back(phi_h0 / (1.0 - e[k]));
    pr.push_back(p[k]);
    best.p_top = std::max(best.p_top, p[k]);
    best.p_bottom = std::min(best.p_bottom, p[k]);
  }
  if (phi.empty()) best.p_bottom = 0.0;
  if (phi.size() < 3) return best;
  double mean_p = 0.0;
  for (double v : pr) mean_p += v;
  mean_p /= static_cast<double>(pr.size());
  double ss_tot = 0.0;
  for (double v : pr) ss_tot += (v - mean_p) * (v - mean_p);
  // phi is scaled by its largest value so that phi^n stays of order one for any n.
  const double phi_max = *std::max_element(phi.begin(), phi.end());
  double best_ss = std::numeric_limits<double>::infinity();
  for (double n = 1.0; n <= 30.0 + 1e-9; n += 0.01) {
    double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
    const auto m = static_cast<double>(phi.size());
    std::vector<double> x(phi.size());
    for (std::size_t k = 0; k < phi.size(); ++k) {
      x[k] = std::pow(phi[k] / phi_max, n);
      sx += x[k];
      sy += pr[k];
      sxx += x[k] * x[k];
      sxy += x[k] * pr[k];
    }
    const double det = m * sxx - sx * sx;
    if (!(det > 0.0)) continue;
    const double a = (m * sxy - sx * sy) / det, b = (sy - a * sx) / m;
    double ss = 0.0;
    for (std::size_t k = 0; k < phi.size(); ++k) ss += std::pow(pr[k] - (a * x[k] + b), 2);
    if (ss < best_ss) {
      best_ss = ss;
      best.n = n;
      best.k = a / std::pow(phi_max, n);
      best.phi0 = (a > 0.0 && -b / a > 0.0) ? phi_max * std::pow(-b / a, 1.0 / n) : 0.0;
    }
  }
  best.r2 = ss_tot > 0.0 ? 1.0 - best_ss / ss_tot : 0.0;
  return best;
}

double FibreVolume(const Network& net) {
  double v = 0.0;
  for (const FibreRecord& f : net.fibres) v += kPi * 0.25 * f.diameter * f.diameter * f.length;
  return v;
}

}  // namespace fibrenet::pipeline
