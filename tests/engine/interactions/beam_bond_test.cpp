#include "engine/interactions/beam_bond.h"

#include <random>

#include <gtest/gtest.h>

#include "engine/core/quaternion.h"

namespace fibrenet {
namespace {

constexpr double kR = 16e-6, kL = 32e-6, kE = 10e9, kG = 3e9;

BeamBondParams Fibre() { return BeamBondParams::FromBeam(kE, kG, kR, kL); }

Quat RandomRotation(std::mt19937& rng, double max_angle) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vec3 axis(u(rng), u(rng), u(rng));
  return QuatFromRotationVector(axis.normalized() * max_angle * std::abs(u(rng)));
}

// A pair in a deformed state: i at the origin, j near (L, 0, 0), both slightly rotated.
struct Pair {
  Vec3 x_i = Vec3::Zero(), x_j;
  Quat q_i = Quat::Identity(), q_j = Quat::Identity();
  BondState state;
};

Pair DeformedPair(std::mt19937& rng, double strain) {
  Pair p;
  p.x_j = Vec3(kL, 0, 0);
  p.state = MakeBondState(p.x_j - p.x_i, p.q_i, p.q_j);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  p.x_j += kL * strain * Vec3(u(rng), u(rng), u(rng));
  p.q_i = RandomRotation(rng, strain);
  p.q_j = RandomRotation(rng, strain);
  return p;
}

BondResult Evaluate(const Pair& p, const BeamBondParams& params) {
  BondState copy = p.state;
  return EvaluateBond({p.x_j - p.x_i, p.q_i, p.q_j, Vec3::Zero(), Vec3::Zero(), Vec3::Zero()},
                      params, copy, 0.0);
}

TEST(BeamBond, BeamTheoryStiffnessesUseCircularSection) {
  const BeamBondParams p = Fibre();
  const double A = kPi * kR * kR, I = kPi * std::pow(kR, 4) / 4.0;
  EXPECT_NEAR(p.k_n, kE * A / kL, 1e-9 * p.k_n);
  EXPECT_NEAR(p.k_s, 12.0 * kE * I / std::pow(kL, 3), 1e-9 * p.k_s);
  EXPECT_NEAR(p.k_b, kE * I / kL, 1e-9 * p.k_b);
  EXPECT_NEAR(p.k_t, kG * 2.0 * I / kL, 1e-9 * p.k_t);
}

TEST(BeamBond, RestStateHasNoForce) {
  std::mt19937 rng(1);
  Pair p = DeformedPair(rng, 0.0);
  const BondResult r = Evaluate(p, Fibre());
  EXPECT_LT(r.force_i.norm(), 1e-12);
  EXPECT_LT(r.torque_i.norm(), 1e-18);
}

TEST(BeamBond, LargeRigidRotationGivesNoForceOrChangeInEnergy) {
  std::mt19937 rng(2);
  for (int trial = 0; trial < 20; ++trial) {
    Pair p = DeformedPair(rng, 0.02);
    const BondResult before = Evaluate(p, Fibre());
    const Quat R = RandomRotation(rng, 3.1);  // up to nearly a half turn
    const Vec3 shift(1e-3, -2e-3, 5e-4);
    Pair moved = p;
    moved.x_i = R * p.x_i + shift;
    moved.x_j = R * p.x_j + shift;
    moved.q_i = R * p.q_i;
    moved.q_j = R * p.q_j;
    const BondResult after = Evaluate(moved, Fibre());
    EXPECT_NEAR(after.Energy(), before.Energy(), 1e-9 * before.Energy());
    EXPECT_LT((after.force_i - R * before.force_i).norm(), 1e-8 * before.force_i.norm());
    EXPECT_LT((after.torque_i - R * before.torque_i).norm(), 1e-8 * before.torque_i.norm());
  }
}

TEST(BeamBond, SwappingEndsGivesTheSameForcesAndTorques) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    Pair p = DeformedPair(rng, 0.05);
    const BondResult ij = Evaluate(p, Fibre());
    Pair swapped;
    swapped.x_i = p.x_j;
    swapped.x_j = p.x_i;
    swapped.q_i = p.q_j;
    swapped.q_j = p.q_i;
    // The same reference state built from the other end.
    swapped.state = MakeBondState(Vec3(-kL, 0, 0), Quat::Identity(), Quat::Identity());
    const BondResult ji = Evaluate(swapped, Fibre());
    const double scale = ij.force_i.norm();
    EXPECT_LT((ji.force_i + ij.force_i).norm(), 1e-9 * scale);  // force on j, seen from j
    EXPECT_LT((ji.torque_i - ij.torque_j).norm(), 1e-9 * ij.torque_j.norm());
    EXPECT_LT((ji.torque_j - ij.torque_i).norm(), 1e-9 * ij.torque_i.norm());
    EXPECT_NEAR(ji.Energy(), ij.Energy(), 1e-9 * ij.Energy());
  }
}

