#include "engine/interactions/beam_bond_lanes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "engine/core/force_buffers.h"
#include "engine/core/forces.h"
#include "engine/core/parallel.h"
#include "engine/core/quaternion.h"
#include "engine/core/world.h"

namespace fibrenet {
namespace {

constexpr double kR = 16e-6, kL = 32e-6, kE = 10e9, kG = 3e9, kMass = 1e-10, kDt = 1e-9;

Quat RandomRotation(std::mt19937& rng, double max_angle) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Vec3 axis(u(rng), u(rng), u(rng));
  return QuatFromRotationVector(axis.normalized() * max_angle * std::abs(u(rng)));
}

Vec3 RandomVector(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return scale * Vec3(u(rng), u(rng), u(rng));
}

// A bond made at rest along a random direction, then strained by `strain` (relative
// displacement and rotations of that order) and set moving, with damping factors of its own.
struct Case {
  BondGeometry g;
  BondState s;
  BondDampingFactors damping;
};

Case RandomCase(std::mt19937& rng, double strain) {
  Case c;
  const Quat q_i0 = RandomRotation(rng, 3.0), q_j0 = RandomRotation(rng, 3.0);
  const Vec3 d0 = kL * RandomVector(rng, 1.0).normalized();
  c.s = MakeBondState(d0, q_i0, q_j0);
  c.s.dashpot = 1e-3 * strain * kL;
  // The bond's own damping factors (a pair lighter or heavier than its type's).
  std::uniform_real_distribution<float> factor(0.3f, 3.0f);
  c.damping = {factor(rng), factor(rng)};
  c.g.d = d0 + RandomVector(rng, strain * kL);
  c.g.q_i = RandomRotation(rng, strain) * q_i0;
  c.g.q_j = RandomRotation(rng, strain) * q_j0;
  c.g.v_rel = RandomVector(rng, 1e-2);
  c.g.omega_i = RandomVector(rng, 1e3);
  c.g.omega_j = RandomVector(rng, 1e3);
  return c;
}

void Gather(const std::vector<Case>& cases, const std::vector<BeamBondParams>& params,
            BondLanesInput& in) {
  in.damped = in.viscous = false;
  for (int l = 0; l < kBondLanes; ++l)
    SetLane(in, l, cases[l].g, cases[l].s, LanesTypeOf(params[l], kDt), cases[l].damping);
}

BeamBondParams Elastic() { return BeamBondParams::FromBeam(kE, kG, kR, kL); }

BeamBondParams HillDamped() {
  BeamBondParams p = Elastic();
  p.failure = BondFailure::kHill;
  p.F_r0 = p.F_s0 = 10.0;
  p.HillDefaults();
  p.damping_n = p.damping_s = 1e-6;
  p.damping_rot = 1e-15;
  return p;
}

BeamBondParams Viscous() {
  BeamBondParams p = HillDamped();
  p.maxwell_tau = 3e-8;
  return p;
}

// Every lane equals EvaluateBond on its bond bit for bit (forces, torques, dissipation, mode
// loads, the dashpot's new extension), at relative rotations in the short series, in the
// long one and beyond both (closed forms), and in groups that mix them. Lanes mix elastic,
// damped and viscous types, so a damped or viscous group carries lanes without damping or
// dashpot too.
TEST(BeamBondLanes, EachLaneEqualsEvaluateBondBitForBit) {
  std::mt19937 rng(11);
  int short_series = 0, long_series = 0, closed_form = 0;
  for (double strain : {0.0, 1e-7, 1e-5, 1e-3, 3e-3, 0.01, 0.02, 0.05, 0.1, 0.3}) {
    for (int group = 0; group < 50; ++group) {
      std::vector<Case> cases;
      std::vector<BeamBondParams> params;
      for (int l = 0; l < kBondLanes; ++l) {
        // One group in five mixes a small strain into a large one's lanes.
        cases.push_back(RandomCase(rng, group % 5 == 0 && l % 2 == 0 ? 1e-4 : strain));
        params.push_back((group + l) % 3 == 0   ? Elastic()
                         : (group + l) % 3 == 1 ? HillDamped()
                                                : Viscous());
      }
      BondLanesInput in;
      Gather(cases, params, in);
      BondLanesResult lanes;
      EvaluateBondLanes(in, kDt, lanes);
      for (int l = 0; l < kBondLanes; ++l) {
        BondState copy = cases[l].s;
        const BondResult r = EvaluateBond(cases[l].g, params[l], copy, kDt, cases[l].damping);
        const double theta2 = RotationVector((cases[l].g.q_i * cases[l].s.b_i).conjugate() *
                                             (cases[l].g.q_j * cases[l].s.b_j))
                                  .squaredNorm();
        ++(theta2 < kShortSeriesAngle2  ? short_series
           : theta2 < kBondSeriesAngle2 ? long_series
                                        : closed_form);
        EXPECT_EQ(lanes.force_i.x[l], r.force_i.x()) << "strain " << strain << " lane " << l;
        EXPECT_EQ(lanes.force_i.y[l], r.force_i.y());
        EXPECT_EQ(lanes.force_i.z[l], r.force_i.z());
        EXPECT_EQ(lanes.torque_i.x[l], r.torque_i.x());
        EXPECT_EQ(lanes.torque_i.y[l], r.torque_i.y());
        EXPECT_EQ(lanes.torque_i.z[l], r.torque_i.z());
        EXPECT_EQ(lanes.torque_j.x[l], r.torque_j.x());
        EXPECT_EQ(lanes.torque_j.y[l], r.torque_j.y());
        EXPECT_EQ(lanes.torque_j.z[l], r.torque_j.z());
        EXPECT_EQ(lanes.dissipated[l], r.dissipated);
        EXPECT_EQ(lanes.dashpot[l], copy.dashpot);
        EXPECT_EQ(lanes.f_r[l], r.f_r);
        EXPECT_EQ(lanes.f_s[l], r.f_s);
        EXPECT_EQ(lanes.tau_b[l], r.tau_b);
        EXPECT_EQ(lanes.tau_t[l], r.tau_t);
      }
    }
  }
  EXPECT_GT(short_series, 1000);
  EXPECT_GT(long_series, 100);
  EXPECT_GT(closed_form, 100);
}

// Types whose bonds break at strains of about 1e-3 (forces of about 10 mN).
BeamBondParams WeakHill() {
  BeamBondParams p = HillDamped();
  p.F_r0 = p.F_s0 = 1e-2;
  p.HillDefaults();
  return p;
}

BeamBondParams WeakModes() {
  BeamBondParams p = Elastic();
  p.failure = BondFailure::kModeThresholds;
  p.max_tension = p.max_shear = 5e-3;
  p.max_bending = p.max_twist = 5e-9;
  return p;
}

// The lanes' failure estimate lies within 1e-14 of FailureIndex, and where the lanes say a
// bond holds, FailureIndex says so too.
TEST(BeamBondLanes, FailureEstimateAgreesWithTheFailureIndex) {
  std::mt19937 rng(3);
  int held = 0, handed_over = 0;
  for (int group = 0; group < 400; ++group) {
    std::vector<Case> cases;
    std::vector<BeamBondParams> params;
    for (int l = 0; l < kBondLanes; ++l) {
      cases.push_back(RandomCase(rng, 2e-3));
      params.push_back((group + l) % 2 == 0 ? WeakHill() : WeakModes());
    }
    BondLanesInput in;
    Gather(cases, params, in);
    BondLanesResult lanes;
    EvaluateBondLanes(in, kDt, lanes);
    for (int l = 0; l < kBondLanes; ++l) {
      const double index =
          FailureIndex(params[l], lanes.f_r[l], lanes.f_s[l], lanes.tau_b[l], lanes.tau_t[l]);
      EXPECT_NEAR(lanes.failure_estimate[l], index, 1e-14 * index);
      if (LaneHolds(lanes, l)) {
        EXPECT_LT(index, 1.0);
        ++held;
      } else {
        ++handed_over;
      }
    }
  }
  EXPECT_GT(held, 100);
  EXPECT_GT(handed_over, 100);
}

TEST(BeamBondLanes, TakeEveryTypeWithoutPlasticYield) {
  EXPECT_TRUE(LanesTakeType(Elastic()));
  EXPECT_TRUE(LanesTakeType(HillDamped()));
  EXPECT_TRUE(LanesTakeType(Viscous()));
  BeamBondParams plastic = Elastic();
  plastic.yield_moment = 1e-9;
  EXPECT_FALSE(LanesTakeType(plastic));
}

// The bond loop, which sends groups of four through the lanes, gives every particle the
// forces and torques of EvaluateBond applied bond by bond in order, bit for bit, with bonds
// of types the lanes do not take, broken bonds, bonds beyond the short series and bonds
// that break in this step, or nearly do, among them.
TEST(BeamBondLanes, TheBondLoopEqualsEvaluateBondInOrder) {
  const int saved_threads = ThreadCount();
  SetThreadCount(1);
  std::mt19937 rng(5);
  World w;
  w.cell.lo = Vec3(-1.0, -1.0, -1.0);
  w.cell.hi = Vec3(1.0, 1.0, 1.0);
  BeamBondParams plastic = HillDamped();
  plastic.yield_moment = 1e-9;
  BeamBondParams weak = HillDamped();
  weak.F_r0 = weak.F_s0 = 1e-6;  // breaks at once
  weak.HillDefaults();
  const std::int32_t types[7] = {w.bonds.AddType(Elastic()),  w.bonds.AddType(HillDamped()),
                                 w.bonds.AddType(WeakHill()), w.bonds.AddType(WeakModes()),
                                 w.bonds.AddType(Viscous()),  w.bonds.AddType(plastic),
                                 w.bonds.AddType(weak)};
  constexpr int kBonds = 203;
  for (int b = 0; b < kBonds; ++b) {
    const double strain = b % 17 == 0 ? 0.05 : 1e-3;
    const Case c = RandomCase(rng, strain);
    const Vec3 x_i = RandomVector(rng, 1e-3);
    // Some bonds point back to an earlier particle: the loop writes in both directions.
    const bool backwards = b % 5 == 0;
    const std::size_t first = w.particles.size();
    w.particles.Add(Vec3::Zero(), kR, kMass, b);
    w.particles.Add(Vec3::Zero(), kR, kMass, b);
    const auto i = static_cast<std::int32_t>(first + (backwards ? 1 : 0));
    const auto j = static_cast<std::int32_t>(first + (backwards ? 0 : 1));
    w.particles.x[i] = x_i, w.particles.x[j] = x_i + c.g.d;
    w.particles.q[i] = c.g.q_i, w.particles.q[j] = c.g.q_j;
    w.particles.v[j] = c.g.v_rel;
    w.particles.omega[i] = c.g.omega_i, w.particles.omega[j] = c.g.omega_j;
    const std::int32_t type = b == 101      ? types[6]
                              : b % 13 == 0 ? types[5]
                              : b % 7 == 3  ? types[4]
                                            : types[b % 4];
    w.bonds.Add(i, j, type, BondKind::kFibreFibre, c.s);
    w.bonds.damping_factors.push_back(c.damping);
  }
  // Broken bonds alone and in a run: a group of four that holds one sends its live bonds
  // through EvaluateBond.
  for (int b : {7, 20, 21, 22, 150}) w.bonds.broken[b] = 1;
  w.settings.dt = kDt;

  World reference = w;
  for (std::size_t b = 0; b < reference.bonds.size(); ++b) {
    if (reference.bonds.broken[b]) continue;
    Particles& p = reference.particles;
    const std::int32_t i = reference.bonds.i[b], j = reference.bonds.j[b];
    const BondGeometry g{reference.cell.Delta(p.x[i], p.x[j]),
                         p.q[i],
                         p.q[j],
                         p.v[j] - p.v[i],
                         p.omega[i],
                         p.omega[j]};
    const BondResult r =
        EvaluateBond(g, reference.bonds.types[reference.bonds.type[b]], reference.bonds.state[b],
                     w.settings.dt, reference.bonds.DampingFactors(b));
    if (r.broken) {
      reference.bonds.broken[b] = 1;
      continue;
    }
    p.force[i] += r.force_i;
    p.torque[i] += r.torque_i;
    p.force[j] -= r.force_i;
    p.torque[j] += r.torque_j;
  }

  ForceBuffers buffers;
  buffers.Prepare(w.particles, w.bonds);
  StepLosses losses;
  AccumulateBondForces(w, buffers, losses);
  buffers.Reduce();
  SetThreadCount(saved_threads);

  EXPECT_TRUE(losses.bonds_broke);
  EXPECT_EQ(w.bonds.broken, reference.bonds.broken);
  EXPECT_EQ(w.bonds.broken[101], 1);
  for (std::size_t k = 0; k < w.particles.size(); ++k) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(w.particles.force[k][c], reference.particles.force[k][c]) << "particle " << k;
      EXPECT_EQ(w.particles.torque[k][c], reference.particles.torque[k][c]) << "particle " << k;
    }
  }
  for (std::size_t b = 0; b < w.bonds.size(); ++b)
    EXPECT_EQ(w.bonds.state[b].dashpot, reference.bonds.state[b].dashpot) << "bond " << b;
}

}  // namespace
}  // namespace fibrenet
