// Thickness-direction (ZD) compression with unloading (paper 3.6; SPEC 2.5).
//
// Procedure. The network is copied and put between two platens: a floor (Wall, side +1) at
// the lowest particle's bottom and a top platen (Wall, side -1) at the highest particle's
// top, both periodic in x and y. The top platen comes down at strain_rate times the initial
// gap (faster in the approach, slower in the toe: see the settings), until the strain reaches
// max_strain or the pressure max_pressure, then goes back up at the speed it had at the turn
// until the pressure is gone (or the gap is the initial one). Contacts (van Wyk, with friction
// as the switches say) are on.
// Quasi-static control as for the tensile test (test_rig.h), with the affine field
// u_z = v_platen (z - z_floor) / gap.
//
// Definitions:
//  strain                   (h0 - gap) / h0, h0 the gap at first contact [-]
//  pressure [Pa]            top platen force / cell area
//  zd_modulus_kPa           least-squares slope d pressure / d strain of the loading branch
//                           over modulus_pressure_lo <= p <= modulus_pressure_hi (default
//                           0.5..2 kPa, the range of caliper and handfeel tests; when the test
//                           peaks below the top of the window, 25%..100% of the peak)
//  zd_thickness_um          h0
//  zd_compression_energy_J_per_m2  loading work per area, h0 * integral p d(strain) (KES WC)
//  zd_hysteresis_fraction   (loading work - unloading work) / loading work (1 - KES RC)
//  zd_residual_strain       strain at which the unloading pressure has fallen to
//                           residual_pressure_fraction (1%) of the peak
//  zd_snap_throughs         falls of the loading pressure by more than 10% from its highest
//                           since the last fall (from 1% of modulus_pressure_lo on)
//  zd_peak_pressure_kPa, zd_max_strain, zd_kinetic_work_ratio and zd_drag_load_ratio (the
//  guards, as for the tensile test, over the loading from the window start to the peak;
//  the kinetic one also over the unloading down to the window start, against the loading
//  work), zd_mass_scale
// Attribution (optional, attribution = true; three extra runs): the base run keeps every
// mechanism; each variant switches one off (bond failure; friction, i.e. dissipative fibre
// slippage; Maxwell viscoelasticity). zd_hysteresis_share_<m> = (H_base - H_without_m) /
// H_base and zd_residual_share_<m> likewise for the residual strain, m in {bond_breakage,
// slippage, viscous}; they need not sum to one (mechanisms interact; the rest is
// rearrangement and contact damping).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "engine/pipeline/curves.h"
#include "engine/pipeline/network.h"
#include "engine/pipeline/progress.h"
#include "engine/pipeline/test_rig.h"