TEST(BeamBond, ForcesAndTorquesBalanceAngularMomentum) {
  std::mt19937 rng(4);
  for (int trial = 0; trial < 20; ++trial) {
    Pair p = DeformedPair(rng, 0.05);
    const BondResult r = Evaluate(p, Fibre());
    // Net torque about the origin: x_i x F_i + x_j x F_j + T_i + T_j = 0.
    const Vec3 net = p.x_i.cross(r.force_i) + p.x_j.cross(-r.force_i) + r.torque_i + r.torque_j;
    EXPECT_LT(net.norm(), 1e-12 * (r.torque_i.norm() + kL * r.force_i.norm()));
  }
}

TEST(BeamBond, ForceIsMinusEnergyGradientForSmallDeformations) {
  std::mt19937 rng(5);
  const BeamBondParams params = Fibre();
  for (int trial = 0; trial < 10; ++trial) {
    Pair p = DeformedPair(rng, 1e-4);
    const BondResult r = Evaluate(p, params);
    const double h = 1e-10;
    for (int a = 0; a < 3; ++a) {
      Pair plus = p, minus = p;
      plus.x_j[a] += h;
      minus.x_j[a] -= h;
      const double grad = (Evaluate(plus, params).Energy() - Evaluate(minus, params).Energy()) / (2 * h);
      EXPECT_NEAR(-r.force_i[a], -grad, 1e-3 * r.force_i.norm() + 1e-12) << "axis " << a;
      // Rotating j about axis a: torque on j is minus the energy gradient.
      Pair rp = p, rm = p;
      const double phi = 1e-7;
      rp.q_j = QuatFromRotationVector(Vec3::Unit(a) * phi) * p.q_j;
      rm.q_j = QuatFromRotationVector(-Vec3::Unit(a) * phi) * p.q_j;
      const double dE = (Evaluate(rp, params).Energy() - Evaluate(rm, params).Energy()) / (2 * phi);
      EXPECT_NEAR(r.torque_j[a], -dE, 2e-3 * r.torque_j.norm() + 1e-15) << "axis " << a;
    }
  }
}

TEST(BeamBond, HillCriterionIgnoresCompression) {
  BeamBondParams params = Fibre();
  params.failure = BondFailure::kHill;
  params.HillDefaults();
  Pair p;
  p.x_j = Vec3(kL, 0, 0);
  p.state = MakeBondState(p.x_j, p.q_i, p.q_j);
  // Shear at 80% of F_s0 alone does not break; adding compression must not break it.
  const double shear = 0.8 * params.F_s0 / params.k_s;
  p.x_j = Vec3(kL * (1.0 - 0.05), shear, 0);
  BondResult r = Evaluate(p, params);
  EXPECT_FALSE(r.broken);
  EXPECT_NEAR(r.failure_index, 0.8, 0.01);
  // The same shear with tension at 30% of F_r0 breaks it.
  p.x_j.x() = kL + 0.3 * params.F_r0 / params.k_n;
  r = Evaluate(p, params);
  EXPECT_TRUE(r.broken);
}

