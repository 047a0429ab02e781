// In-plane tensile test (paper 3.5; SPEC 2.5): a strip of the sheet is held by two grips and
// pulled apart at a set strain rate until it fails or a set strain is reached, optionally
// with load-unload-reload cycles first.
//
// Procedure. The network is copied; for a CD test it is turned a quarter turn so the load
// runs along x. The cell is cut open along x (bonds across the periodic face removed: a strip
// cut from the sheet) and stays periodic across, so the strip is infinitely wide and the
// grips hold its width (no lateral contraction; the lateral stress is measured instead).
// Grips: the particles within grip_length of either end, fixed (Particles::Fix) and moved
// apart at +-V/2, V = strain_rate * span; the free particles start with the matching affine
// velocity. Quasi-static control and the variant switches: test_rig.h.
//
// Definitions (ISO 1924-2 where it defines them; all stresses per unit width):
//  strain                   grip displacement / initial free span between the grips
//  stress [N/m]             grip force / strip width (the cell side across)
//  tensile_strength_N_per_m peak stress
//  strain_at_break          strain at the peak stress
//  tea_J_per_m2             integral of stress d(strain) from 0 to the peak (along the path)
//  tensile_modulus_N_per_m  least-squares slope of stress on strain over the first loading
//                           branch where modulus_window_lo <= stress / peak <= modulus_window_hi
//                           (default 10%..50% of that branch's peak: past the start-up toe,
//                           below the nonlinear part)
//  strain energy at the peak, as increments over the unloaded state (strain_energy.h):
//    strain_energy_per_fibre_nJ, energy_share_normal/_shear/_bending/_twist (shares of the
//    summed increments), strain_energy_top10_share, strain_energy_gini
//  tensile_lateral_stress_ratio  lateral / axial stress resultant in the modulus window,
//                           from the interaction virial (C12 / C11 of the strip)
//  tensile_kinetic_work_ratio    quasi-static guard: largest kinetic energy (beyond the
//                           affine stretch the grips impose, test_rig.h) / grip work over the
//                           samples from the start of the modulus window to the peak;
//  tensile_drag_load_ratio  the same for the share of the grip load the background drag
//                           carries, |drag virial| / (grip force x span) (test_rig.h)
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "engine/pipeline/curves.h"
#include "engine/pipeline/network.h"
#include "engine/pipeline/progress.h"
#include "engine/pipeline/test_rig.h"

namespace fibrenet::pipeline {

enum class LoadAxis { kMD, kCD };  // MD along x, CD along y

struct TensileSettings {
  LoadAxis axis = LoadAxis::kMD;
  double grip_length = 0.0;     // [m]; 0 = 10% of the cell side along the load
  double strain_rate = 0.1;     // [1/s]
  // Stop here if the strip has not failed, (0, 2]. With automatic mass scaling the loading
  // to max_strain takes quasi_static.loading_steps steps: set it near twice the expected
  // strain at break.
  double max_strain = 0.1;
  // Failure: the stress has fallen below failure_drop * peak after the peak.
  double failure_drop = 0.5;    // (0, 1)
  // Load-unload-reload cycles before the final loading: each entry is the strain to load to;
  // the grips then return until the stress is zero (or the strain is), and load again.
  std::vector<double> cycle_strains;
  double modulus_window_lo = 0.1, modulus_window_hi = 0.5;  // fractions of the peak
  int samples = 400;            // curve points over max_strain (more with cycles)
  MaterialSwitches switches;
  QuasiStaticSettings quasi_static;
  std::int64_t max_steps = 20'000'000;

  std::string Validate() const;
};

struct TensileResult {
  std::vector<Metric> metrics;
  // "tensile_md" or "tensile_cd": strain, stress_N_per_m, lateral_stress_N_per_m, kinetic_J,
  // grip_work_J, drag_load_ratio, energy_{normal,shear,bending,twist}_J (increments), bonds_broken, branch
  // (0 first loading, 1 unloading, 2 reloading, ...).
  Curve curve;
  std::vector<double> fibre_energy_at_peak;  // per fibre [J], for snapshots
  std::vector<std::string> warnings;
  double mass_scale = 1.0, dt = 0.0;
  std::int64_t steps = 0;
  bool failed = false;       // the strip broke (stress fell below failure_drop * peak)
  bool quasi_static = true;  // the guard held

  double Value(const std::string& name) const;  // metric value; throws when absent
};

// Runs the test on a copy of `net`. Throws InputError for invalid settings, RunError when
// the simulation fails.
TensileResult RunTensileTest(Network net, const TensileSettings& s, const Progress& progress = {});

// Sheet stiffness per unit width of the affine (Cox) limit for the network's intra-fibre
// bonds: (1/A) sum k_n L0^2 cos^4(theta) for uniaxial strain along the axis (theta the bond's
// angle to it in the plane), and the fibre volume per sheet area sum A_f L0 / A [m], so that
// Cox's E_f phi / 3 per unit width is E_f * volume_per_area / 3.
struct AffineReference {
  double uniaxial_strain_N_per_m = 0.0;
  double fibre_volume_per_area = 0.0;  // [m]
  double mean_youngs_modulus = 0.0;    // bond-length weighted [Pa]
  double CoxN_per_m() const { return mean_youngs_modulus * fibre_volume_per_area / 3.0; }
};
AffineReference AffineStiffness(const Network& net, LoadAxis axis);

}  // namespace fibrenet::pipeline
