// Creping (paper 3.3): the pressed sheet, glued to the Yankee dryer by its coating, meets the
// doctor blade at the Yankee speed; it is scraped off, buckles into folds against the blade,
// loses bonds and sheds dust, and leaves along the blade face towards the reel.
//
// Frame. The simulation runs in the frame of the Yankee surface: the surface (the plane
// z = 0) and the glued sheet are at rest and the blade moves at -yankee_speed along x (MD).
// Over the simulated length (a few mm) the Yankee's curvature (radius 2-3 m) changes the
// surface height by well under a micrometre, a small fraction of a fibre radius, so a flat
// surface is enough. The sheet is cut open along MD (a finite strip, fibres crossing its
// ends cut) and stays periodic across (CD). Real inertia: no mass scaling; bond failure on.
//
// Adhesion. Every particle whose bottom lies within adhesion.reach radii of the surface is
// held by an adhesive beam bond (BondKind::kAdhesive, glue.h) to a fixed anchor, its mirror
// image below the surface: the stiffness of a glue layer, failure by the Hill criterion with
// the coating's peel and shear strengths, which may scatter (lognormal, strength_cv, sampled
// in 16 equiprobable classes), and optionally the coating's damping.
//
// The reel. The creped sheet is drawn away along the blade face at the reel speed
// yankee_speed / (1 + crepe_ratio): particles the blade has passed (their place on the
// Yankee is behind the tip) and that lie beyond takeaway_height along the face from the tip
// feel a drag of relaxation time takeaway_time towards that velocity (in the Yankee frame:
// the blade's velocity plus the reel speed along the face). The drag moves the drawn sheet
// rigidly and so does not reshape its folds; its work is booked as applied work. Sheet the
// blade has not reached, lifted off the Yankee ahead of it, is not drawn.
//
// Metrics. The creped sheet (the largest piece held together by intact bonds, beyond the
// takeaway height) is read in its own frame (u along its MD axis, the principal axis of its
// mass in the plane of MD and thickness; h normal to it):
// crepe_profile.h gives the crepe frequency (folds per mm of creped sheet), the amplitude and
// the caliper at the blade. Dust: every other piece. bulk_gain is the creped sheet's caliper
// once it has come to rest off the blade (below) against the sheet's before creping.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/pipeline/curves.h"
#include "engine/pipeline/forming.h"
#include "engine/pipeline/glue.h"
#include "engine/pipeline/metrics.h"
#include "engine/pipeline/network.h"
#include "engine/pipeline/progress.h"

namespace fibrenet::pipeline {

struct CrepingSettings {
  double yankee_speed = 30.0;        // [m/s]
  double creping_angle = 1.4835298641951802;  // blade face to the Yankee surface [rad] (85 deg)
  double crepe_ratio = 0.15;         // Yankee speed / reel speed - 1
  double takeaway_height = 0.0;      // [m] along the face; 0 = 3 x the sheet's caliper
  double takeaway_time = 2e-6;       // [s]
  double tip_clearance = 0.0;        // blade tip above the surface [m]
  // Run-in: the blade starts from rest and reaches the Yankee speed, at a constant
  // acceleration, once it has scraped this length of the strip [m], so that the cut leading
  // end is not rammed end-on at full speed, as a continuous sheet never is. 0 = off (the
  // blade at full speed from the start). It must lie within the leading end zone.
  double run_in_length = 0.0;
  // Hard core of the steel blade and Yankee (blade.h) [N/m]. It must hold particles out of
  // the pinch between the face and the Yankee at the tip: at 3e4 (a fibre wall of transverse
  // modulus 1 GPa over a particle's 32 um) the crushing load of a web with strong bonds
  // (about 3 kN/m) squeezed a particle under the tip in every run; from 1.2e5 on none passes
  // and the creping metrics no longer move with it beyond their scatter (docs/creping.md).
  double blade_hard_stiffness = 1.2e5;
  // Hard core of fibre-fibre contacts during creping (VanWykParams::hard_stiffness): two
  // collapsed fibre walls (1 GPa over 32 um each) in series [N/m]. Without it the pile-up at
  // the blade pressed cross-sections through each other (centre distance down to 2% of
  // R_i + R_j).
  double fibre_hard_stiffness = 1.5e4;
  // Coulomb friction of the sheet on the blade's steel; unset, the fibre-fibre contacts' mu.
  // It resists the sheet's climb up the face, the one brake on it besides the reel's draw.
  std::optional<double> blade_friction_mu;
  AdhesionSettings adhesion;
  // After the blade: the dust and the pieces left on the Yankee are removed, and the creped
  // sheet, free of blade and coating, comes to rest on a floor by dynamic relaxation (masses
  // x relax_mass_scale, background drag of relaxation time relax_damping_time, bond dashpots
  // at relax_bond_damping_ratio of critical) until its
  // kinetic energy is below relax_kinetic_ratio of its strain energy, or its strain energy
  // changes by less than relax_energy_tolerance over 50 damping times.
  double relax_mass_scale = 1000.0;  // >= 1
  double relax_damping_time = 1e-5;  // [s]
  double relax_bond_damping_ratio = 0.5;  // bond dashpots, fraction of critical, [0, 1]
  double relax_kinetic_ratio = 1e-3; // (0, 1)
  double relax_energy_tolerance = 0.01;  // (0, 1)
  std::int64_t relax_max_steps = 50'000;
  // bonds_broken_fraction counts the fibre-fibre bonds of the strip's middle: this fraction
  // of its length at either cut end is left out (the blade's first blow on the leading end
  // breaks bonds that a continuous sheet keeps). [0, 0.45]
  double end_zone_fraction = 0.2;
  // The crepe band (crepe_profile.h): the waviness cutoff, 800 um as surface metrology
  // takes for profiles whose elements are 0.13-0.4 mm apart (ISO 4288), so that folds of
  // up to 0.4 mm pass whole and the sheet's millimetre-long curving away from the blade
  // does not; the shortest fold wavelength (0 = 4 mean particle diameters of the sheet:
  // shorter is the fibres' own texture); a fold train's least amplitude (0 = the sheet's
  // mean particle radius). [m]
  double crepe_cutoff = 800e-6;
  double crepe_shortest_wavelength = 0.0;
  double crepe_min_amplitude = 0.0;
  int curve_samples = 200;           // rows of the bond-loss curve
  int impact_frames = 0;             // snapshots kept during the impact (paper Fig. 6)
  std::int64_t max_steps = 20'000'000;

