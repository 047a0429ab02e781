// Waviness of a profile: the second-order Gaussian regression filter of surface metrology
// (ISO 16610-31). At each point a parabola is fitted to the profile by least squares with
// Gaussian weights exp(-pi (t / (gamma cutoff))^2); its value there is the waviness. The
// fit reproduces a parabola exactly, so a sloped or bowed profile has no edge error and no
// end of the profile needs to be dropped. gamma = 0.7309 passes half the amplitude of a
// sine whose wavelength is the cutoff; the profile minus its waviness is its roughness.
#pragma once

#include <vector>

namespace fibrenet::pipeline {

// Waviness of `height`, sampled every `bin`, for the cutoff wavelength `cutoff` (same unit).
std::vector<double> GaussianRegressionWaviness(const std::vector<double>& height, double bin,
                                               double cutoff);

}  // namespace fibrenet::pipeline
