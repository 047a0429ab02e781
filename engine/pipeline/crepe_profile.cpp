#include "engine/pipeline/crepe_profile.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

#include "engine/pipeline/percentile.h"

namespace fibrenet::pipeline {

namespace {

// Fills NaN entries from the nearest filled entry before them (or after, at the start).
void FillGaps(std::vector<double>& v) {
  double last = std::numeric_limits<double>::quiet_NaN();
  for (double& x : v) {
    if (std::isnan(x)) x = last;
    else last = x;
  }
  for (auto it = v.rbegin(); it != v.rend(); ++it) {
    if (std::isnan(*it)) *it = last;
    else last = *it;
  }
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
  out.height.assign(nu, nan);
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
    if (filled > 0) out.height[iu] = sum / filled;
  }
  FillGaps(out.height);
  if (!tops.empty())
    out.caliper = Percentile(tops, 1.0 - percentile / 100.0) - Percentile(bottoms, percentile / 100.0);
  return out;
}

CrepeSpectrum AnalyseCrepe(const std::vector<double>& height, double bin) {
  CrepeSpectrum s;
  const int n = static_cast<int>(height.size());
  if (n < 8 || !(bin > 0.0)) return s;
  // Least-squares line through the profile, removed.
  double su = 0.0, sh = 0.0, suu = 0.0, suh = 0.0;
  for (int j = 0; j < n; ++j) {
    su += j;
    sh += height[j];
    suu += double(j) * j;
    suh += j * height[j];
  }
  const double slope = (n * suh - su * sh) / (n * suu - su * su);
  const double offset = (sh - slope * su) / n;
  std::vector<double> z(n);
  double rms = 0.0;
  for (int j = 0; j < n; ++j) {
    z[j] = height[j] - (offset + slope * j);
    rms += z[j] * z[j];
  }
  s.amplitude = std::sqrt(2.0 * rms / n);
  // Hann window; the amplitude of a sine is recovered by dividing by the window's mean, 1/2.
  const double pi = 3.14159265358979323846;
  double best = -1.0;
  int best_k = 0;
  std::vector<double> mag;
  for (int k = 2; k <= n / 2; ++k) {  // k = 1 is a wavelength of the whole profile
    std::complex<double> c = 0.0;
    for (int j = 0; j < n; ++j) {
      const double w = 0.5 - 0.5 * std::cos(2.0 * pi * j / (n - 1));
      c += w * z[j] * std::polar(1.0, -2.0 * pi * k * j / n);
    }
    const double a = 2.0 * std::abs(c) / (0.5 * n);
    mag.push_back(a);
    s.frequencies.push_back(k / (n * bin));
    s.amplitudes.push_back(a);
    if (a > best) {
      best = a;
      best_k = k;
    }
  }
  // Parabolic refinement of the peak on its neighbours (indices in mag are k - 2).
  double k_peak = best_k;
  const int m = best_k - 2;
  if (m > 0 && m + 1 < static_cast<int>(mag.size())) {
    const double a = mag[m - 1], b = mag[m], c = mag[m + 1];
    const double denom = a - 2.0 * b + c;
    if (denom < 0.0) k_peak += 0.5 * (a - c) / denom;
  }
  s.frequency = k_peak / (n * bin);
  return s;
}

}  // namespace fibrenet::pipeline
