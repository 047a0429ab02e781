// Rotation helpers on unit quaternions used by the integrator and the bond kinematics.
#pragma once

#include <cmath>

#include "engine/core/types.h"

namespace fibrenet {

// Rotation vector (axis * angle, radians) of a unit quaternion, angle in [0, pi].
inline Vec3 RotationVector(const Quat& q) {
  // Take the shorter way round: q and -q are the same rotation.
  const double sign = q.w() < 0.0 ? -1.0 : 1.0;
  const Vec3 v = sign * q.vec();
  const double s = v.norm();
  if (s < 1e-12) return 2.0 * v;  // small-angle limit, exact to O(angle^3)
  const double w = sign * q.w();
  if (s < 1e-3 * w) {
    // angle = 2 atan(t), t = s / w < 1e-3: the series to t^5 is exact to round-off (the next
    // term is t^7 / 7 < 1e-21 t) and spares the atan2 call, for bonds run once per step.
    const double t = s / w, t2 = t * t;
    return v * ((2.0 / w) * (1.0 - t2 * (1.0 / 3.0 - t2 * 0.2)));
  }
  const double angle = 2.0 * std::atan2(s, w);
  return v * (angle / s);
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
  const double n = h.norm();
  if (n < 1e-12) return Quat(0.0, 1.0, 0.0, 0.0);  // a half turn: any perpendicular axis
  h.coeffs() /= n;
  return h;
}

// A rotation taking the x axis onto the unit vector `axis`, with no twist about it.
inline Quat FrameAlongAxis(const Vec3& axis) {
  return Quat::FromTwoVectors(Vec3::UnitX(), axis);
}

// Left Jacobian of SO(3) at the rotation vector phi: exp(phi + delta) = exp(J_l(phi) delta)
// exp(phi) to first order in delta. Its inverse maps a small world-side rotation gamma onto
// the change of the rotation vector: log(exp(gamma) exp(phi)) = phi + J_l^-1(phi) gamma.
// Series below 1e-3 rad, where the closed forms lose digits.
inline Mat3 LeftJacobian(const Vec3& phi) {
  const double a = phi.norm(), a2 = a * a;
  Mat3 K;
  K << 0.0, -phi.z(), phi.y(), phi.z(), 0.0, -phi.x(), -phi.y(), phi.x(), 0.0;
  const double c1 = a < 1e-3 ? 0.5 - a2 / 24.0 : (1.0 - std::cos(a)) / a2;
  const double c2 = a < 1e-3 ? 1.0 / 6.0 - a2 / 120.0 : (a - std::sin(a)) / (a2 * a);
  return Mat3::Identity() + c1 * K + c2 * K * K;
}

inline Mat3 InverseLeftJacobian(const Vec3& phi) {
  const double a = phi.norm(), a2 = a * a;
  Mat3 K;
  K << 0.0, -phi.z(), phi.y(), phi.z(), 0.0, -phi.x(), -phi.y(), phi.x(), 0.0;
  const double c2 = a < 1e-3 ? 1.0 / 12.0 + a2 / 720.0
                             : 1.0 / a2 - std::cos(0.5 * a) / (2.0 * a * std::sin(0.5 * a));
  return Mat3::Identity() - 0.5 * K + c2 * K * K;
}

// The same Jacobians applied transposed to a vector, without forming a matrix (the bond's
// hot path): with K v = phi x v, K^T = -K and (K K)^T = K K, so
//   J_l^T v = v - c1 phi x v + c2 phi x (phi x v),  J_l^-T v = v + phi x v / 2 + c2' phi x (phi x v).
inline Vec3 LeftJacobianTransposeTimes(const Vec3& phi, const Vec3& v) {
  const double a = phi.norm(), a2 = a * a;
  const double c1 = a < 1e-3 ? 0.5 - a2 / 24.0 : (1.0 - std::cos(a)) / a2;
  const double c2 = a < 1e-3 ? 1.0 / 6.0 - a2 / 120.0 : (a - std::sin(a)) / (a2 * a);
  const Vec3 pv = phi.cross(v);
  return v - c1 * pv + c2 * phi.cross(pv);
}

inline Vec3 InverseLeftJacobianTransposeTimes(const Vec3& phi, const Vec3& v) {
  const double a = phi.norm(), a2 = a * a;
  const double c2 = a < 1e-3 ? 1.0 / 12.0 + a2 / 720.0
                             : 1.0 / a2 - std::cos(0.5 * a) / (2.0 * a * std::sin(0.5 * a));
  const Vec3 pv = phi.cross(v);
  return v + 0.5 * pv + c2 * phi.cross(pv);
}

}  // namespace fibrenet
