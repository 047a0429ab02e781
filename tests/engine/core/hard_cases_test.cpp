// Hard cases that must stay stable (SPEC section 5, issue 2): each ends with no NaN and the
// energy accounted, or with a clear RunError.
//
// "Accounted" is EnergyReport::Accounted (kinetic + strain + dissipated + released - work -
// regained overlap), which an exact integration would keep constant. It is followed here in
// its leapfrog form: the kinetic energy is taken as 1/2 m v_(n-1/2) . v_(n+1/2) with the
// strain energy at x_n, which removes the O(omega dt) offset of the energy at the end of a
// step (velocities live half a step from positions) and leaves O((omega dt)^2). Its largest
// deviation from the start, relative to the energy scale of the case, must stay within a few
// percent.
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "engine/core/energy.h"
#include "engine/core/error.h"
#include "engine/core/parallel.h"
#include "engine/core/quaternion.h"
#include "engine/core/simulation.h"
#include "engine/core/time_step.h"

namespace fibrenet {
namespace {

constexpr double kR = 16e-6, kL = 32e-6, kE = 10e9, kG = 3e9;
constexpr double kMass = 2.5e-7 * kL;  // one diameter of a 25 mg/100 m fibre [kg]

// The cases are small: each runs on one thread (ScopedThreadCount one(1)), which avoids
// OpenMP's fork and join on a busy machine.

World EmptyWorld(double width = 1e-3) {
  World w;
  w.cell.lo = Vec3(0.0, 0.0, -1e-3);
  w.cell.hi = Vec3(width, width, 1e-3);
  return w;
}

// A straight chain of n spheres along `dir` from `start`, bonded in that (stress-free) state.
std::size_t AddChain(World& w, int n, const Vec3& start, const Vec3& dir, std::int32_t type) {
  const std::size_t first = w.particles.size();
  for (int k = 0; k < n; ++k) {
    Vec3 x = start + k * kL * dir;
    w.cell.Wrap(x);
    w.particles.Add(x, kR, kMass, static_cast<std::int32_t>(first));
  }
  for (int k = 0; k + 1 < n; ++k) {
    const auto a = static_cast<std::int32_t>(first + k);
    w.bonds.Add(a, a + 1, type, BondKind::kFibre,
                MakeBondState(kL * dir, w.particles.q[a], w.particles.q[a + 1]));
  }
  return first;
}

bool AllFinite(const World& w) {
  for (std::size_t i = 0; i < w.particles.size(); ++i)
    if (!w.particles.x[i].allFinite() || !w.particles.v[i].allFinite() ||
        !w.particles.q[i].coeffs().allFinite() || !w.particles.omega[i].allFinite())
      return false;
  return true;
}

struct Balance {
  double initial = 0.0;  // accounted energy over the first step [J]
  double worst = 0.0;    // largest |accounted - initial| [J]
};

// Runs `steps` steps and follows the leapfrog form of the accounted energy.
Balance RunAccounted(World& w, Simulation& sim, int steps) {
  Particles& p = w.particles;
  Balance b;
  double U = MeasureEnergy(w).strain.Total();
  std::vector<Vec3> v_old, omega_old;
  for (int s = 0; s < steps; ++s) {
    v_old = p.v;
    omega_old = p.omega;
    const double released_before = w.energy.released;
    const double regained_before = w.energy.overlap_regained;
    sim.Step();
    double kinetic = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i)
      kinetic += 0.5 * (p.mass[i] * v_old[i].dot(p.v[i]) + p.inertia[i] * omega_old[i].dot(p.omega[i]));
    // Bonds that broke during this step are still in U(x_n), and the contacts of their pairs
    // are not yet: the step released the one and regained the other.
    const EnergyLedger& l = w.energy;
    const double accounted =
        U + kinetic + l.Dissipated() + released_before - l.Work() - regained_before;
    if (s == 0) b.initial = accounted;
    b.worst = std::max(b.worst, std::abs(accounted - b.initial));
    U = MeasureEnergy(w).strain.Total();
  }
  return b;
}

TEST(HardCases, BondToContactStiffnessRatioOfAMillion) {
  ScopedThreadCount one(1);
  World w = EmptyWorld(0.5e-3);
  w.physics.contacts = true;
  w.physics.friction = true;
  w.contact.normal.C = 2e-6;  // a soft contact: k_n / k_contact at touch above 1e6
  w.contact.restitution = 0.6;
  w.contact.Derive();
  w.walls.push_back(Wall{});
  const std::int32_t type = w.bonds.AddType(BeamBondParams::FromBeam(kE, kG, kR, kL));
  const double k_contact = w.contact.normal.C * w.contact.normal.g / (2.0 * kR);
  ASSERT_GE(w.bonds.types[0].k_n / k_contact, 1e6);
  // A lower fibre on the floor and an upper one falling across it at 1 m/s, both crossing
  // the periodic faces.
  AddChain(w, 12, Vec3(0.3e-3, 0.2e-3, kR), Vec3::UnitX(), type);
  const std::size_t upper = AddChain(w, 12, Vec3(0.4e-3, 0.35e-3, 3 * kR + 2e-6), Vec3::UnitY(), type);
  for (std::size_t i = upper; i < w.particles.size(); ++i) w.particles.v[i] = Vec3(0.0, 0.0, -1.0);
  Simulation sim(w);
  sim.Prepare();
  const double scale = MeasureEnergy(w).Kinetic();
  const Balance b = RunAccounted(w, sim, 12000);
  RecordProperty("energy_error", fmt::format("{:.2e}", b.worst / scale));
  EXPECT_TRUE(AllFinite(w));
  EXPECT_LT(b.worst, 0.02 * scale) << "initial " << b.initial;
  EXPECT_LT(w.min_contact_ratio, 0.99);  // they did touch
  EXPECT_GT(w.min_contact_ratio, 0.3);   // and the soft contact held
  EXPECT_GT(w.energy.damping, 0.0);
}

TEST(HardCases, FibreTwistedTenTurnsAndReleased) {
  ScopedThreadCount one(1);
  World w = EmptyWorld(4e-3);
  const std::int32_t type = w.bonds.AddType(BeamBondParams::FromBeam(kE, kG, kR, kL));
  constexpr int kParticles = 101;
  AddChain(w, kParticles, Vec3(0.1e-3, 0.5e-3, 0.0), Vec3::UnitX(), type);
  // Ten turns over 100 bonds: 0.63 rad of twist per bond, put into the orientations.
  const double per_bond = 10.0 * 2.0 * kPi / (kParticles - 1);
  // A small random shake, so that twist couples into bending and stretching.
  std::mt19937 rng(7);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int k = 0; k < kParticles; ++k) {
    w.particles.q[k] = QuatFromRotationVector(Vec3(k * per_bond, 0.0, 0.0));
    w.particles.v[k] = 0.1 * Vec3(n(rng), n(rng), n(rng));
  }
  Simulation sim(w);
  sim.Prepare();
  const StrainEnergy strain = MeasureEnergy(w).strain;
  const double expected = (kParticles - 1) * 0.5 * w.bonds.types[0].k_t * per_bond * per_bond;
  EXPECT_NEAR(strain.twist, expected, 1e-9 * expected);
  const Balance b = RunAccounted(w, sim, 6000);
  RecordProperty("energy_error", fmt::format("{:.2e}", b.worst / expected));
  EXPECT_TRUE(AllFinite(w));
  EXPECT_LT(b.worst, 0.02 * expected);
  // It has unwound: much of the twist energy is kinetic now.
  EXPECT_LT(MeasureEnergy(w).strain.twist, 0.9 * expected);
}

