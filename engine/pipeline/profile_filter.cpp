#include "engine/pipeline/profile_filter.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "engine/core/types.h"

namespace fibrenet::pipeline {

std::vector<double> GaussianRegressionWaviness(const std::vector<double>& height, double bin,
                                               double cutoff) {
  constexpr double kGamma = 0.7309;  // 50% transmission at the cutoff for the parabola fit
  const int n = static_cast<int>(height.size());
  std::vector<double> waviness(height);
  if (n < 3 || !(bin > 0.0) || !(cutoff > 0.0)) return waviness;
  const double width = kGamma * cutoff / bin;  // in samples
  // The weights fall below 4e-6 beyond two widths; at least two samples either side, so that
  // every fit has three distinct points even at the ends.
  const int reach = std::max(2, static_cast<int>(std::ceil(2.0 * width)));
  std::vector<double> weight(reach + 1);
  for (int d = 0; d <= reach; ++d) weight[d] = std::exp(-kPi * (d / width) * (d / width));
  for (int i = 0; i < n; ++i) {
    // Normal equations of the weighted fit h ~ a + b t + c t^2, t in samples from i.
    Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
    for (int j = std::max(0, i - reach); j <= std::min(n - 1, i + reach); ++j) {
      const double t = j - i, w = weight[std::abs(j - i)];
      const Eigen::Vector3d basis(1.0, t, t * t);
      m += w * basis * basis.transpose();
      rhs += w * height[j] * basis;
    }
    waviness[i] = m.ldlt().solve(rhs)[0];
  }
  return waviness;
}

}  // namespace fibrenet::pipeline
