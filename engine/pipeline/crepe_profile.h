// The crepe of a creped sheet, read from its surface the way a profilometer reads it: the
// sheet is described in its own frame (u along the machine direction of the creped sheet,
// y across, h the height above its base plane), the top surface is the highest particle
// surface in each (u, y) bin, and the MD height profile is that surface averaged across y.
//
// The folds are read the way surface metrology separates roughness from waviness: the
// sheet's own long shape (a sheet curving away from the blade, a strip bowed over
// millimetres) is the waviness, removed by a Gaussian regression filter of cutoff `cutoff`
// (profile_filter.h); the particles' own texture is removed the same way, with half the
// shortest fold wavelength counted, `shortest_wavelength`, as its cutoff. What is left is
// the crepe band. Its spectrum (Hann-windowed: the profile has two ends) has a fold train
// where it has a peak that rises above both neighbours with an amplitude of at least
// `min_amplitude` (folds lower than a fibre's radius are the surface's texture, not crepe)
// and the band holds at least three folds of that amplitude (one buckle is not a train).
#pragma once

#include <vector>

#include "engine/core/types.h"

namespace fibrenet::pipeline {

// A particle in the sheet's frame: x = (u, y, h), and its radius.
struct FramePoint {
  Vec3 x;
  double radius = 0.0;
};

struct CrepeProfile {
  double bin = 0.0;            // u step of the profile [m]
  double u0 = 0.0;             // u of the start of the first bin [m]
  std::vector<double> height;  // mean top surface per u bin [m]
  // Caliper: the distance between two plates resting on the surface, read as the given
  // percentile of the bins' top heights from above and of their bottom heights from below.
  double caliper = 0.0;        // [m]
};

// Bins of `bin` along u over [u_lo, u_hi) and of `y_bin` across y. The profile covers the
// bins from the first to the last the sheet reaches (u0 says where it starts); empty bins
// between them take the straight line between their filled neighbours. `percentile`
// (in %) sets the caliper's plates.
CrepeProfile MeasureCrepeProfile(const std::vector<FramePoint>& points, double u_lo, double u_hi,
                                 double bin, double y_lo, double y_hi, double y_bin,
                                 double percentile);

// The wavelengths that count as folds [m].
struct CrepeBand {
  double cutoff = 800e-6;               // longest: the waviness filter's cutoff
  double shortest_wavelength = 128e-6;  // shortest: the texture filter's cutoff
  double min_amplitude = 16e-6;         // a fold's least amplitude (the peak, the count)
};

// Folds a profile needs to hold for a fold train.
inline constexpr int kFoldsInATrain = 3;

struct CrepeSpectrum {
  double frequency = 0.0;        // the fold train's folds per unit length; 0: none [1/m]
  double peak_amplitude = 0.0;   // a sine's amplitude at the band's highest peak [m]
  // Rises of the crepe band from below -min_amplitude to above +min_amplitude.
  int fold_count = 0;
  double amplitude = 0.0;        // sqrt(2) x the RMS of the crepe band [m]
  // The profile split, one entry per profile bin (a profile too short to split is all
  // waviness): its long shape, and the crepe band (profile - waviness - texture) [m].
  std::vector<double> waviness, folds;
  std::vector<double> frequencies, amplitudes;  // the crepe band's one-sided spectrum [1/m], [m]
};

// The crepe of a profile sampled every `bin`. The spectrum's peak is sought among the
// wavelengths from band.shortest_wavelength to the shorter of band.cutoff and half the
// profile (two folds at least), and refined by a parabola through it and its neighbours.
CrepeSpectrum AnalyseCrepe(const std::vector<double>& height, double bin, const CrepeBand& band);

// The length of the profile's line over its projected length, (size - 1) x bin: 1 for a flat
// profile (or one of fewer than two points), sqrt(1 + s^2) for a slope s.
double ContourRatio(const std::vector<double>& height, double bin);

}  // namespace fibrenet::pipeline
