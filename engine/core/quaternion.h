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
  const double angle = 2.0 * std::atan2(s, sign * q.w());
  return v * (angle / s);
}

// Unit quaternion of a rotation vector (axis * angle).
inline Quat QuatFromRotationVector(const Vec3& phi) {
  const double angle = phi.norm();
  if (angle < 1e-12) {
    Quat q(1.0, 0.5 * phi.x(), 0.5 * phi.y(), 0.5 * phi.z());
    return q.normalized();
  }
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

}  // namespace fibrenet
