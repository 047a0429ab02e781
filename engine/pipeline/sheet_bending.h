// Pure bending of a sheet strip, as the Kawabata KES-FB2 tester does: the strip (cut open
// along the bending direction, periodic across, as in the tensile test) is held by two grips
// that turn in opposite senses about the strip's mid-plane while their pivots follow the
// chord of a circular arc, so the free span takes a constant curvature kappa with no net
// axial force from the kinematics.
//
// Quasi-static by steps, not by rate. The first flexural mode of a millimetre span is so slow
// against the time step (its period is of order (span / particle spacing)^2 steps, ~10^4 for
// a 2 mm tissue strip) that a rate-driven test would need ~10^5 steps per level of accuracy.
// Instead the curvature is raised in `levels` equal increments; at each, every free particle
// is moved by the increment of the pure-bending field (its reference point (X, Z) mapped onto
// the arc with plane sections normal to it), the grips are set to the new angle, and the
// sheet relaxes until the moment is steady (relative change below relax_tolerance over
// relax_check steps, twice in a row) or relax_steps have run. A homogeneous sheet is already
// in equilibrium in the field; relaxation only settles the local, non-affine part. The test
// is static: no viscoelastic rate effect enters it.
//
// Relaxation by local non-viscous damping (test_rig.h) by default: it takes the same share of
// every mode's energy per cycle, whatever its period. A drag towards rest (relax_time_steps)
// critically damps one period only: the slow flexural modes of a strip, and the loops of a
// creped sheet, are overdamped by a drag of 50 steps and creep, so that the moment changes
// little per check long before it has settled (docs/virtual-tests.md, "Sheet bending:
// relaxation").
//
// Measured: the moment each grip takes about its pivot (forces and torques of its
// particles), per unit width, m = (M_right - M_left) / (2 W) [N m/m], less its value at zero
// curvature; kappa = turning angle / initial free span [1/m].
// bending_stiffness: least-squares slope dm/dkappa over kappa in [fit_from * max_curvature,
// max_curvature] (KES-FB2 fits 0.5..1.5 1/cm), in mN mm (= uN m, per unit width).
// bending_relaxation_residual: the largest relative change of the moment over the last
// relax_check steps of any level (the guard: below relax_tolerance when every level settled).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "engine/pipeline/curves.h"
#include "engine/pipeline/network.h"
#include "engine/pipeline/progress.h"
#include "engine/pipeline/tensile_test.h"
#include "engine/pipeline/test_rig.h"

namespace fibrenet::pipeline {

struct BendingSettings {
  LoadAxis axis = LoadAxis::kMD;  // MD: the strip runs along x and bends about y
  double grip_length = 0.0;       // [m]; 0 = 10% of the strip
  double max_curvature = 150.0;   // [1/m], (0, 1e5]
  double fit_from = 1.0 / 3.0;    // fit window start as a fraction of max_curvature, [0, 1)
  int levels = 6;                 // curvature increments, [2, 100]
  int ramp_steps = 2000;          // steps over which a level's increment is imposed, [0, 1e7]
  int relax_steps = 100000;       // most steps per level, [10, 1e7]
  int relax_check = 200;          // steps between moment checks, [1, relax_steps]
  double relax_tolerance = 2e-4;  // relative moment change that counts as settled, (0, 1)
  double local_damping = 0.7;     // local non-viscous damping while relaxing, [0, 1) (0 = off)
  double relax_time_steps = 0;    // damping time of a drag towards rest in time steps, 0 = none
  double bond_damping_ratio = 0.3;
  double time_step_safety = 0.5;
  MaterialSwitches switches;

  std::string Validate() const;
};

struct BendingResult {
  std::vector<Metric> metrics;
  // "bending_md"/"bending_cd": curvature_per_m, moment_N_m_per_m, axial_force_N_per_m,
  // relax_steps, residual.
  Curve curve;
  std::vector<std::string> warnings;
  double dt = 0.0;
  std::int64_t steps = 0;
  bool settled = true;
};

BendingResult RunBendingTest(Network net, const BendingSettings& s, const Progress& progress = {});

}  // namespace fibrenet::pipeline
