// Through-air drying (TAD) as a structuring stage: the formed web lies on a structured
// drying fabric whose open areas are pockets (a relief of depth `fabric.height` below the
// fabric's knuckles), and the air drawn through the open areas presses the web into them
// with a pressure difference `pressure`. Fibre-fibre bonds form in the moulded state (the
// sheet dries there); then the air stops and the sheet, now on a flat support, springs back.
//
// The pressure field acts as a body force on the particles over the open areas: particle i
// at (x, y) gets f_i = -pressure * level(x, y) * m_i / b (b the basis weight, level the
// pattern's 0..1 level, 1 in the pockets), so that a column of the web over a pocket carries
// the pressure times its area, whatever the fidelity. Like pressing, the stage is
// quasi-static (mass scaling allowed) with a background drag of relaxation time
// damping_time; moulding and springback end when the kinetic energy is below
// settle_kinetic_ratio x that of the web drifting freely under the air load against the drag.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/pipeline/bonding.h"
#include "engine/pipeline/forming.h"
#include "engine/pipeline/network.h"
#include "engine/pipeline/progress.h"
#include "engine/pipeline/relief_pattern.h"

namespace fibrenet::pipeline {

struct ThroughAirSettings {
  ReliefPattern fabric;             // the open areas: height = pocket depth
  double pressure = 20e3;           // air pressure difference over the open areas [Pa]
  // Stiffness of the wet fibres while they are moulded, relative to the dry fibres' (the
  // intra-fibre bonds' k_n, k_s, k_b, k_t): wet fibres are soft, and once the sheet dries in
  // the moulded shape (set_fibre_shape) they keep it at their dry stiffness.
  double wet_stiffness_scale = 1.0;  // (0, 1]
  double mass_scale = 1.0;          // >= 1, quasi-static mass scaling
  double damping_time = 1e-5;       // background drag relaxation time [s]
  double settle_kinetic_ratio = 1e-4;
  std::optional<BondingSettings> bonding;  // absent: no bonds form
  bool set_fibre_shape = true;
  std::int64_t max_steps = 5'000'000;  // per phase

  std::string Validate() const;
};

struct ThroughAirResult {
  std::int64_t steps = 0;
  double dt = 0.0;
  double air_work = 0.0;           // work of the pressure field while moulding [J]
  double imprint_moulded = 0.0;    // Imprint() on the fabric, before bonding [m]
  double imprint = 0.0;            // Imprint() after springback [m]
  std::size_t bonds_formed = 0;
  bool settled = false;
  std::vector<std::string> warnings;
};

ThroughAirResult DryThroughAir(Network& net, const SheetSpec& sheet, const ThroughAirSettings& s,
                               const Progress& progress);

}  // namespace fibrenet::pipeline
