// QuatFromRotationVector: its series branch for small rotations (below kSmallRotation2, the
// size of every step's rotation) agrees with the closed form to rounding, and so does the
// closed form above it; the result is a unit quaternion either way.
#include "engine/core/quaternion.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace fibrenet {
namespace {

// The closed form in long double, as the reference.
Quat Reference(const Vec3& phi) {
  const long double angle = std::sqrt(static_cast<long double>(phi.squaredNorm()));
  const long double h = 0.5L * angle, s = std::sin(h) / angle;
  return Quat(static_cast<double>(std::cos(h)), static_cast<double>(s * phi.x()),
              static_cast<double>(s * phi.y()), static_cast<double>(s * phi.z()));
}

TEST(Quaternion, RotationVectorMatchesTheClosedFormOnBothSidesOfTheSeriesLimit) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> gauss;
  const double limit = std::sqrt(kSmallRotation2);
  for (double angle : {1e-12, 1e-9, 1e-6, 1e-4, 1e-3, 0.5 * limit, 0.999 * limit, limit,
                       1.001 * limit, 0.1, 1.0, 3.0}) {
    for (int k = 0; k < 20; ++k) {
      const Vec3 axis = Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
      const Vec3 phi = angle * axis;
      const Quat q = QuatFromRotationVector(phi), r = Reference(phi);
      EXPECT_NEAR(q.w(), r.w(), 4e-16) << "angle " << angle;
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(q.vec()[c], r.vec()[c], 4e-16 * std::max(1.0, angle)) << "angle " << angle;
      EXPECT_NEAR(q.norm(), 1.0, 4e-16) << "angle " << angle;
    }
  }
}

}  // namespace
}  // namespace fibrenet
