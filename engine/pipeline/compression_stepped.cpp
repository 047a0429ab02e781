// The stepped loading of the ZD compression (CompressionSettings::Loading::kStepped).
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "engine/pipeline/compression_rig.h"

namespace fibrenet::pipeline {

std::int64_t LoadStepped(CompressionRig& rig, const CompressionSettings& s,
                         const Progress& progress) {
  rig.Prepare();
  // A move takes the steps the continuous loading at constant speed spends on its strain, so
  // that the moves add up to loading_steps.
  const double move_gap = s.max_strain * rig.h0 / s.samples;
  const auto move_steps =
      std::max<std::int64_t>(1, std::llround(move_gap / rig.speed / rig.dt));
  const double move_speed = move_gap / (static_cast<double>(move_steps) * rig.dt);
  const std::int64_t settle_max = s.settle_max_steps > 0 ? s.settle_max_steps : 100 * move_steps;
  const std::int64_t check_every = std::max<std::int64_t>(1, move_steps / 5);
  const double allowed = s.toe_kinetic_share * s.quasi_static.kinetic_work_tolerance;
  // Before the platen has done that much work, rest is measured against it: in empty space
  // the platen does none, and the sheet is at rest already.
  const double work_floor = s.modulus_pressure_lo * rig.area * move_gap;
  // At rest the two platens carry the same load; what they differ by is still accelerating
  // the sheet. With the masses scaled, a kinetic energy within the guard can still carry
  // force swings of several percent in stiff contacts.
  const double imbalance_limit = s.quasi_static.kinetic_work_tolerance;
  // Below the window's start the imbalance is measured against the load it starts at.
  const double load_floor = s.modulus_pressure_lo * rig.area;

  std::int64_t step = 0;
  int unsettled = 0;
  bool out_of_steps = false;
  Stopwatch clock;
  double next_report = progress.interval_s;
  // One move of the platen by move_gap (down: -1, up: +1), then the rest; false when the
  // step budget ran out.
  auto move_and_settle = [&](int direction) {
    rig.SetPlatenVelocity(direction * move_speed);
    for (std::int64_t k = 0; k < move_steps; ++k, ++step) rig.Step();
    rig.SetPlatenVelocity(0.0);
    std::int64_t waited = 0;
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

  rig.Sample(false);
  double peak = 0.0, strain_at_peak = 0.0;
  for (;;) {
    if (!move_and_settle(-1)) break;
    const double strain = rig.Strain(), pressure = rig.Pressure();
    if (pressure > peak) {
      peak = pressure;
      strain_at_peak = strain;
    }
    rig.Sample(false);
    // A rounding margin of a thousandth of a move: samples x move_gap is max_strain x h0.
    if (strain >= s.max_strain - 1e-3 * move_gap / rig.h0 ||
        (s.max_pressure > 0.0 && pressure >= s.max_pressure))
      break;
  }
  while (!out_of_steps) {
    if (!move_and_settle(+1)) break;
    const double strain = rig.Strain();
    rig.Sample(true);
    if (strain <= 0.0 ||
        (rig.Pressure() <= 0.0 && strain_at_peak - strain > 0.02 * strain_at_peak))
      break;
  }
  if (out_of_steps)
    rig.warnings.push_back(fmt::format("{}: stopped at max_steps = {} (strain {:.4g})", rig.name,
                                       s.max_steps, rig.Strain()));
  if (unsettled > 0)
    rig.warnings.push_back(fmt::format(
        "{}: {} of the stepped loading's rests did not settle within {} steps (raise "
        "settle_max_steps)", rig.name, unsettled, settle_max));
  return step;
}

}  // namespace fibrenet::pipeline
