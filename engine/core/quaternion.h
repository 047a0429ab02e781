// Rotation helpers on unit quaternions used by the integrator and the bond kinematics.
#pragma once

#include <cmath>

#include "engine/core/types.h"

namespace fibrenet {

// Below this squared angle [rad^2] the rotation-vector and Jacobian helpers use Taylor series
// (0.2 rad): a bond's relative rotation almost always lies below it, and the series, exact to
// rounding there, spare the square root, atan2, sin and cos of the closed forms.
inline constexpr double kBondSeriesAngle2 = 0.04;
// Below this one (0.032 rad), where nearly every bond of a loaded sheet lies, shorter series
// of the same functions are already exact to rounding: they cut the chain of dependent
// multiplications that each bond evaluation waits on.
inline constexpr double kShortSeriesAngle2 = 1e-3;

// The short series, written once for any arithmetic type T (double here; the bond lanes of
// beam_bond_lanes.h evaluate the very same polynomials on four values at a time).
// atan(t) / t at t2 = t^2 < kShortSeriesAngle2 / 4.
template <class T>
inline T AtanOverTShortSeries(T t2) {
  return 1.0 - t2 * (1.0 / 3.0 - t2 * (1.0 / 5.0 - t2 * (1.0 / 7.0 - t2 / 9.0)));
}
// c1, c2 and c of the SO(3) Jacobians below, at a2 < kShortSeriesAngle2.
template <class T>
inline T LeftJacobianC1ShortSeries(T a2) {
  return 0.5 - a2 * (1.0 / 24.0 - a2 * (1.0 / 720.0 - a2 / 40320.0));
}
template <class T>
inline T LeftJacobianC2ShortSeries(T a2) {
  return 1.0 / 6.0 - a2 * (1.0 / 120.0 - a2 * (1.0 / 5040.0 - a2 / 362880.0));
}
template <class T>
inline T InverseLeftJacobianShortSeries(T a2) {
  return 1.0 / 12.0 + a2 * (1.0 / 720.0 + a2 * (1.0 / 30240.0 + a2 / 1209600.0));
}

// The factor that takes the vector part v of a unit quaternion with w >= 0 (s2 = |v|^2) to
// its rotation vector: theta = v * RotationVectorScale(s2, w). Scalar on its own so that the
// bond lanes (beam_bond_lanes.h) apply the very same branches to one lane.
inline double RotationVectorScale(double s2, double w) {
  // angle = 2 atan(t), t = |v| / w, t^2 about angle^2 / 4. Below t = 0.1 (0.2 rad) the series
  // of atan(t) / t to t^14 is exact to rounding: the first term left out, t^16 / 17, is below
  // 6e-18; below t^2 = kShortSeriesAngle2 / 4 the series to t^8 is (t^10 / 11 < 1e-19).
  if (s2 < 0.25 * kBondSeriesAngle2 * w * w) {
    const double inv_w = 1.0 / w;
    const double t2 = s2 * inv_w * inv_w;
    const double atan_t_over_t =
        t2 < 0.25 * kShortSeriesAngle2
            ? AtanOverTShortSeries(t2)
            : 1.0 - t2 * (1.0 / 3.0 -
                          t2 * (1.0 / 5.0 -
                                t2 * (1.0 / 7.0 -
                                      t2 * (1.0 / 9.0 -
                                            t2 * (1.0 / 11.0 -
                                                  t2 * (1.0 / 13.0 - t2 / 15.0))))));
    return (2.0 * inv_w) * atan_t_over_t;
  }
  const double s = std::sqrt(s2);
  return 2.0 * std::atan2(s, w) / s;
}

// Rotation vector (axis * angle, radians) of a unit quaternion, angle in [0, pi].
inline Vec3 RotationVector(const Quat& q) {
  // Take the shorter way round: q and -q are the same rotation.
  const double sign = q.w() < 0.0 ? -1.0 : 1.0;
  const Vec3 v = sign * q.vec();
  const double w = sign * q.w();
  return v * RotationVectorScale(v.squaredNorm(), w);
}

// Below this squared rotation angle [rad^2] QuatFromRotationVector uses its series.
inline constexpr double kSmallRotation2 = 1e-4;

// Unit quaternion of a rotation vector (axis * angle).
inline Quat QuatFromRotationVector(const Vec3& phi) {
  const double angle2 = phi.squaredNorm();
  // A step's rotation is tiny (omega dt << 1): the Taylor series of cos(h) and sin(h) / (2h),
  // h = angle / 2, to h^4 is exact to rounding below 0.01 rad (the first term left out is
  // below 3e-17) and costs neither a square root nor sin and cos.
  if (angle2 < kSmallRotation2) {
    const double h2 = 0.25 * angle2;
    const double c = 1.0 - h2 * (0.5 - h2 / 24.0);
    const double s = 0.5 * (1.0 - h2 * (1.0 / 6.0 - h2 / 120.0));
    return Quat(c, s * phi.x(), s * phi.y(), s * phi.z());
  }
  const double angle = std::sqrt(angle2);
  const double h = 0.5 * angle;
  const Vec3 axis = phi / angle;
  const double s = std::sin(h);
  return Quat(std::cos(h), s * axis.x(), s * axis.y(), s * axis.z());
}

// Half of the rotation q (the rotation that applied twice gives q), taking the short way.
inline Quat HalfRotation(const Quat& q) {
  const double sign = q.w() < 0.0 ? -1.0 : 1.0;
  Quat h(1.0 + sign * q.w(), sign * q.x(), sign * q.y(), sign * q.z());
  // |h|^2 = (1 + |w|)^2 + |v|^2 = 2 (1 + |w|) for a unit q: one square root and one division.
  const double n2 = 2.0 * h.w();
  if (n2 < 1e-24) return Quat(0.0, 1.0, 0.0, 0.0);  // a half turn: any perpendicular axis
  h.coeffs() *= 1.0 / std::sqrt(n2);
  return h;
}

// A rotation taking the x axis onto the unit vector `axis`, with no twist about it. Defined
// in quaternion.cpp: Eigen's FromTwoVectors brings in its SVD, whose templates cost every
// file that includes this header ten seconds of compile time.
Quat FrameAlongAxis(const Vec3& axis);

// Left Jacobian of SO(3) at the rotation vector phi: exp(phi + delta) = exp(J_l(phi) delta)
// exp(phi) to first order in delta. Its inverse maps a small world-side rotation gamma onto
// the change of the rotation vector: log(exp(gamma) exp(phi)) = phi + J_l^-1(phi) gamma.
// With K the cross-product matrix of phi (K v = phi x v) and a = |phi|:
//   J_l = I + c1 K + c2 K^2,  c1 = (1 - cos a) / a^2,  c2 = (a - sin a) / a^3;
//   J_l^-1 = I - K / 2 + c K^2,  c = 1 / a^2 - cot(a / 2) / (2 a).
struct LeftJacobianCoefficients {
  double c1, c2;
};

// c1 and c2 at a2 = |phi|^2. Below kBondSeriesAngle2 their series to a^10 are exact to
// rounding (the terms left out are below 1e-19), where the closed forms lose digits; below
// kShortSeriesAngle2 so are the series to a^6 (the terms left out below 2e-18 relative).
inline LeftJacobianCoefficients LeftJacobianCoefficientsAt(double a2) {
  if (a2 < kShortSeriesAngle2)
    return {LeftJacobianC1ShortSeries(a2), LeftJacobianC2ShortSeries(a2)};
  if (a2 < kBondSeriesAngle2) {
    return {0.5 - a2 * (1.0 / 24.0 -
                        a2 * (1.0 / 720.0 -
                              a2 * (1.0 / 40320.0 - a2 * (1.0 / 3628800.0 - a2 / 479001600.0)))),
            1.0 / 6.0 - a2 * (1.0 / 120.0 -
                              a2 * (1.0 / 5040.0 -
                                    a2 * (1.0 / 362880.0 -
                                          a2 * (1.0 / 39916800.0 - a2 / 6227020800.0))))};
  }
  const double a = std::sqrt(a2);
  return {(1.0 - std::cos(a)) / a2, (a - std::sin(a)) / (a2 * a)};
}

// c at a2 = |phi|^2; below kBondSeriesAngle2 its series to a^10 (the next term is below 1e-19),
// below kShortSeriesAngle2 its series to a^6 (the next term below 3e-18 relative).
inline double InverseLeftJacobianCoefficientAt(double a2) {
  if (a2 < kShortSeriesAngle2) return InverseLeftJacobianShortSeries(a2);
  if (a2 < kBondSeriesAngle2) {
    return 1.0 / 12.0 +
           a2 * (1.0 / 720.0 +
                 a2 * (1.0 / 30240.0 +
                       a2 * (1.0 / 1209600.0 + a2 * (1.0 / 47900160.0 +
                                                     a2 * (691.0 / 1307674368000.0)))));
  }
  const double a = std::sqrt(a2);
  return 1.0 / a2 - std::cos(0.5 * a) / (2.0 * a * std::sin(0.5 * a));
}

inline Mat3 CrossProductMatrix(const Vec3& phi) {
  Mat3 K;
  K << 0.0, -phi.z(), phi.y(), phi.z(), 0.0, -phi.x(), -phi.y(), phi.x(), 0.0;
  return K;
}

inline Mat3 LeftJacobian(const Vec3& phi) {
  const Mat3 K = CrossProductMatrix(phi);
  const LeftJacobianCoefficients c = LeftJacobianCoefficientsAt(phi.squaredNorm());
  return Mat3::Identity() + c.c1 * K + c.c2 * K * K;
}

inline Mat3 InverseLeftJacobian(const Vec3& phi) {
  const Mat3 K = CrossProductMatrix(phi);
  return Mat3::Identity() - 0.5 * K + InverseLeftJacobianCoefficientAt(phi.squaredNorm()) * K * K;
}

// The same Jacobians applied transposed to a vector, without forming a matrix: K^T = -K and
// (K K)^T = K K, so
//   J_l^T v = v - c1 phi x v + c2 phi x (phi x v),  J_l^-T v = v + phi x v / 2 + c phi x (phi x v).
// The coefficients come from the functions above, so that a caller applying one Jacobian
// twice computes them once. The bond applies J_l^-T, and the product of both through the
// operator below; J_l^T alone is what that operator is checked against.
inline Vec3 LeftJacobianTransposeTimes(const Vec3& phi, const LeftJacobianCoefficients& c,
                                       const Vec3& v) {
  const Vec3 pv = phi.cross(v);
  return v - c.c1 * pv + c.c2 * phi.cross(pv);
}

inline Vec3 InverseLeftJacobianTransposeTimes(const Vec3& phi, double c, const Vec3& v) {
  const Vec3 pv = phi.cross(v);
  return v + 0.5 * pv + c * phi.cross(pv);
}

// alpha and beta of the operator below, for any arithmetic type T (as the series above).
template <class T>
inline T InverseTimesHalfAlpha(T a2, T c_inverse, T half_c1, T half_c2) {
  return 0.5 - 0.5 * half_c1 - a2 * (0.125 * half_c2 - 0.5 * c_inverse * half_c1);
}
template <class T>
inline T InverseTimesHalfBeta(T a2, T c_inverse, T half_c1, T half_c2) {
  return c_inverse + 0.25 * (half_c2 - half_c1) - 0.25 * a2 * c_inverse * half_c2;
}

// J_l^-T(phi) J_l^T(phi / 2) v as one operator (a bond shares its force couple through it):
// both factors are polynomials in the cross-product matrix K of phi, and K^3 = -a^2 K, so the
// product is I + alpha K + beta K^2. c_inverse is InverseLeftJacobianCoefficientAt(a2) and
// half the coefficients LeftJacobianCoefficientsAt(a2 / 4).
inline Vec3 InverseTimesHalfLeftJacobianTransposeTimes(const Vec3& phi, double a2, double c_inverse,
                                                       const LeftJacobianCoefficients& half,
                                                       const Vec3& v) {
  const double alpha = InverseTimesHalfAlpha(a2, c_inverse, half.c1, half.c2);
  const double beta = InverseTimesHalfBeta(a2, c_inverse, half.c1, half.c2);
  const Vec3 pv = phi.cross(v);
  return v + alpha * pv + beta * phi.cross(pv);
}

}  // namespace fibrenet