TEST(HardCases, FibreBentIntoARingWithItsEndsBonded) {
  ScopedThreadCount one(1);
  World w = EmptyWorld();
  w.physics.contacts = true;
  w.contact.Derive();
  const std::int32_t type = w.bonds.AddType(BeamBondParams::FromBeam(kE, kG, kR, kL));
  constexpr int kParticles = 40;
  // A straight fibre (rest state straight) placed on a circle of chord kL, its particles
  // turned with the tangent, and its ends bonded with the same straight rest state.
  const double radius = kL / (2.0 * std::sin(kPi / kParticles));
  const Vec3 centre(0.95e-3, 0.5e-3, 0.0);  // the ring crosses the periodic x face
  const std::size_t first = AddChain(w, kParticles, Vec3::Zero(), Vec3::UnitX(), type);
  const BondState straight = w.bonds.state[0];
  w.bonds.Add(static_cast<std::int32_t>(first + kParticles - 1), static_cast<std::int32_t>(first),
              type, BondKind::kFibre, straight);
  std::mt19937 rng(3);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int k = 0; k < kParticles; ++k) {
    const double phi = 2.0 * kPi * k / kParticles;
    Vec3 x = centre + radius * Vec3(std::cos(phi), std::sin(phi), 0.0);
    w.cell.Wrap(x);
    w.particles.x[first + k] = x;
    // Turned with the tangent: each bond's mid frame then lies along its chord.
    w.particles.q[first + k] = QuatFromRotationVector(Vec3(0.0, 0.0, phi + 0.5 * kPi));
    w.particles.v[first + k] = 0.2 * Vec3(n(rng), n(rng), n(rng));
  }
  Simulation sim(w);
  sim.Prepare();
  const EnergyReport start = MeasureEnergy(w);
  // Bent uniformly by 2 pi / n per bond, neither stretched nor sheared.
  const double bend = 2.0 * kPi / kParticles;
  const double expected = kParticles * 0.5 * w.bonds.types[0].k_b * bend * bend;
  EXPECT_NEAR(start.strain.bending, expected, 1e-6 * expected);
  EXPECT_LT(start.strain.normal + start.strain.shear, 1e-9 * expected);
  const Balance b = RunAccounted(w, sim, 6000);
  RecordProperty("energy_error", fmt::format("{:.2e}", b.worst / (expected + start.Kinetic())));
  EXPECT_TRUE(AllFinite(w));
  EXPECT_LT(b.worst, 0.02 * (expected + start.Kinetic()));
  EXPECT_EQ(w.bonds.CountIntact(), static_cast<std::size_t>(kParticles));
  // Still a ring of that radius.
  Vec3 mean = Vec3::Zero();
  for (int k = 0; k < kParticles; ++k) mean += w.cell.Delta(w.particles.x[first], w.particles.x[first + k]);
  const Vec3 c = w.particles.x[first] + mean / kParticles;
  for (int k = 0; k < kParticles; ++k)
    EXPECT_NEAR(w.cell.Delta(c, w.particles.x[first + k]).norm(), radius, 0.05 * radius) << k;
}

