// The stepped loading of the ZD compression (CompressionSettings::Loading::kStepped).
#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "engine/pipeline/compression_rig.h"

namespace fibrenet::pipeline {

std::int64_t LoadStepped(CompressionRig& rig, const CompressionSettings& s,
                         const Progress& progress) {
  rig.Prepare();
  // The largest move takes the steps the continuous loading at constant speed spends on its
  // strain, so that moves of that size add up to loading_steps.
  const double base_gap = s.max_strain * rig.h0 / s.samples;
  const auto base_steps =
      std::max<std::int64_t>(1, std::llround(base_gap / rig.speed / rig.dt));
  const double smallest_gap = std::ldexp(base_gap, -s.max_move_halvings);
  const std::int64_t settle_max = s.settle_max_steps > 0 ? s.settle_max_steps : 100 * base_steps;
  const std::int64_t check_every = std::max<std::int64_t>(1, base_steps / 5);
  const double allowed = s.toe_kinetic_share * s.quasi_static.kinetic_work_tolerance;
  // Before the platen has done that much work, rest is measured against it: in empty space
  // the platen does none, and the sheet is at rest already.
  const double work_floor = s.modulus_pressure_lo * rig.area * base_gap;
  // At rest the two platens carry the same load; what they differ by is still accelerating
  // the sheet. With the masses scaled, a kinetic energy within the guard can still carry
  // force swings of several percent in stiff contacts.
  const double imbalance_limit = s.quasi_static.kinetic_work_tolerance;
  // Below the window's start the imbalance is measured against the load it starts at.
  const double load_floor = s.modulus_pressure_lo * rig.area;
  const bool sized = s.window_samples > 0;
  const double window_step =
      sized ? (s.modulus_pressure_hi - s.modulus_pressure_lo) / s.window_samples : 0.0;
  auto allowed_step = [&](double pressure) {
    return pressure < s.modulus_pressure_hi ? window_step : s.pressure_step_fraction * pressure;
  };

  std::int64_t step = 0;
  int unsettled = 0, unresolved = 0;
  bool out_of_steps = false;
  Stopwatch clock;
  double next_report = progress.interval_s;
  // One move of the platen by `gap` (down: -1, up: +1), then the rest; false when the step
  // budget ran out.
  auto move_and_settle = [&](int direction, double gap) {
    const auto move_steps = std::max<std::int64_t>(1, std::llround(gap / rig.speed / rig.dt));
    rig.SetPlatenVelocity(direction * gap / (static_cast<double>(move_steps) * rig.dt));
    for (std::int64_t k = 0; k < move_steps; ++k, ++step) rig.Step();
    rig.SetPlatenVelocity(0.0);
    // A step's reactions are those of where the platen stood at its start: one step at the
    // standing platen reads the load where it stopped.
    rig.Step();
    ++step;
    std::int64_t waited = 1;
    for (;;) {
      const double limit = allowed * std::max(rig.PlatenWork(), work_floor);
      if (rig.FluctuatingKinetic() <= limit &&
          rig.ForceImbalance(load_floor) <= imbalance_limit)
        break;
      if (waited >= settle_max) {
        ++unsettled;
        break;
      }
      for (std::int64_t k = 0; k < check_every; ++k, ++step, ++waited) rig.Step();
    }
    if (progress.report && clock.Seconds() >= next_report) {
      progress.Say(fmt::format("{}: step {} strain {:.4g} pressure {:.4g} Pa ({}, stepped)",
                               rig.name, step, rig.Strain(), rig.Pressure(),
                               direction < 0 ? "loading" : "unloading"));
      next_report = clock.Seconds() + progress.interval_s;
    }
    out_of_steps = step >= s.max_steps;
    return !out_of_steps;
  };
  // Moves towards `target_gap` until `done` says so, each sampled at its rest; a move whose
  // pressure changed the wrong way (`direction` x change < 0: up while loading, down while
  // unloading) by more than the allowed step is undone and halved. False when the budget ran
  // out.
  double gap = base_gap;
  auto advance = [&](int direction, double target_gap, auto&& done) {
    for (;;) {
      // A thousandth of the largest move is a rounding margin.
      const double left = direction * (target_gap - rig.Gap());
      if (left <= 1e-3 * base_gap) return true;
      const double move = std::min(gap, left);
      const double before_pressure = rig.Pressure();
      std::optional<World> before;
      if (sized) before = rig.w;
      const int unsettled_before = unsettled;
      if (!move_and_settle(direction, move)) return false;
      const double change = direction * (before_pressure - rig.Pressure());
      const double step_limit = allowed_step(before_pressure);
      if (sized && change > step_limit) {
        if (gap > smallest_gap) {
          rig.w = std::move(*before);
          unsettled = unsettled_before;
          gap *= 0.5;
          continue;
        }
        ++unresolved;
      }
      if (sized && change < 0.5 * step_limit) gap = std::min(2.0 * gap, base_gap);
      rig.Sample(direction > 0);
      if (done()) return true;
    }
  };

  rig.Sample(false);
  double peak = 0.0, strain_at_peak = 0.0;
  const bool loaded = advance(-1, (1.0 - s.max_strain) * rig.h0, [&] {
    const double pressure = rig.Pressure();
    if (pressure > peak) {
      peak = pressure;
      strain_at_peak = rig.Strain();
    }
    return s.max_pressure > 0.0 && pressure >= s.max_pressure;
  });
  if (loaded) {
    advance(+1, rig.h0, [&] {
      return rig.Pressure() <= 0.0 && strain_at_peak - rig.Strain() > 0.02 * strain_at_peak;
    });
  }
  if (out_of_steps)
    rig.warnings.push_back(fmt::format("{}: stopped at max_steps = {} (strain {:.4g})", rig.name,
                                       s.max_steps, rig.Strain()));
  if (unsettled > 0)
    rig.warnings.push_back(fmt::format(
        "{}: {} of the stepped loading's rests did not settle within {} steps (raise "
        "settle_max_steps)", rig.name, unsettled, settle_max));
  if (unresolved > 0)
    rig.warnings.push_back(fmt::format(
        "{}: {} moves changed the pressure by more than the allowed step even at 1/{} of a "
        "move (raise max_move_halvings)", rig.name, unresolved,
        std::ldexp(1.0, s.max_move_halvings)));
  return step;
}

}  // namespace fibrenet::pipeline
