#include "engine/pipeline/crepe_profile.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

#include "engine/pipeline/percentile.h"
#include "engine/pipeline/profile_filter.h"

namespace fibrenet::pipeline {

namespace {

// Fills NaN entries between filled ones with the straight line between those.
void Interpolate(std::vector<double>& v) {
  std::size_t last = 0;
  for (std::size_t k = 1; k < v.size(); ++k) {
    if (std::isnan(v[k])) continue;
    for (std::size_t m = last + 1; m < k; ++m)
      v[m] = v[last] + (v[k] - v[last]) * double(m - last) / double(k - last);
    last = k;
  }
}

// Folds of the crepe band: rises from below mean - h to above mean + h (a profile element
// with a height discrimination of h, as roughness counts its elements).
int CountFolds(const std::vector<double>& band, double mean, double h) {
  int folds = 0;
  int side = 0;  // -1 last beyond the lower level, +1 beyond the upper, 0 neither yet
  for (double v : band) {
    if (v < mean - h) {
      side = -1;
    } else if (v > mean + h) {
      if (side < 0) ++folds;
      side = 1;
    }
  }
  return folds;
}

}  // namespace

CrepeProfile MeasureCrepeProfile(const std::vector<FramePoint>& points, double u_lo, double u_hi,
                                 double bin, double y_lo, double y_hi, double y_bin,
                                 double percentile) {
  CrepeProfile out;
  out.bin = bin;
  const int nu = std::max(1, static_cast<int>(std::floor((u_hi - u_lo) / bin)));
  const int ny = std::max(1, static_cast<int>(std::floor((y_hi - y_lo) / y_bin)));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> top(static_cast<std::size_t>(nu) * ny, nan), bottom(top.size(), nan);
  for (const FramePoint& p : points) {
    const int iu = static_cast<int>(std::floor((p.x.x() - u_lo) / bin));
    if (iu < 0 || iu >= nu) continue;
    const int iy = std::clamp(static_cast<int>(std::floor((p.x.y() - y_lo) / y_bin)), 0, ny - 1);
    const std::size_t k = static_cast<std::size_t>(iu) * ny + iy;
    const double hi = p.x.z() + p.radius, lo = p.x.z() - p.radius;
    top[k] = std::isnan(top[k]) ? hi : std::max(top[k], hi);
    bottom[k] = std::isnan(bottom[k]) ? lo : std::min(bottom[k], lo);
  }
  std::vector<double> height(nu, nan);
  std::vector<double> tops, bottoms;
  for (int iu = 0; iu < nu; ++iu) {
    double sum = 0.0;
    int filled = 0;
    for (int iy = 0; iy < ny; ++iy) {
      const std::size_t k = static_cast<std::size_t>(iu) * ny + iy;
      if (std::isnan(top[k])) continue;
      sum += top[k];
      ++filled;
      tops.push_back(top[k]);
      bottoms.push_back(bottom[k]);
    }
    if (filled > 0) height[iu] = sum / filled;
  }
  const auto filled = [](double h) { return !std::isnan(h); };
  const auto first = std::find_if(height.begin(), height.end(), filled);
  if (first != height.end()) {
    const auto last = std::find_if(height.rbegin(), height.rend(), filled).base();
    out.u0 = u_lo + double(first - height.begin()) * bin;
    out.height.assign(first, last);
    Interpolate(out.height);
  }
  if (!tops.empty())
    out.caliper = Percentile(tops, 1.0 - percentile / 100.0) - Percentile(bottoms, percentile / 100.0);
  return out;
}

CrepeSpectrum AnalyseCrepe(const std::vector<double>& height, double bin, const CrepeBand& band) {
  CrepeSpectrum s;
  const int n = static_cast<int>(height.size());
  if (n < 8 || !(bin > 0.0)) {  // too short to split: all waviness, no crepe band
    s.waviness = height;
    s.folds.assign(height.size(), 0.0);
    return s;
  }
  s.waviness = GaussianRegressionWaviness(height, bin, band.cutoff);
  // The texture filter's cutoff is half the shortest fold counted, so that folds from there up
  // pass nearly whole (97% at twice the cutoff).
  const std::vector<double> smooth =
      GaussianRegressionWaviness(height, bin, 0.5 * band.shortest_wavelength);
  s.folds.resize(n);
  double mean = 0.0, rms = 0.0;
  for (int j = 0; j < n; ++j) {
    s.folds[j] = smooth[j] - s.waviness[j];
    mean += s.folds[j] / n;
  }
  for (int j = 0; j < n; ++j) rms += (s.folds[j] - mean) * (s.folds[j] - mean) / n;
  s.amplitude = std::sqrt(2.0 * rms);
  // Hann window; the amplitude of a sine is recovered by dividing by the window's mean, 1/2.
  std::vector<double> windowed(n);
  for (int j = 0; j < n; ++j)
    windowed[j] = (0.5 - 0.5 * std::cos(2.0 * kPi * j / (n - 1))) * (s.folds[j] - mean);
  for (int k = 1; k <= n / 2; ++k) {
    std::complex<double> c = 0.0;
    for (int j = 0; j < n; ++j) c += windowed[j] * std::polar(1.0, -2.0 * kPi * k * j / n);
    s.frequencies.push_back(k / (n * bin));
    s.amplitudes.push_back(2.0 * std::abs(c) / (0.5 * n));
  }
  // Wavenumbers k (index k - 1) whose wavelength n bin / k lies in the band.
  const double length = n * bin;
  const int k_lo = std::max(2, static_cast<int>(std::ceil(length / band.cutoff - 1e-9)));
  const int k_hi =
      std::min(n / 2 - 1, static_cast<int>(std::floor(length / band.shortest_wavelength + 1e-9)));
  const std::vector<double>& a = s.amplitudes;
  int best = -1;
  for (int k = k_lo; k <= k_hi; ++k) {
    const double here = a[k - 1];
    if (here > a[k - 2] && here > a[k] && (best < 0 || here > a[best - 1])) best = k;
  }
  s.fold_count = CountFolds(s.folds, mean, band.min_amplitude);
  if (best < 0) return s;
  s.peak_amplitude = a[best - 1];
  if (s.peak_amplitude < band.min_amplitude || s.fold_count < kFoldsInATrain) return s;
  // Parabolic refinement of the peak on its neighbours.
  const double left = a[best - 2], peak = a[best - 1], right = a[best];
  s.frequency = (best + 0.5 * (left - right) / (left - 2.0 * peak + right)) / length;
  return s;
}

double ContourRatio(const std::vector<double>& height, double bin) {
  if (height.size() < 2) return 1.0;
  double length = 0.0;
  for (std::size_t k = 1; k < height.size(); ++k)
    length += std::hypot(bin, height[k] - height[k - 1]);
  return length / (static_cast<double>(height.size() - 1) * bin);
}

}  // namespace fibrenet::pipeline