TEST(HardCases, HalfOfAllBondsBreakInOneStep) {
  ScopedThreadCount one(1);
  World w = EmptyWorld(2e-3);
  w.physics.contacts = true;
  w.contact.Derive();
  BeamBondParams strong = BeamBondParams::FromBeam(kE, kG, kR, kL);
  BeamBondParams weak = strong;
  weak.failure = BondFailure::kModeThresholds;
  constexpr double kStrain = 0.01;
  weak.max_tension = 0.5 * strong.k_n * kStrain * kL;  // half the tension it will carry
  const std::int32_t t_strong = w.bonds.AddType(strong), t_weak = w.bonds.AddType(weak);
  constexpr int kParticles = 41;
  AddChain(w, kParticles, Vec3(0.1e-3, 0.5e-3, 0.0), Vec3::UnitX(), t_strong);
  for (std::size_t b = 0; b < w.bonds.size(); b += 2) w.bonds.type[b] = t_weak;
  // Stretch every bond by 1% and hold still: the weak half must all go at the first step.
  for (int k = 0; k < kParticles; ++k) w.particles.x[k].x() = 0.1e-3 + k * kL * (1.0 + kStrain);
  Simulation sim(w);
  sim.Prepare();
  const double stored = MeasureEnergy(w).strain.Total();
  const Balance first = RunAccounted(w, sim, 1);
  EXPECT_EQ(w.bonds.CountIntact(), w.bonds.size() / 2);
  ASSERT_EQ(w.bonds.events.size(), w.bonds.size() / 2);
  for (const BondBreakEvent& e : w.bonds.events) {
    EXPECT_EQ(e.step, 0);
    EXPECT_EQ(e.bond % 2, 0);
  }
  EXPECT_NEAR(w.energy.released, 0.5 * stored, 1e-9 * stored);
  EXPECT_LT(first.worst, 1e-9 * stored);
  const Balance rest = RunAccounted(w, sim, 4000);
  RecordProperty("energy_error", fmt::format("{:.2e}", std::max(rest.worst, std::abs(rest.initial -
                                                                                  first.initial)) / stored));
  EXPECT_TRUE(AllFinite(w));
  EXPECT_LT(std::abs(rest.initial - first.initial), 0.02 * stored);
  EXPECT_LT(rest.worst, 0.02 * stored);
}

