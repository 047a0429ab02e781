// Percentiles of samples, shared by the thickness and crepe-profile measurements.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace fibrenet::pipeline {

// The q-quantile (q in [0, 1]) by linear interpolation between order statistics; 0 when
// there are no samples.
inline double Percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const double pos = std::clamp(q, 0.0, 1.0) * static_cast<double>(v.size() - 1);
  const auto k = static_cast<std::size_t>(std::floor(pos));
  if (k + 1 >= v.size()) return v.back();
  return v[k] + (pos - static_cast<double>(k)) * (v[k + 1] - v[k]);
}

}  // namespace fibrenet::pipeline