namespace fibrenet::pipeline {

struct CompressionSettings {
  // Continuous: the platen comes down without stopping, at the speeds the keys below set.
  // Stepped: it comes down by max_strain / samples at the full speed, then stands until the
  // sheet is at rest (kinetic energy within toe_kinetic_share x kinetic_work_tolerance of the
  // platen work, or of one move's work at modulus_pressure_lo while the platen has done less;
  // and the two platens' loads equal within kinetic_work_tolerance of the larger, or of the
  // load at modulus_pressure_lo), and the curve is sampled there; unloading likewise. Its
  // curve is a path of rest states: a snap-through of the sheet (the loops of a creped sheet
  // toppling) settles and is counted (zd_snap_throughs) instead of reading as loading too
  // fast, and the platen crosses empty space at the full speed. The approach and the
  // feedback keys act on the continuous loading only.
  enum class Loading { kContinuous, kStepped };
  Loading loading = Loading::kContinuous;
  std::int64_t settle_max_steps = 0;  // stepped: most steps a rest may take (0: 100 x a move's)
  // Stepped: the moves shrink where the curve is steep. A move whose rest pressure has risen
  // (loading) or fallen (unloading) by more than the allowed step since the last rest is
  // undone and made again at half its gap, at most max_move_halvings times; after a move
  // that changed it by less than half the step, the next one doubles, up to max_strain /
  // samples. The allowed step is (modulus_pressure_hi - modulus_pressure_lo) /
  // window_samples while the last rest's pressure is below modulus_pressure_hi, and
  // pressure_step_fraction x that pressure above it. A creped sheet's web is met within one
  // move of the loops' grid otherwise. window_samples = 0: every move at max_strain / samples.
  int window_samples = 8;
  double pressure_step_fraction = 0.25;
  int max_move_halvings = 12;
  double max_strain = 0.6;        // (0, 0.95]
  double max_pressure = 0.0;      // [Pa]; > 0: stop loading at this pressure (or max_strain)
  double strain_rate = 1.0;       // platen speed / h0 [1/s]
  // Slow toe: while loading, the platen speed is the full speed times
  // sqrt(toe_kinetic_share x kinetic_work_tolerance x platen work so far / kinetic energy of
  // the affine field at the full speed), within [min_speed_fraction, 1] (1 = constant speed).
  // With the masses scaled, a sheet moving at the full speed holds far more kinetic energy
  // than the platen has put in during the toe; the kinetic energy goes as the speed squared.
  double min_speed_fraction = 0.01;
  double toe_kinetic_share = 0.25;  // (0, 1]
  // Approach (off by default): until the pressure first reaches approach_pressure_fraction x
  // modulus_pressure_lo, the platen comes down at approach_speed_fraction of the full speed
  // (never slower than the slow toe would). No figure is read there: the guard starts at the
  // modulus window. On the generic tissue, 0.03 to 0.5 saves 20% of the steps and shifts the
  // hysteresis by -1.3% and the peak pressure by +1.3% (three replicates each,
  // docs/virtual-tests.md): off by default, a scene asks for it. 0 (or <= min_speed_fraction):
  // none.
  double approach_speed_fraction = 0.0;
  double approach_pressure_fraction = 0.25;
  // Tapered approach (off by default): the platen starts at the full speed and comes down at
  // approach_speed_fraction x sqrt(approach end pressure / pressure) of it, never faster than
  // the full speed and never speeding up again, so that the kinetic energy the platen puts
  // into the sheet per unit of pressure stays what it is at the approach's end. The toe of a
  // sheet whose highest fibres stand above the rest carries a few pascals over much of the
  // approach's strain: the 2.5 mm generic tissue takes 8% fewer steps with its ZD metrics
  // within the replicates' scatter (docs/virtual-tests.md).
  bool approach_taper = false;
  // Feedback above the window (off by default): once the pressure has passed
  // modulus_pressure_hi, the platen may go faster than the slow toe's rule, as far as the
  // kinetic energy it measures (beyond the affine field) allows: every 1/400 of the loading
  // time at the full speed, the speed is multiplied by sqrt(toe_kinetic_share x tolerance /
  // (kinetic energy / platen work)), at most x 1.05 and at least x 0.5, and never set below
  // the rule. The rule assumes the sheet's motion beyond the affine field is as large as the
  // affine field's; past a few kPa it is a tenth of that or less. The modulus window is run
  // as without it, so zd_modulus_kPa does not change (docs/virtual-tests.md).
  bool feedback_above_window = false;
  // Feedback from the window's start (off by default; needs feedback_above_window): the
  // feedback above acts from modulus_pressure_lo on, through the window too. The window at
  // the min_speed_fraction floor reads the modulus above the run at half the floor (1.7% on
  // the 2.5 mm generic tissue); with the feedback through it, 0.9%, in 11% fewer steps
  // (docs/virtual-tests.md).
  bool feedback_in_window = false;
  double modulus_pressure_lo = 500.0, modulus_pressure_hi = 2000.0;  // [Pa]
  double residual_pressure_fraction = 0.01;
  // The van Wyk fit's pressure range [Pa] (0 = from 1% of the highest pressure fitted; no top
  // but the first bond failure). The bonded generic tissue's local exponent falls from more
  // than 30 at a few kPa to about 5 at 100-290 kPa, so the exponent is the range's as much as
  // the sheet's: sheets are compared over one range (docs/virtual-tests.md).
  double van_wyk_pressure_lo = 0.0, van_wyk_pressure_hi = 0.0;
  int samples = 400;              // curve points over the loading
  bool attribution = false;       // run the three variants for the sources of hysteresis
  MaterialSwitches switches;
  QuasiStaticSettings quasi_static;
  std::int64_t max_steps = 20'000'000;

  std::string Validate() const;
};

struct CompressionResult {
  std::vector<Metric> metrics;
  // "compression": strain, pressure_Pa, gap_m, kinetic_J, platen_work_J, drag_load_ratio, bonds_broken,
  // branch (0 loading, 1 unloading); with attribution also compression_<variant>.
  std::vector<Curve> curves;
  std::vector<std::string> warnings;
  double h0 = 0.0;  // [m]
  double mass_scale = 1.0, dt = 0.0;
  std::int64_t steps = 0;
  bool quasi_static = true;

  double Value(const std::string& name) const;
};

CompressionResult RunCompressionTest(const Network& net, const CompressionSettings& s,
                                     const Progress& progress = {});

// Snap-throughs of a loading branch: falls of the pressure by more than 10% from its highest
// since the last fall, once that highest has passed from_pressure [Pa].
int CountSnapThroughs(const std::vector<double>& loading_pressure, double from_pressure);

// Fit of the loading branch to the van Wyk form p = k (phi^n - phi0^n), phi the fibre volume
// fraction (fibre volume / (cell area x gap)). For each n on a fine grid, k and k phi0^n follow
// by linear least squares; the n with the smallest residual wins.
struct VanWykFit {
  double n = 0.0, k = 0.0, phi0 = 0.0;  // exponent, [Pa], [-]
  double r2 = 0.0;                      // coefficient of determination
  double p_top = 0.0;                   // highest pressure fitted [Pa]
  double p_bottom = 0.0;                // lowest pressure fitted [Pa]
};
// The van Wyk form is the elastic densification of the network (fibre segments bending
// between contacts): it is fitted up to the first bond failure (the samples before
// "bonds_broken" first rises, where the curve has that column), not through the breaking
// that softens a bonded sheet's curve beyond it. phi = phi_h0 / (1 - strain), phi_h0 the
// volume fraction at h0. Fits the loading samples with p_lo <= p <= p_hi (p_lo = 0: 1% of
// the highest pressure of that range; p_hi = 0: no top), n on a 0.01 grid in [1, 30]; fewer
// than three samples: no fit (n = 0, r2 = 0).
VanWykFit FitVanWyk(const Curve& compression, double phi_h0, double p_lo = 0.0,
                    double p_hi = 0.0);
// Fibre volume of the network, sum over fibres of pi (d/2)^2 * length [m^3], for phi.
double FibreVolume(const Network& net);

}  // namespace fibrenet::pipeline
