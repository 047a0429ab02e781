// RotateLanes against the integrator's scalar line, bit for bit, and the lanes it leaves to it.
#include "engine/core/rotation_lanes.h"

#include <gtest/gtest.h>

#include <random>

namespace fibrenet {
namespace {

Quat RandomOrientation(std::mt19937& rng) {
  std::normal_distribution<double> gauss;
  return Quat(gauss(rng), gauss(rng), gauss(rng), gauss(rng)).normalized();
}

Vec3 RandomSpin(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return scale * Vec3(u(rng), u(rng), u(rng));
}

Quat ScalarLine(const Quat& q, const Vec3& omega, double dt) {
  return (QuatFromRotationVector(omega * dt) * q).normalized();
}

// Runs four particles through the lanes; returns the holds mask and each lane's quaternion.
unsigned RunLanes(const Quat (&q)[kLanes], const Vec3 (&omega)[kLanes], double dt,
                  Quat (&out)[kLanes]) {
  QuatLanes q_lanes;
  Vec3Lanes omega_lanes;
  GatherQuatLanes({&q[0], &q[1], &q[2], &q[3]}, q_lanes);
  GatherVec3Lanes(omega, omega_lanes);
  const RotationLanesResult r = RotateLanes(q_lanes, omega_lanes, dt);
  for (int l = 0; l < kLanes; ++l) out[l] = Quat(r.q.w[l], r.q.x[l], r.q.y[l], r.q.z[l]);
  return r.holds;
}

TEST(RotationLanes, EachLaneEqualsTheScalarUpdateBitForBit) {
  std::mt19937 rng(11);
  constexpr double kDt = 1e-8;
  int compared = 0;
  // Step rotations from 1e-10 rad up to the series limit (0.01 rad), orientations anywhere.
  for (double spin : {1e-2, 1e1, 1e3, 1e5, 9.9e5}) {
    for (int group = 0; group < 500; ++group) {
      Quat q[kLanes], out[kLanes];
      Vec3 omega[kLanes];
      for (int l = 0; l < kLanes; ++l) {
        q[l] = RandomOrientation(rng);
        omega[l] = RandomSpin(rng, spin / std::sqrt(3.0));
      }
      const unsigned holds = RunLanes(q, omega, kDt, out);
      ASSERT_EQ(holds, (1u << kLanes) - 1) << "spin " << spin;
      for (int l = 0; l < kLanes; ++l) {
        const Quat expected = ScalarLine(q[l], omega[l], kDt);
        ASSERT_EQ(out[l].w(), expected.w()) << "spin " << spin << " lane " << l;
        ASSERT_EQ(out[l].x(), expected.x()) << "spin " << spin << " lane " << l;
        ASSERT_EQ(out[l].y(), expected.y()) << "spin " << spin << " lane " << l;
        ASSERT_EQ(out[l].z(), expected.z()) << "spin " << spin << " lane " << l;
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, 5 * 500 * kLanes);
}

TEST(RotationLanes, LeavesRotationsBeyondTheSeriesAndZeroQuaternionsToTheScalarLine) {
  std::mt19937 rng(12);
  Quat q[kLanes] = {RandomOrientation(rng), RandomOrientation(rng), Quat(0.0, 0.0, 0.0, 0.0),
                    RandomOrientation(rng)};
  const double limit = std::sqrt(kSmallRotation2);
  const double dt = 1e-8;
  // Lane 1 turns by 1.01 times the series limit in the step, lane 3 by 0.99 times it.
  Vec3 omega[kLanes] = {Vec3(1e3, 0.0, 0.0), Vec3(0.0, 1.01 * limit / dt, 0.0),
                        Vec3(0.0, 0.0, 1e3), Vec3(0.0, 0.0, 0.99 * limit / dt)};
  Quat out[kLanes];
  EXPECT_EQ(RunLanes(q, omega, dt, out), 0b1001u);
  EXPECT_EQ(out[3].coeffs(), ScalarLine(q[3], omega[3], dt).coeffs());
}

}  // namespace
}  // namespace fibrenet
