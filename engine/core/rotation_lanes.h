// The integrator's orientation update of four particles side by side, one per lane:
//   q <- (QuatFromRotationVector(omega dt) * q).normalized(),
// with the same operations in the same order as that scalar line, so each lane's orientation
// equals it bit for bit.
//
// Why: the update is a chain of dependent operations (the rotation's series with its two
// divisions, the product, the norm's square root and four divisions), and it was 57% of the
// integrator's samples in the pressing. The scalar product also went through memory, stored
// in halves and read back whole, which stalls on the store forwarding.
//
// The lanes take the common case only, and say per lane when the particle needs the scalar
// line: its step's rotation must lie in QuatFromRotationVector's series (kSmallRotation2),
// and the product's squared norm must be positive (Eigen leaves a zero quaternion as it is).
#pragma once

#include "engine/core/lanes.h"
#include "engine/core/quaternion.h"

namespace fibrenet {

struct RotationLanesResult {
  QuatLanes q;     // the new orientations
  unsigned holds;  // bit l: lane l's q is the scalar line's; otherwise the caller runs that
};

inline RotationLanesResult RotateLanes(const QuatLanes& q, const Vec3Lanes& omega, double dt) {
  using namespace lanes;
  const Vec3Lanes phi = Scale(Splat(dt), omega);
  const Lanes angle2 = Dot(phi, phi);
  // QuatFromRotationVector's series, term for term.
  const Lanes h2 = 0.25 * angle2;
  const Lanes c = 1.0 - h2 * (0.5 - h2 / 24.0);
  const Lanes s = 0.5 * (1.0 - h2 * (1.0 / 6.0 - h2 / 120.0));
  const QuatLanes step{c, s * phi.x, s * phi.y, s * phi.z};
  const QuatLanes turned = Product(step, q);
  // Eigen's squared norm of the coefficients (x, y, z, w) adds them in two halves:
  // (x^2 + z^2) + (y^2 + w^2); normalized() divides each by the square root.
  const Lanes norm2 = (turned.x * turned.x + turned.z * turned.z) +
                      (turned.y * turned.y + turned.w * turned.w);
  const Lanes norm = Sqrt(norm2);
  RotationLanesResult r;
  r.q = {turned.w / norm, turned.x / norm, turned.y / norm, turned.z / norm};
  r.holds = 0;
  for (int l = 0; l < kLanes; ++l)
    if (angle2[l] < kSmallRotation2 && norm2[l] > 0.0) r.holds |= 1u << l;
  return r;
}

}  // namespace fibrenet
