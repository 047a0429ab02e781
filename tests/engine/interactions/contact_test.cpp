// Law-level checks of the non-bonded contact (engine/interactions/contact.h,
// van_wyk_normal.h): paper Eq. 4 and its energy, force = -dE/dd, Newton's third law and the
// balance of angular momentum with friction, symmetry under swapping i and j, the Coulomb
// cap, the rotation of the tangential history, and the damping calibration.
#include "engine/interactions/contact.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace fibrenet {
namespace {

constexpr double kRi = 16e-6, kRj = 12e-6, kSum = kRi + kRj;

// Eq. 4 and its integral from d to R_i + R_j, written out independently of the law.
double Eq4Force(double d) { return 0.00026 * (std::pow(kSum / d, 3.45) - 1.0); }
double Eq4Energy(double d) {
  const double C = 0.00026, g = 3.45;
  return C * (kSum / (g - 1.0) * (std::pow(kSum / d, g - 1.0) - 1.0) - (kSum - d));
}

Vec3 RandomUnit(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Vec3(n(rng), n(rng), n(rng)).normalized();
}

// A touching pair at centre distance `ratio` (R_i + R_j) with random relative motion.
ContactGeometry RandomPair(std::mt19937& rng, double ratio) {
  std::normal_distribution<double> n(0.0, 1.0);
  const double dist = ratio * kSum;
  ContactGeometry g{dist * RandomUnit(rng), dist, kRi, kRj, 3e-12,
                    0.1 * Vec3(n(rng), n(rng), n(rng)), 1e4 * Vec3(n(rng), n(rng), n(rng)),
                    1e4 * Vec3(n(rng), n(rng), n(rng))};
  return g;
}

ContactParams Defaults(double restitution = 1.0) {
  ContactParams p;
  p.restitution = restitution;
  p.Derive();
  return p;
}

TEST(VanWyk, ReproducesEquation4AndItsEnergy) {
  const VanWykParams p;
  EXPECT_DOUBLE_EQ(p.C, 0.00026);
  EXPECT_DOUBLE_EQ(p.g, 3.45);
  for (double ratio : {0.999, 0.95, 0.9, 0.8, 0.7, 0.6, 0.51}) {
    const double d = ratio * kSum;
    const NormalResult r = EvaluateVanWyk(d, kSum, p);
    EXPECT_NEAR(r.force, Eq4Force(d), 1e-12 * Eq4Force(d)) << ratio;
    EXPECT_NEAR(r.energy, Eq4Energy(d), 1e-9 * Eq4Energy(d)) << ratio;
    EXPECT_NEAR(r.stiffness, 0.00026 * 3.45 * std::pow(kSum / d, 3.45) / d, 1e-12 * r.stiffness);
  }
  const NormalResult apart = EvaluateVanWyk(1.01 * kSum, kSum, p);
  EXPECT_EQ(apart.force, 0.0);
  EXPECT_EQ(apart.energy, 0.0);
}

TEST(VanWyk, StiffBranchContinuesOnTheTangentAndStaysFinite) {
  const VanWykParams p;
  const double d_lin = p.linear_below * kSum;
  const NormalResult at = EvaluateVanWyk(d_lin, kSum, p);
  for (double d : {0.4 * kSum, 0.1 * kSum, 1e-6 * kSum, 0.0}) {
    const NormalResult r = EvaluateVanWyk(d, kSum, p);
    EXPECT_NEAR(r.force, at.force + at.stiffness * (d_lin - d), 1e-12 * r.force);
    EXPECT_DOUBLE_EQ(r.stiffness, at.stiffness);
    EXPECT_TRUE(std::isfinite(r.energy));
  }
}

TEST(VanWyk, ForceIsMinusTheEnergyDerivative) {
  const VanWykParams p;
  for (double ratio : {0.99, 0.9, 0.75, 0.6, 0.52, 0.45, 0.3}) {
    const double d = ratio * kSum, h = 1e-6 * kSum;
    const double fd = (EvaluateVanWyk(d - h, kSum, p).energy - EvaluateVanWyk(d + h, kSum, p).energy) / (2 * h);
    const NormalResult r = EvaluateVanWyk(d, kSum, p);
    EXPECT_NEAR(fd, r.force, 1e-6 * r.force) << ratio;
    const double dk = (EvaluateVanWyk(d - h, kSum, p).force - EvaluateVanWyk(d + h, kSum, p).force) / (2 * h);
    EXPECT_NEAR(dk, r.stiffness, 1e-6 * r.stiffness) << ratio;
  }
}

TEST(VanWyk, HardCoreAddsALinearSpringBelowTheStiffBranchOnly) {
  VanWykParams hard;
  hard.hard_stiffness = 1.5e4;
  const VanWykParams soft;
  const double d_lin = soft.linear_below * kSum;
  for (double ratio : {0.99, 0.7, 0.5}) {  // above d_lin and at it: unchanged
    const NormalResult a = EvaluateVanWyk(ratio * kSum, kSum, hard);
    const NormalResult b = EvaluateVanWyk(ratio * kSum, kSum, soft);
    EXPECT_EQ(a.force, b.force) << ratio;
    EXPECT_EQ(a.energy, b.energy) << ratio;
  }
  for (double ratio : {0.45, 0.3, 0.1}) {
    const double d = ratio * kSum, x = d_lin - d;
    const NormalResult a = EvaluateVanWyk(d, kSum, hard);
    const NormalResult b = EvaluateVanWyk(d, kSum, soft);
    EXPECT_NEAR(a.force - b.force, 1.5e4 * x, 1e-9 * a.force) << ratio;
    EXPECT_NEAR(a.energy - b.energy, 0.5 * 1.5e4 * x * x, 1e-9 * a.energy) << ratio;
    EXPECT_NEAR(a.stiffness - b.stiffness, 1.5e4, 1e-9 * a.stiffness) << ratio;
    // Still conservative: force = -dE/dd.
    const double h = 1e-6 * kSum;
    const double fd = (EvaluateVanWyk(d - h, kSum, hard).energy - EvaluateVanWyk(d + h, kSum, hard).energy) / (2 * h);
    EXPECT_NEAR(fd, a.force, 1e-6 * a.force) << ratio;
  }
  hard.hard_stiffness = -1.0;
  EXPECT_NE(hard.Validate(), "");
}

TEST(Contact, NewtonsThirdLawAndAngularMomentumWithFriction) {
  std::mt19937 rng(1);
  const ContactParams p = Defaults(0.7);
  for (int trial = 0; trial < 50; ++trial) {
    const ContactGeometry g = RandomPair(rng, 0.7 + 0.29 * (trial % 10) / 10.0);
    Vec3 xi = 1e-9 * RandomUnit(rng);
    const ContactResult r = EvaluateContact(g, p, xi, 1e-8, true);
    // The force on i is -force_j by construction; the torques must balance the moment of
    // the force pair about any point: d x F_j + T_i + T_j = 0.
    const Vec3 net = g.d.cross(r.force_j) + r.torque_i + r.torque_j;
    EXPECT_LT(net.norm(), 1e-12 * kSum * r.force_j.norm()) << trial;
    EXPECT_GE(r.normal_force, 0.0);
  }
}

TEST(Contact, SwappingIAndJGivesTheSameForcesAndTorques) {
  std::mt19937 rng(2);
  const ContactParams p = Defaults(0.5);
  for (int trial = 0; trial < 50; ++trial) {
    const ContactGeometry g = RandomPair(rng, 0.6 + 0.39 * (trial % 10) / 10.0);
    const ContactGeometry s{-g.d, g.dist, g.r_j, g.r_i, g.m_eff, -g.v_rel, g.omega_j, g.omega_i};
    const Vec3 start = 2e-10 * RandomUnit(rng);
    Vec3 xi = start, xi_swapped = -start;  // the history seen from the other side
    const ContactResult a = EvaluateContact(g, p, xi, 1e-8, true);
    const ContactResult b = EvaluateContact(s, p, xi_swapped, 1e-8, true);
    const double f = a.force_j.norm(), t = a.torque_i.norm() + a.torque_j.norm() + 1e-30;
    EXPECT_LT((b.force_j + a.force_j).norm(), 1e-12 * f) << trial;  // on old i
    EXPECT_LT((b.torque_i - a.torque_j).norm(), 1e-9 * t) << trial;
    EXPECT_LT((b.torque_j - a.torque_i).norm(), 1e-9 * t) << trial;
    EXPECT_LT((xi_swapped + xi).norm(), 1e-12 * xi.norm() + 1e-30) << trial;
    EXPECT_NEAR(b.slip_loss, a.slip_loss, 1e-12 * a.slip_loss + 1e-30);
  }
}

TEST(Contact, FrictionIsCappedAtMuTimesTheNormalForce) {
  std::mt19937 rng(3);
  const ContactParams p = Defaults(0.8);
  for (int trial = 0; trial < 20; ++trial) {
    const ContactGeometry g = RandomPair(rng, 0.9);
    const Vec3 n = g.d / g.dist;
    // A history far beyond the Coulomb limit: the contact must slip to exactly mu F_n.
    Vec3 xi = RandomUnit(rng);
    xi = 1e-6 * (xi - xi.dot(n) * n).normalized();
    const ContactResult r = EvaluateContact(g, p, xi, 1e-8, true);
    const Vec3 f_t = r.force_j - r.force_j.dot(n) * n;
    EXPECT_NEAR(f_t.norm(), p.mu * r.normal_force, 1e-12 * r.normal_force);
    EXPECT_GT(r.slip_loss, 0.0);
    // The stored history is the spring stretch that gives the capped force.
    const double k_t = p.tangential_ratio * EvaluateVanWyk(g.dist, kSum, p.normal).stiffness;
    EXPECT_NEAR(xi.norm() * k_t, p.mu * r.normal_force, 1e-9 * p.mu * r.normal_force);
    // Below the cap there is no slip.
    Vec3 small = 1e-15 * (RandomUnit(rng).cross(n)).normalized();
    const ContactResult stick = EvaluateContact(g, p, small, 0.0, true);
    EXPECT_EQ(stick.slip_loss, 0.0);
    EXPECT_LT((stick.force_j - stick.force_j.dot(n) * n).norm(), p.mu * stick.normal_force);
  }
}

// The hard core is the collapsed wall in compression: it stiffens the normal spring, not the
// friction spring. A friction spring that stiffened 25-fold as a pair entered the core would
// make the contact's energy jump there, with no force doing work for it.
TEST(Contact, TheHardCoreStiffensTheNormalSpringNotTheFrictionSpring) {
  ContactParams soft = Defaults();
  ContactParams hard = soft;
  hard.normal.hard_stiffness = 1.5e4;
  const Vec3 n = Vec3(1.0, 2.0, 2.0) / 3.0;
  const Vec3 xi0 = 1e-9 * n.cross(Vec3::UnitZ()).normalized();  // stuck: below mu F_n
  auto at = [&](double ratio, const ContactParams& p) {
    const double dist = ratio * kSum;
    const ContactGeometry g{dist * n, dist, kRi, kRj, 3e-12, Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
    Vec3 xi = xi0;
    return EvaluateContact(g, p, xi, 0.0, true);
  };
  const ContactResult s = at(0.3, soft), h = at(0.3, hard);
  EXPECT_GT(h.normal_force, s.normal_force + 1e4 * 0.2 * kSum);
  const Vec3 ft_s = s.force_j - s.force_j.dot(n) * n, ft_h = h.force_j - h.force_j.dot(n) * n;
  ASSERT_GT(ft_s.norm(), 0.0);
  EXPECT_LT((ft_h - ft_s).norm(), 1e-9 * ft_s.norm());
  // The energy is continuous across the core's edge (d_lin = 0.5 (R_i + R_j)).
  const double k_t = hard.tangential_ratio * EvaluateVanWyk(0.5 * kSum, kSum, hard.normal).stiffness;
  const double friction_energy = 0.5 * k_t * xi0.squaredNorm();
  EXPECT_NEAR(at(0.5 - 1e-12, hard).energy, at(0.5 + 1e-12, hard).energy, 1e-2 * friction_energy);
}

// A slip books exactly the friction spring's energy it releases, however far the history
// stood beyond the cap (as where the normal force falls at once): the contact's energy
// before equals its energy after plus the loss.
TEST(Contact, SlipBooksTheFrictionSpringEnergyItReleases) {
  std::mt19937 rng(5);
  const ContactParams p = Defaults(0.8);
  for (const double beyond : {1.001, 2.0, 100.0}) {
    const ContactGeometry g{0.9 * kSum * Vec3::UnitX(), 0.9 * kSum, kRi, kRj, 3e-12,
                            Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
    const NormalResult nr = EvaluateVanWyk(g.dist, kSum, p.normal);
    const double k_t = p.tangential_ratio * nr.law_stiffness;
    Vec3 xi = (beyond * p.mu * nr.force / k_t) * RandomUnit(rng).cross(Vec3::UnitX()).normalized();
    const double before = nr.energy + 0.5 * k_t * xi.squaredNorm();
    const ContactResult r = EvaluateContact(g, p, xi, 0.0, true);  // no motion: dt = 0
    EXPECT_GT(r.slip_loss, 0.0);
    EXPECT_NEAR(r.energy + r.slip_loss, before, 1e-12 * before) << "history at " << beyond << " x the cap";
  }
}

TEST(Contact, HistoryIsRotatedIntoTheNewTangentPlaneKeepingItsLength) {
  std::mt19937 rng(4);
  ContactParams p = Defaults();
  p.mu = 1e9;  // no slip: the history is only rotated
  for (int trial = 0; trial < 20; ++trial) {
    const Vec3 n_old = RandomUnit(rng);
    Vec3 xi = 1e-10 * (RandomUnit(rng).cross(n_old)).normalized();
    const double length = xi.norm();
    // The pair has turned: a new normal, no relative motion (dt = 0 adds no displacement).
    const Vec3 n_new = (n_old + 0.3 * RandomUnit(rng)).normalized();
    const ContactGeometry g{0.9 * kSum * n_new, 0.9 * kSum, kRi, kRj, 3e-12,
                            Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
    EvaluateContact(g, p, xi, 0.0, true);
    EXPECT_NEAR(xi.norm(), length, 1e-12 * length);
    EXPECT_LT(std::abs(xi.dot(n_new)), 1e-12 * length);
  }
}

TEST(Contact, DampingNeverPullsThePairTogether) {
  const ContactParams p = Defaults(0.1);
  // Separating fast at a light overlap: the damping would exceed the spring force.
  const ContactGeometry g{Vec3(0.999 * kSum, 0, 0), 0.999 * kSum, kRi, kRj, 3e-12,
                          Vec3(10.0, 0, 0), Vec3::Zero(), Vec3::Zero()};
  Vec3 xi = Vec3::Zero();
  const ContactResult r = EvaluateContact(g, p, xi, 1e-8, false);
  EXPECT_EQ(r.normal_force, 0.0);
  EXPECT_GE(r.damping_power, 0.0);
}

// A linear spring-dashpot whose total force may not pull, integrated finely.
double NumericCappedRestitution(double zeta) {
  double y = 0.0, v = 1.0;
  const double h = 1e-5;
  for (int k = 1; k < 10000000; ++k) {
    v += (-y - 2.0 * zeta * v) * h;
    y += v * h;
    if (y + 2.0 * zeta * v <= 0.0) return -v;
  }
  return -1.0;
}

TEST(ContactDamping, CappedRestitutionMatchesTheDashpotIntegral) {
  for (double zeta : {0.02, 0.1, 0.3, 0.6, 0.9, 1.0, 1.5, 4.0})
    EXPECT_NEAR(CappedRestitution(zeta), NumericCappedRestitution(zeta), 2e-5) << zeta;
  EXPECT_EQ(CappedRestitution(0.0), 1.0);
}

TEST(ContactDamping, DeriveInvertsTheRestitution) {
  for (double e : {0.05, 0.2, 0.5, 0.8, 0.95, 0.999}) {
    const ContactParams p = Defaults(e);
    EXPECT_NEAR(CappedRestitution(p.zeta), e, 1e-12) << e;
    // More damping than the linear-spring formula, whose contact would end at zero overlap.
    const double ln_e = std::log(e);
    EXPECT_GT(p.zeta, -ln_e / std::sqrt(kPi * kPi + ln_e * ln_e)) << e;
  }
  EXPECT_EQ(Defaults(1.0).zeta, 0.0);
}

}  // namespace
}  // namespace fibrenet
