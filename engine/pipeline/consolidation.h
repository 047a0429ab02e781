// Consolidation (paper 3.2): a flat plate (a top wall) comes down onto the formed web on
// the wire, presses it to a target thickness or pressure, holds until the web is at rest,
// then fibre-fibre bonds form between touching particles of
// different fibres (bonding.h); the plate lifts and the sheet springs back until settled.
//
// Pressing is quasi-static: it may use mass scaling, guarded by the ratio of the kinetic
// energy beyond the affine squeeze (velocity rising linearly from the wire to the plate) to
// the plate's work at the end of the compression (reported; a warning when it exceeds
// kinetic_work_tolerance, default 1%). While the plate approaches the web or rests
// (hold, springback) a background drag with relaxation time damping_time
// (F = -m_mean / damping_time * v) takes out residual motion and elastic ringing; it is off
// while the plate presses, where it would resist the squeeze itself. Contacts damp through
// their restitution coefficient throughout.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/pipeline/bonding.h"
#include "engine/pipeline/forming.h"
#include "engine/pipeline/metrics.h"
#include "engine/pipeline/network.h"
#include "engine/pipeline/progress.h"
#include "engine/pipeline/relief_pattern.h"

namespace fibrenet::pipeline {

enum class PressTarget { kThickness, kPressure };

// What a target thickness means: the plate gap, or the sheet's thickness by the metrics
// definition at the hold (the plate is moved until they agree). The sheet's surfaces stand
// above the plate gap by the fibres' transverse collapse at the plate (van Wyk overlap),
// which springs back when the plate lifts; kSheet makes the sheet, not the plate, hit the
// target.
enum class ThicknessControl { kPlate, kSheet };

struct PressingSettings {
  PressTarget target = PressTarget::kThickness;
  double target_thickness = 200e-6;  // [m], see ThicknessControl
  ThicknessControl control = ThicknessControl::kSheet;
  double control_tolerance = 0.01;   // relative
  int max_corrections = 5;
  double target_pressure = 0.0;      // plate force / cell area [Pa]
  double speed = 0.1;                // plate speed while pressing and lifting [m/s]
  double approach_speed = 1.0;       // plate speed down to the web's top surface [m/s]
  // Two speeds (off by default; a thickness target only): the plate presses at fast_speed
  // down to fast_until_ratio x the target thickness, where the web still carries little,
  // then at speed. The end of the compression, where the guard reads and the bonds form,
  // runs as slowly as with one speed. On the 2.5 mm generic tissue 0.3 m/s down to 1.5 x
  // the target saves 23-36% of the steps; its strength and the default's lie within 1.7% of
  // a 0.05 m/s reference on average, on three seeds whose noise per run is 1-3%
  // (docs/network.md): no scene uses it until more realisations resolve it.
  double fast_speed = 0.0;           // [m/s]; 0 (or at most speed): one speed
  double fast_until_ratio = 1.5;     // of the target thickness, > 1
  double mass_scale = 1.0;           // >= 1, quasi-static mass scaling
  double damping_time = 1e-5;        // background drag relaxation time [s]
  double min_hold_time = 0.0;        // [s] hold at least this long before bonding
  // Hold and springback end when the kinetic energy is below this fraction of the plate's
  // work (and, for the springback, after the plate has left the sheet).
  double settle_kinetic_ratio = 1e-4;
  double kinetic_work_tolerance = 0.01;
  std::optional<BondingSettings> bonding;  // absent: no bonds form
  // Embossing: bosses of this pattern stand out of the plate. The target thickness is then
  // the gap between the wire and the plate's land (the boss tips come closer by the boss
  // height) and the plate is not corrected to a sheet thickness.
  std::optional<ReliefPattern> emboss;
  bool set_fibre_shape = true;             // fibres keep their pressed shape (see bonding.h)
  std::int64_t max_steps = 5'000'000;      // per phase

  std::string Validate() const;
};

// One sample of the pressing curve.
struct PressPoint {
  double time = 0.0;       // [s] since the stage began
  double plate_z = 0.0;    // plate position above the wire [m]
  double pressure = 0.0;   // plate force / cell area [Pa]
  double kinetic = 0.0;    // [J]
};

struct PressingResult {
  std::int64_t steps = 0;
  double dt = 0.0;
  double max_pressure = 0.0;             // [Pa]
  double first_touch = 0.0;              // plate height at first contact with the web [m]
  double press_start = 0.0;              // plate height where the approach ended [m]
  double plate_gap_at_hold = 0.0;        // [m]
  double thickness_at_hold = 0.0;        // [m], by the metrics' definition, when bonds form
  double plate_work = 0.0;               // [J] work the plate did on the web while pressing
  double kinetic_to_work_ratio = 0.0;    // at the end of the compression
  std::size_t bonds_formed = 0;
  double imprint_at_hold = 0.0;          // embossing: Imprint() at the hold [m]
  double imprint = 0.0;                  // embossing: Imprint() after springback [m]
  bool settled = false;                  // the springback came to rest
  std::vector<PressPoint> curve;
  std::vector<std::string> warnings;
};

// `metrics` defines the thickness reported at the hold.
PressingResult Press(Network& net, const SheetSpec& sheet, const PressingSettings& s,
                     const MetricsSettings& metrics, const Progress& progress);

}  // namespace fibrenet::pipeline