// A bond formed on a pressed pair (rest length "current") keeps its particles overlapping.
// Once it breaks they meet as a contact, whose compression throws them apart: the ledger
// books that contact energy as regained, and the balance holds through the break. Without
// the booking the balance would be off by all of it (the energy the pair flies off with).
TEST(HardCases, ABrokenBondGivesItsPairsOverlapBackAsAContact) {
  ScopedThreadCount one(1);
  World w = EmptyWorld(0.5e-3);
  w.physics.contacts = true;  // no friction, no damping: the contact returns all it holds
  w.contact.Derive();
  BeamBondParams params = BeamBondParams::FromBeam(kE, kG, kR, kL);
  params.failure = BondFailure::kModeThresholds;
  params.max_tension = 1e-3;  // a stretch of about 4 nm
  const std::int32_t type = w.bonds.AddType(params);
  const double d0 = 0.6 * 2.0 * kR;  // 40% overlap, above the law's linear branch
  w.particles.Add(Vec3(0.25e-3, 0.25e-3, 0.0), kR, kMass, 0);
  w.particles.Add(Vec3(0.25e-3 + d0, 0.25e-3, 0.0), kR, kMass, 1);
  w.bonds.Add(0, 1, type, BondKind::kFibreFibre,
              MakeBondState(Vec3(d0, 0.0, 0.0), w.particles.q[0], w.particles.q[1]));
  w.particles.v[0] = Vec3(-0.5, 0.0, 0.0);  // pulled apart: the bond breaks within steps
  w.particles.v[1] = Vec3(0.5, 0.0, 0.0);
  const double held = EvaluateVanWyk(d0, 2.0 * kR, w.contact.normal).energy;
  Simulation sim(w);
  sim.Prepare();
  // 1000 steps: the pair flies apart at some 50 m/s and would meet again across the cell.
  const Balance b = RunAccounted(w, sim, 1000);
  ASSERT_EQ(w.bonds.CountIntact(), 0u);
  // The bond broke nanometres from its rest length, where the contact held nearly all.
  EXPECT_NEAR(w.energy.overlap_regained, held, 0.01 * held);
  EXPECT_GT(w.cell.Delta(w.particles.x[0], w.particles.x[1]).norm(), 2.0 * kR);  // apart
  EXPECT_GT(MeasureEnergy(w).Kinetic(), 0.9 * held);
  RecordProperty("energy_error", fmt::format("{:.2e}", b.worst / held));
  EXPECT_LT(b.worst, 0.02 * held);
}

// Two crossing fibres, one falling on the other, with contacts and friction.
World CrossingFibres() {
  World w = EmptyWorld(0.5e-3);
  w.physics.contacts = true;
  w.physics.friction = true;
  w.contact.restitution = 0.5;
  w.contact.Derive();
  const std::int32_t type = w.bonds.AddType(BeamBondParams::FromBeam(kE, kG, kR, kL));
  AddChain(w, 10, Vec3(0.1e-3, 0.25e-3, 0.0), Vec3::UnitX(), type);
  const std::size_t upper = AddChain(w, 10, Vec3(0.25e-3, 0.1e-3, 2 * kR + 1e-6), Vec3::UnitY(), type);
  for (std::size_t i = upper; i < w.particles.size(); ++i) w.particles.v[i] = Vec3(0.0, 0.0, -2.0);
  return w;
}

TEST(HardCases, TimeStepTenTimesTooLargeIsReducedToAStableRun) {
  ScopedThreadCount one(1);
  World w = CrossingFibres();
  const double allowed = w.settings.safety * CriticalTimeStep(w).dt_crit;
  w.settings.dt = 10.0 * allowed;
  w.settings.policy = TimeStepPolicy::kReduce;
  Simulation sim(w);
  const std::string warning = sim.Prepare();
  EXPECT_NE(warning.find("reduced"), std::string::npos) << warning;
  EXPECT_DOUBLE_EQ(w.settings.dt, allowed);
  const double scale = MeasureEnergy(w).Kinetic();
  const Balance b = RunAccounted(w, sim, 3000);
  RecordProperty("energy_error", fmt::format("{:.2e}", b.worst / scale));
  EXPECT_TRUE(AllFinite(w));
  EXPECT_LT(b.worst, 0.02 * scale);
  EXPECT_LT(w.min_contact_ratio, 1.0);
}

TEST(HardCases, TimeStepTenTimesTooLargeIsRefusedClearly) {
  World w = CrossingFibres();
  const double allowed = w.settings.safety * CriticalTimeStep(w).dt_crit;
  w.settings.dt = 10.0 * allowed;
  w.settings.policy = TimeStepPolicy::kRefuse;
  Simulation sim(w);
  try {
    sim.Prepare();
    FAIL() << "accepted a time step ten times too large";
  } catch (const RunError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("exceeds"), std::string::npos) << what;
    EXPECT_NE(what.find("set dt <="), std::string::npos) << what;
  }
}

// Without the time-step control the same step blows up; the run must stop with an error
// that names the step and a particle, not run on with NaN.
TEST(HardCases, TimeStepTenTimesTooLargeForcedThroughStopsWithAClearError) {
  ScopedThreadCount one(1);
  World w = CrossingFibres();
  Simulation sim(w);
  sim.Prepare();
  w.settings.dt *= 10.0;  // bypasses the policy, as a careless caller could
  try {
    sim.Run(20000);
    FAIL() << "ran 20000 steps at ten times the stable step";
  } catch (const RunError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("unstable at step"), std::string::npos) << what;
    EXPECT_NE(what.find("particle"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace fibrenet
