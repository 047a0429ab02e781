// The crepe of a creped sheet, read from its surface the way a profilometer reads it: the
// sheet is described in its own frame (u along the machine direction of the creped sheet,
// y across, h the height above its base plane), the top surface is the highest particle
// surface in each (u, y) bin, and the MD height profile is that surface averaged across y.
// The profile is not periodic (a creped strip has two ends): it is detrended and
// Hann-windowed before its spectrum is taken.
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
  std::vector<double> height;  // mean top surface per u bin [m]
  // Caliper: the distance between two plates resting on the surface, read as the given
  // percentile of the bins' top heights from above and of their bottom heights from below.
  double caliper = 0.0;        // [m]
};

// Bins of `bin` along u over [u_lo, u_hi) and of `y_bin` across y; empty u bins are filled
// from their neighbours. `percentile` (in %) sets the caliper's plates.
CrepeProfile MeasureCrepeProfile(const std::vector<FramePoint>& points, double u_lo, double u_hi,
                                 double bin, double y_lo, double y_hi, double y_bin,
                                 double percentile);

struct CrepeSpectrum {
  double frequency = 0.0;  // dominant folds per unit length [1/m]
  double amplitude = 0.0;  // sqrt(2) x the RMS of the detrended profile [m]
  std::vector<double> frequencies, amplitudes;  // the one-sided spectrum [1/m], [m]
};

// Dominant frequency of a profile sampled every `bin`: the peak of the amplitude spectrum of
// the detrended, Hann-windowed profile, refined by a parabola through the peak and its
// neighbours. Wavelengths longer than half the profile are not counted.
CrepeSpectrum AnalyseCrepe(const std::vector<double>& height, double bin);

}  // namespace fibrenet::pipeline
