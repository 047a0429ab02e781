// The rotation helpers switch from Taylor series to closed forms at an angle (QuatFromRotation-
// Vector at kSmallRotation2, the size of every step's rotation; RotationVector and the SO(3)
// Jacobians at kBondSeriesAngle2, beyond a bond's usual relative rotation, and from short to
// long series at kShortSeriesAngle2). On both sides of each switch they agree with a long
// double reference to rounding.
#include "engine/core/quaternion.h"

#include <cmath>
#include <vector>
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

// Angles [rad] on both sides of the series limit `limit` and of the short series' limit, from
// tiny to near a half turn.
std::vector<double> AnglesAround(double limit) {
  const double short_limit = std::sqrt(kShortSeriesAngle2);
  return {1e-12, 1e-8, 1e-4, 1e-2, 0.999 * short_limit, short_limit, 1.001 * short_limit,
          0.5 * limit, 0.999 * limit, limit, 1.001 * limit, 0.5, 1.0, 2.0, 3.0};
}

TEST(Quaternion, RotationVectorMatchesAtan2OnBothSidesOfTheSeriesLimit) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> gauss;
  for (double angle : AnglesAround(std::sqrt(kBondSeriesAngle2))) {
    for (int k = 0; k < 20; ++k) {
      const Vec3 axis = Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
      Quat q = QuatFromRotationVector(angle * axis);
      if (k % 2 == 1) q.coeffs() = -q.coeffs();  // the same rotation: the short way is taken
      const long double sign = q.w() < 0.0 ? -1.0L : 1.0L;
      const long double x = sign * q.x(), y = sign * q.y(), z = sign * q.z(), w = sign * q.w();
      const long double s = std::sqrt(x * x + y * y + z * z);
      const long double scale = 2.0L * std::atan2(s, w) / s;
      const Vec3 theta = RotationVector(q);
      const long double expected[3] = {scale * x, scale * y, scale * z};
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(theta[c], static_cast<double>(expected[c]), 4e-16 * angle) << "angle " << angle;
      }
    }
  }
}

// c1 = (1 - cos a) / a^2 and c2 = (a - sin a) / a^3 by their series in long double (20 terms,
// exact to its rounding for a <= 1) or by the closed forms in long double above that.
LeftJacobianCoefficients ReferenceCoefficients(double angle) {
  const long double a = angle, a2 = a * a;
  if (angle > 1.0) {
    return {static_cast<double>((1.0L - std::cos(a)) / a2),
            static_cast<double>((a - std::sin(a)) / (a2 * a))};
  }
  long double c1 = 0.0L, c2 = 0.0L, power = 1.0L, factorial = 2.0L;  // (2k+2)!
  for (int k = 0; k < 20; ++k) {
    c1 += power / factorial;
    c2 += power / (factorial * (2 * k + 3));
    power *= -a2;
    factorial *= (2 * k + 3) * (2 * k + 4);
  }
  return {static_cast<double>(c1), static_cast<double>(c2)};
}

TEST(Quaternion, JacobianCoefficientsMatchTheReferenceOnBothSidesOfTheSeriesLimit) {
  for (double angle : AnglesAround(std::sqrt(kBondSeriesAngle2))) {
    const LeftJacobianCoefficients c = LeftJacobianCoefficientsAt(angle * angle);
    const LeftJacobianCoefficients r = ReferenceCoefficients(angle);
    // The closed forms lose digits to cancellation (1 - cos a) as a falls to the limit.
    const double tolerance = angle < std::sqrt(kBondSeriesAngle2) ? 2e-16 : 5e-14;
    EXPECT_NEAR(c.c1, r.c1, tolerance * r.c1) << "angle " << angle;
    EXPECT_NEAR(c.c2, r.c2, tolerance * r.c2) << "angle " << angle;
  }
}

TEST(Quaternion, InverseLeftJacobianInvertsTheLeftJacobianOnBothSidesOfTheSeriesLimit) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> gauss;
  for (double angle : AnglesAround(std::sqrt(kBondSeriesAngle2))) {
    const Vec3 phi = angle * Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
    const Mat3 product = InverseLeftJacobian(phi) * LeftJacobian(phi);
    EXPECT_LT((product - Mat3::Identity()).cwiseAbs().maxCoeff(), 1e-14) << "angle " << angle;
    // The vector forms apply the transposes of the same matrices.
    const Vec3 v(gauss(rng), gauss(rng), gauss(rng));
    const double a2 = phi.squaredNorm();
    EXPECT_LT((LeftJacobianTransposeTimes(phi, LeftJacobianCoefficientsAt(a2), v) -
               LeftJacobian(phi).transpose() * v)
                  .norm(),
              1e-15 * v.norm());
    EXPECT_LT((InverseLeftJacobianTransposeTimes(phi, InverseLeftJacobianCoefficientAt(a2), v) -
               InverseLeftJacobian(phi).transpose() * v)
                  .norm(),
              1e-15 * v.norm());
  }
}

TEST(Quaternion, TheCombinedJacobianOperatorEqualsItsTwoFactorsAppliedInTurn) {
  std::mt19937_64 rng(13);
  std::normal_distribution<double> gauss;
  for (double angle : AnglesAround(std::sqrt(kBondSeriesAngle2))) {
    const Vec3 phi = angle * Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
    const Vec3 v(gauss(rng), gauss(rng), gauss(rng));
    const double a2 = phi.squaredNorm();
    const double c = InverseLeftJacobianCoefficientAt(a2);
    const LeftJacobianCoefficients half = LeftJacobianCoefficientsAt(0.25 * a2);
    const Vec3 in_turn =
        InverseLeftJacobianTransposeTimes(phi, c, LeftJacobianTransposeTimes(0.5 * phi, half, v));
    const Vec3 combined = InverseTimesHalfLeftJacobianTransposeTimes(phi, a2, c, half, v);
    EXPECT_LT((combined - in_turn).norm(), 1e-15 * v.norm()) << "angle " << angle;
  }
}

}  // namespace
}  // namespace fibrenet
