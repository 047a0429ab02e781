// EvaluateContactLanes against EvaluateContact, bit for bit, over every branch of the law:
// apart, the power law, the hard core, stick and slip, empty and held histories, with and
// without damping and friction.
#include "engine/interactions/contact_lanes.h"

#include <gtest/gtest.h>

#include <random>

namespace fibrenet {
namespace {

constexpr double kDt = 2e-9;

struct Pair {
  ContactGeometry g;
  Vec3 xi;
};

Vec3 RandomVector(std::mt19937& rng, double scale) {
  std::normal_distribution<double> n(0.0, 1.0);
  return scale * Vec3(n(rng), n(rng), n(rng));
}

// A pair at centre distance ratio x (R_i + R_j): from deep in the hard core (ratio below 0.5)
// to apart (above 1), moving and spinning, with a history from none to one that slips.
Pair RandomPair(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double r_i = 10e-6 + 10e-6 * u(rng), r_j = 10e-6 + 10e-6 * u(rng);
  const double ratio = 0.3 + 0.75 * u(rng);
  const double dist = ratio * (r_i + r_j);
  Pair pair;
  pair.g = ContactGeometry{dist * RandomVector(rng, 1.0).normalized(),
                           dist,
                           r_i,
                           r_j,
                           1e-12 * (0.5 + u(rng)),
                           RandomVector(rng, 0.1),
                           RandomVector(rng, 1e4),
                           RandomVector(rng, 1e4)};
  const double history = u(rng);
  pair.xi = history < 0.2 ? Vec3::Zero() : RandomVector(rng, std::pow(10.0, -9.0 + 4.0 * history));
  return pair;
}

void ExpectSame(const Vec3& lanes, const Vec3& scalar, const char* what, int lane) {
  for (int c = 0; c < 3; ++c) ASSERT_EQ(lanes[c], scalar[c]) << what << " lane " << lane;
}

void CompareGroups(const ContactParams& params, bool friction, int groups, int& slipped) {
  std::mt19937 rng(21);
  for (int group = 0; group < groups; ++group) {
    Pair pairs[kLanes];
    for (Pair& p : pairs) p = RandomPair(rng);
    ContactGeometry g[kLanes];
    Vec3 xi[kLanes];
    for (int l = 0; l < kLanes; ++l) g[l] = pairs[l].g, xi[l] = pairs[l].xi;
    ContactLanesInput in;
    SetContactLanes(g, xi, in);
    ContactLanesResult lanes;
    EvaluateContactLanes(in, params, kDt, friction, lanes);
    for (int l = 0; l < kLanes; ++l) {
      Vec3 history = pairs[l].xi;
      const ContactResult r = EvaluateContact(pairs[l].g, params, history, kDt, friction);
      const auto lane = [l](const Vec3Lanes& v) { return Vec3(v.x[l], v.y[l], v.z[l]); };
      ExpectSame(lane(lanes.force_j), r.force_j, "force", l);
      ExpectSame(lane(lanes.torque_i), r.torque_i, "torque_i", l);
      ExpectSame(lane(lanes.torque_j), r.torque_j, "torque_j", l);
      ExpectSame(lane(lanes.xi), history, "history", l);
      ASSERT_EQ(lanes.damping_power[l], r.damping_power) << "lane " << l;
      ASSERT_EQ(lanes.slip_loss[l], r.slip_loss) << "lane " << l;
      if (r.slip_loss != 0.0) ++slipped;
    }
  }
}

TEST(ContactLanes, EachLaneEqualsEvaluateContactBitForBit) {
  ContactParams params;
  params.restitution = 0.5;
  params.normal.hard_stiffness = 500.0;
  params.Derive();
  int slipped = 0;
  CompareGroups(params, true, 2000, slipped);
  // The random histories reach both sides of the Coulomb cap.
  EXPECT_GT(slipped, 500);
  EXPECT_LT(slipped, 7000);
}

TEST(ContactLanes, WithoutDampingFrictionOrHardCoreToo) {
  ContactParams params;  // restitution 1: no damping; no hard core
  params.Derive();
  ASSERT_EQ(params.zeta, 0.0);
  int slipped = 0;
  CompareGroups(params, false, 500, slipped);
  EXPECT_EQ(slipped, 0);
  params.mu = 0.0;
  CompareGroups(params, true, 500, slipped);
  EXPECT_EQ(slipped, 0);
}

}  // namespace
}  // namespace fibrenet