TEST(BeamBond, MaxwellDashpotRelaxesExponentially) {
  BeamBondParams params = Fibre();
  params.maxwell_tau = 1e-6;
  BondState s = MakeBondState(Vec3(kL, 0, 0), Quat::Identity(), Quat::Identity());
  const double stretch = 1e-3 * kL;
  const BondGeometry g{Vec3(kL + stretch, 0, 0), Quat::Identity(), Quat::Identity(),
                       Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  const double dt = 1e-8;
  double t = 0.0;
  for (int k = 0; k < 200; ++k) {
    const BondResult r = EvaluateBond(g, params, s, dt);
    t += dt;
    const double expected = params.k_n * stretch * std::exp(-t / params.maxwell_tau);
    ASSERT_NEAR(r.f_r, expected, 1e-9 * params.k_n * stretch);
  }
}

TEST(BeamBond, PlasticBendingCapsTheMoment) {
  BeamBondParams params = Fibre();
  params.yield_moment = 1e-9;
  BondState s = MakeBondState(Vec3(kL, 0, 0), Quat::Identity(), Quat::Identity());
  const double angle = 5.0 * params.yield_moment / params.k_b;
  const BondGeometry g{Vec3(kL, 0, 0), Quat::Identity(),
                       QuatFromRotationVector(Vec3(0, angle, 0)), Vec3::Zero(), Vec3::Zero(),
                       Vec3::Zero()};
  const BondResult r = EvaluateBond(g, params, s, 1e-9);
  EXPECT_NEAR(r.tau_b, params.yield_moment, 1e-12 * params.yield_moment);
  EXPECT_NEAR(s.plastic_y, 4.0 * params.yield_moment / params.k_b, 1e-6 * angle);
  EXPECT_GT(r.dissipated, 0.0);
}

// A bond's damping factors multiply its type's dashpots: factors (2, 3) on a type's damping
// give the forces, torques and losses of a type damped twice (translation) and three times
// (rotation) as much.
TEST(BeamBond, TheBondsDampingFactorsScaleItsTypesDashpots) {
  std::mt19937 rng(3);
  Pair p = DeformedPair(rng, 1e-3);
  const BondGeometry g{p.x_j - p.x_i, p.q_i, p.q_j, Vec3(1e-3, -2e-3, 5e-4), Vec3(10, -30, 20),
                       Vec3(-40, 5, 15)};
  BeamBondParams type = Fibre();
  type.damping_n = 2e-6, type.damping_s = 1e-6, type.damping_rot = 3e-15;
  BondState scaled = p.state;
  BeamBondParams heavier = type;
  heavier.damping_n *= 2.0, heavier.damping_s *= 2.0, heavier.damping_rot *= 3.0;
  BondState plain = p.state;
  const BondResult a = EvaluateBond(g, type, scaled, 1e-9, {2.0f, 3.0f});
  const BondResult b = EvaluateBond(g, heavier, plain, 1e-9);
  BondState unscaled = p.state;
  const BondResult c = EvaluateBond(g, type, unscaled, 1e-9);
  for (int k = 0; k < 3; ++k) {
    EXPECT_DOUBLE_EQ(a.force_i[k], b.force_i[k]);
    EXPECT_DOUBLE_EQ(a.torque_i[k], b.torque_i[k]);
    EXPECT_DOUBLE_EQ(a.torque_j[k], b.torque_j[k]);
  }
  EXPECT_DOUBLE_EQ(a.dissipated, b.dissipated);
  EXPECT_GT(std::abs(a.dissipated - c.dissipated), 0.5 * c.dissipated);
}

}  // namespace
}  // namespace fibrenet