  std::string Validate() const;
};

struct CrepingResult {
  std::int64_t steps = 0;
  double dt = 0.0;
  double simulated_time = 0.0;             // [s]
  std::size_t adhesive_bonds = 0;
  std::size_t bonds_cut = 0;                // fibre and fibre-fibre bonds cut at the MD ends
  double bonds_broken_fraction = 0.0;      // fibre-fibre bonds broken / those at the start,
                                           // in the strip's middle (end_zone_fraction)
  double bonds_broken_fraction_all = 0.0;  // the same over the whole strip
  double fibre_bonds_broken = 0.0;         // intra-fibre bonds broken (fibres that broke)
  double adhesive_broken_fraction = 0.0;
  double crepe_frequency = 0.0;             // [1/m] of creped sheet; 0: no fold train
  double crepe_amplitude = 0.0;             // [m] sqrt(2) x the crepe band's RMS
  // The crepe profile's length [m], the least fold amplitude counted [m] and the folds of
  // that amplitude the crepe band holds (a train needs kFoldsInATrain).
  double crepe_profile_length = 0.0, crepe_min_amplitude = 0.0;
  int crepe_fold_count = 0;
  // Where the Yankee length went, read over the crepe profile: the sheet's mass per unit of
  // its projected length over that on the Yankee (the Yankee length gathered into a unit of
  // creped sheet; 1 + crepe_ratio for a sheet the reel takes up at its own speed), split into
  // the contour of the sheet's long shape (waviness) over its projection, the contour of the
  // folds on it (waviness + crepe band over waviness) and what is left, the sheet's own
  // shortening in its plane: gathered = curl x fold x in_plane.
  double crepe_gathered_ratio = 0.0, crepe_curl_ratio = 0.0, crepe_fold_ratio = 0.0,
         crepe_in_plane_ratio = 0.0;
  // Plate calipers [m]: of the sheet before creping and of the creped sheet at rest, both
  // in the sheet's frame (bulk_gain = after / before), and of the creped sheet in its own
  // frame as the blade leaves it (caliper_at_blade).
  double caliper_before = 0.0, caliper_after = 0.0, caliper_at_blade = 0.0;
  double bulk_gain = 0.0;
  std::size_t dust_count = 0;
  double dust_mass_fraction = 0.0;
  double energy_balance_error = 0.0;        // |accounted change| / blade work
  double blade_work = 0.0;                  // [J]
  // Contact energy the pairs of broken bonds regained: the overlap the bonds held since
  // pressing (EnergyLedger::overlap_regained) [J]
  double overlap_regained = 0.0;
  double peak_blade_force = 0.0;            // [N per m of width]
  // How far ahead of the tip the web is off the Yankee (peel_front.h) [m]: the median over the
  // samples with the tip over the strip's middle, and the largest at any sample.
  double delaminated_length = 0.0, delaminated_length_max = 0.0;
  // The glued particles' peel energy F_r0^2 / (2 k_n) per m^2 of strip [J/m^2], against the
  // momentum flux rho_A V^2 of the sheet the blade turns up its face [N/m].
  double coating_toughness = 0.0, momentum_flux = 0.0;
  double reel_tension = 0.0;                // the reel's mean pull along the face while it
  double peak_reel_tension = 0.0;           // draws the sheet, and its peak [N per m of width]
  std::size_t particles_past_blade = 0;     // most free particles behind the face at once
  std::size_t particles_removed = 0;        // dust and pieces left on the Yankee
  double sheet_mass_fraction = 0.0;         // creped sheet mass / sheet mass before
  std::int64_t relax_steps = 0;
  bool relaxed = false;                     // the creped sheet came to rest
  double min_contact_ratio = 1.0;
  Curve bond_loss;                          // time since the start of creping, broken
                                            // fractions, blade force, energies
  Curve crepe_profile;                      // u, height of the creped sheet's top surface
  std::vector<World> impact_frames;         // the world at evenly spaced times of the impact
  std::vector<std::string> warnings;
};

// Crepes the sheet; on return `net` holds the creped sheet alone (dust, the pieces left on
// the Yankee, anchors and blade removed), laid in the sheet frame (x along its own MD axis,
// the principal axis of its mass in the x-z plane; z up from its base; open along x,
// periodic along y) and relaxed at rest on the floor z = 0. Throws RunError when the run
// goes unstable.
CrepingResult Crepe(Network& net, const SheetSpec& sheet, const CrepingSettings& s,
                    const MetricsSettings& metrics, std::uint64_t seed, const Progress& progress);

}  // namespace fibrenet::pipeline
