// The core loop (engine/core/simulation.h, neighbour_list.h, time_step.h): the Verlet list
// against a brute-force search, its rebuild on displacement, the time-step policy, the
// error on a non-finite state, determinism for a given thread count, local damping against
// its analytic decay, and the floating-point mode of the threads.
#include "engine/core/simulation.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "engine/core/energy.h"
#include "engine/core/error.h"
#include "engine/core/float_mode.h"
#include "engine/core/parallel.h"
#include "engine/core/time_step.h"

namespace fibrenet {
namespace {

using Pairs = std::vector<std::pair<int, int>>;

Pairs ListedPairs(const NeighbourList& nl, std::size_t n) {
  Pairs out;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = nl.RowBegin(i); k < nl.RowEnd(i); ++k)
      out.emplace_back(std::minmax(static_cast<int>(i), static_cast<int>(nl.Partner(k))));
  std::sort(out.begin(), out.end());
  return out;
}

// Every unordered pair within R_i + R_j + skin under the minimum image, bonded pairs left out.
Pairs BruteForcePairs(const Particles& p, const Cell& cell, const Bonds& bonds, double skin) {
  Pairs bonded;
  for (std::size_t b = 0; b < bonds.size(); ++b)
    if (!bonds.broken[b])
      bonded.emplace_back(std::min(bonds.i[b], bonds.j[b]), std::max(bonds.i[b], bonds.j[b]));
  std::sort(bonded.begin(), bonded.end());
  Pairs out;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const double reach = p.radius[i] + p.radius[j] + skin;
      if (cell.Delta(p.x[i], p.x[j]).squaredNorm() >= reach * reach) continue;
      const std::pair<int, int> ij(static_cast<int>(i), static_cast<int>(j));
      if (std::binary_search(bonded.begin(), bonded.end(), ij)) continue;
      out.push_back(ij);
    }
  }
  return out;
}

// Random spheres in a cell of edge `width` (periodic or not in x, y), z in [0, height].
World RandomWorld(std::mt19937& rng, int n, double width, double height, bool periodic) {
  World w;
  w.cell.lo = Vec3(0.0, 0.0, -1e-3);
  w.cell.hi = Vec3(width, width, 1e-3);
  w.cell.periodic_x = w.cell.periodic_y = periodic;
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < n; ++k) {
    const double r = 12e-6 + 8e-6 * u(rng);
    w.particles.Add(Vec3(width * u(rng), width * u(rng), height * u(rng)), r, 8e-12, k);
  }
  return w;
}

// Bonds between some close pairs (they must be left out of the list) and some far ones.
void AddSomeBonds(World& w, std::mt19937& rng) {
  const std::int32_t type = w.bonds.AddType(BeamBondParams::FromBeam(10e9, 3e9, 16e-6, 32e-6));
  const Pairs close = BruteForcePairs(w.particles, w.cell, w.bonds, 10e-6);
  for (std::size_t k = 0; k < close.size(); k += 2)
    w.bonds.Add(close[k].first, close[k].second, type, BondKind::kFibreFibre, BondState{});
  std::uniform_int_distribution<int> any(0, static_cast<int>(w.particles.size()) - 1);
  for (int k = 0; k < 20; ++k) {
    const int a = any(rng), b = any(rng);
    if (a != b) w.bonds.Add(a, b, type, BondKind::kFibre, BondState{});
  }
}

TEST(NeighbourList, FindsExactlyTheBruteForcePairs) {
  std::mt19937 rng(1);
  struct Setup {
    int n;
    double width, height;
    bool periodic;
  };
  // Dense and sparse, periodic and open, and cells only two or three grid cells wide; built
  // by one, two and three threads, each of which scans its share of the rows.
  for (const Setup s : {Setup{400, 0.5e-3, 0.1e-3, true}, Setup{400, 0.5e-3, 0.1e-3, false},
                        Setup{150, 0.13e-3, 0.05e-3, true}, Setup{100, 0.17e-3, 0.0, true},
                        Setup{200, 0.6e-3, 0.3e-3, true}, Setup{5000, 1.2e-3, 0.1e-3, true}}) {
    World w = RandomWorld(rng, s.n, s.width, s.height, s.periodic);
    AddSomeBonds(w, rng);
    const double skin = 8e-6;
    const Pairs brute = BruteForcePairs(w.particles, w.cell, w.bonds, skin);
    EXPECT_FALSE(brute.empty());
    for (int threads : {1, 2, 3}) {
      const ScopedThreadCount team(threads);
      NeighbourList list;
      list.Build(w.particles, w.cell, w.bonds, skin);
      EXPECT_EQ(ListedPairs(list, w.particles.size()), brute)
          << s.n << " " << s.width << ", " << threads << " threads";
    }
  }
}

TEST(NeighbourList, LeavesOutBondsUntilTheyBreak) {
  std::mt19937 rng(2);
  World w = RandomWorld(rng, 200, 0.3e-3, 0.05e-3, true);
  AddSomeBonds(w, rng);
  ASSERT_GT(w.bonds.size(), 0u);
  for (std::size_t b = 0; b < w.bonds.size(); b += 3) w.bonds.broken[b] = 1;
  w.neighbours.Build(w.particles, w.cell, w.bonds, 5e-6);
  EXPECT_EQ(ListedPairs(w.neighbours, w.particles.size()),
            BruteForcePairs(w.particles, w.cell, w.bonds, 5e-6));
}

// Bonds that break bring their pairs into the rows at once, without a build: the rows then
// hold the pairs held before and the broken ones, each row sorted and owning its entries, and
// every history as it was; every pair a build would list is among them.
TEST(NeighbourList, PairsOfBrokenBondsJoinTheRowsWithoutABuild) {
  std::mt19937 rng(7);
  World w = RandomWorld(rng, 400, 0.5e-3, 0.1e-3, true);
  AddSomeBonds(w, rng);
  const double skin = 8e-6;
  NeighbourList& nl = w.neighbours;
  nl.Build(w.particles, w.cell, w.bonds, skin);
  for (std::size_t k = 0; k < nl.size(); ++k) nl.History(k) = Vec3(1e-9 * (k + 1), 0.0, -1e-9);
  const std::vector<PairHistory> histories = nl.ExportHistory();
  Pairs expected = ListedPairs(nl, w.particles.size());
  std::vector<std::pair<std::int32_t, std::int32_t>> broken;
  for (std::size_t b = 0; b < w.bonds.size(); b += 2) {
    w.bonds.broken[b] = 1;
    broken.emplace_back(w.bonds.i[b], w.bonds.j[b]);
    expected.push_back(std::minmax(w.bonds.i[b], w.bonds.j[b]));
  }
  std::sort(expected.begin(), expected.end());
  const std::size_t builds = nl.builds();
  ASSERT_TRUE(nl.AddBrokenBondPairs(broken));
  EXPECT_EQ(nl.builds(), builds);
  const Pairs listed = ListedPairs(nl, w.particles.size());
  EXPECT_EQ(listed, expected);
  for (const auto& pair : BruteForcePairs(w.particles, w.cell, w.bonds, skin))
    EXPECT_TRUE(std::binary_search(listed.begin(), listed.end(), pair));
  for (std::size_t i = 0; i < w.particles.size(); ++i)
    for (std::size_t k = nl.RowBegin(i); k < nl.RowEnd(i); ++k) {
      EXPECT_EQ(nl.Owner(k), static_cast<std::int32_t>(i));
      if (k > nl.RowBegin(i)) {
        EXPECT_LT(nl.Partner(k - 1), nl.Partner(k));
      }
    }
  const std::vector<PairHistory> after = nl.ExportHistory();
  ASSERT_EQ(after.size(), histories.size());
  for (std::size_t h = 0; h < after.size(); ++h) {
    EXPECT_EQ(after[h].i, histories[h].i);
    EXPECT_EQ(after[h].j, histories[h].j);
    EXPECT_EQ(after[h].xi, histories[h].xi);
  }
}

// Where the rows cannot stand for a build, nothing changes and the caller builds: a list
// never built, and a pair that a second bond joined at the last build.
TEST(NeighbourList, BrokenBondPairsAreRefusedWhereOnlyABuildWillDo) {
  std::mt19937 rng(8);
  World w = RandomWorld(rng, 200, 0.3e-3, 0.05e-3, true);
  AddSomeBonds(w, rng);
  const std::pair<std::int32_t, std::int32_t> first(w.bonds.i[0], w.bonds.j[0]);
  EXPECT_FALSE(w.neighbours.AddBrokenBondPairs({first}));
  w.bonds.Add(first.first, first.second, w.bonds.type[0], BondKind::kFibreFibre, BondState{});
  w.neighbours.Build(w.particles, w.cell, w.bonds, 5e-6);
  const Pairs before = ListedPairs(w.neighbours, w.particles.size());
  w.bonds.broken[0] = 1;
  EXPECT_FALSE(w.neighbours.AddBrokenBondPairs({first}));
  EXPECT_EQ(ListedPairs(w.neighbours, w.particles.size()), before);
  const std::pair<std::int32_t, std::int32_t> second(w.bonds.i[1], w.bonds.j[1]);
  w.bonds.broken[1] = 1;
  EXPECT_TRUE(w.neighbours.AddBrokenBondPairs({second}));
}

// Particles numbered in no spatial order (fibres placed at random, say): the rows of the
// first half of the particles must still hold about half the pairs, since the threads split
// the rows by particle range. Holding each pair in its lower index's row would give them 3/4.
TEST(NeighbourList, RowsShareThePairsEvenlyWhateverTheParticleOrder) {
  std::mt19937 rng(5);
  World w = RandomWorld(rng, 3000, 0.6e-3, 0.3e-3, true);
  w.neighbours.Build(w.particles, w.cell, w.bonds, 8e-6);
  const std::size_t half = w.particles.size() / 2;
  const double share = static_cast<double>(w.neighbours.RowBegin(half)) /
                       static_cast<double>(w.neighbours.size());
  ASSERT_GT(w.neighbours.size(), 5000u);
  EXPECT_NEAR(share, 0.5, 0.03);
}

// A pair's tangential history is exported from its lower index's side, whichever row holds
// it (seen from the other side it is -xi), and imported back into the same rows unchanged.
TEST(NeighbourList, ContactHistoriesRoundTripFromEitherSide) {
  std::mt19937 rng(6);
  World w = RandomWorld(rng, 400, 0.5e-3, 0.1e-3, true);
  NeighbourList& nl = w.neighbours;
  nl.Build(w.particles, w.cell, w.bonds, 8e-6);
  std::size_t held_by_higher = 0;
  for (std::size_t i = 0; i < w.particles.size(); ++i)
    for (std::size_t k = nl.RowBegin(i); k < nl.RowEnd(i); ++k) {
      nl.History(k) = Vec3(1e-9 * static_cast<double>(k + 1), 2e-9, -3e-9);
      held_by_higher += nl.Partner(k) < static_cast<std::int32_t>(i);
    }
  ASSERT_GT(held_by_higher, 0u);
  const std::vector<PairHistory> exported = nl.ExportHistory();
  ASSERT_EQ(exported.size(), nl.size());
  for (const PairHistory& h : exported) {
    ASSERT_LT(h.i, h.j);
    const bool in_row_i = std::binary_search(nl.partners().begin() + nl.RowBegin(h.i),
                                             nl.partners().begin() + nl.RowEnd(h.i), h.j);
    const std::size_t owner = in_row_i ? h.i : h.j;
    const std::int32_t partner = in_row_i ? h.j : h.i;
    const auto at = std::lower_bound(nl.partners().begin() + nl.RowBegin(owner),
                                     nl.partners().begin() + nl.RowEnd(owner), partner);
    const Vec3 stored = nl.History(static_cast<std::size_t>(at - nl.partners().begin()));
    EXPECT_EQ(h.xi, in_row_i ? stored : Vec3(-stored));
  }
  NeighbourList fresh;
  fresh.Build(w.particles, w.cell, w.bonds, 8e-6);
  fresh.ImportHistory(exported);
  ASSERT_EQ(fresh.size(), nl.size());
  for (std::size_t k = 0; k < nl.size(); ++k) EXPECT_EQ(fresh.History(k), nl.History(k));
  // The same histories named from the other side of each pair.
  std::vector<PairHistory> swapped;
  for (const PairHistory& h : exported) swapped.push_back({h.j, h.i, -h.xi});
  NeighbourList other;
  other.Build(w.particles, w.cell, w.bonds, 8e-6);
  other.ImportHistory(swapped);
  for (std::size_t k = 0; k < nl.size(); ++k) EXPECT_EQ(other.History(k), nl.History(k));
}

TEST(NeighbourList, AParkedListKeepsTheHistoryAndItsNextBuildRestoresIt) {
  std::mt19937 rng(6);
  World w = RandomWorld(rng, 400, 0.5e-3, 0.1e-3, true);
  NeighbourList& nl = w.neighbours;
  nl.Build(w.particles, w.cell, w.bonds, 8e-6);
  for (std::size_t k = 0; k < nl.size(); k += 3) nl.History(k) = Vec3(1e-9 * double(k + 1), 2e-9, -3e-9);
  const std::vector<PairHistory> before = nl.ExportHistory();
  ASSERT_GT(before.size(), 10u);

  // A kept copy holds the history without the rows; the world it came from is untouched.
  const std::size_t rows_bytes = nl.MemoryBytes();
  World copy = KeptCopy(w);
  EXPECT_TRUE(copy.neighbours.parked());
  EXPECT_EQ(copy.neighbours.size(), 0u);
  EXPECT_LT(copy.neighbours.MemoryBytes(), rows_bytes / 4);
  EXPECT_FALSE(nl.parked());
  EXPECT_EQ(nl.MemoryBytes(), rows_bytes);
  EXPECT_EQ(nl.ExportHistory().size(), before.size());
  const std::vector<PairHistory> parked = copy.neighbours.ExportHistory();
  ASSERT_EQ(parked.size(), before.size());

  // A rigid turn turns the parked history too; the copy's first build restores it.
  const Mat3 R = Eigen::AngleAxisd(0.3, Vec3::UnitZ()).toRotationMatrix();
  copy.neighbours.RotateHistory(R);
  copy.neighbours.Build(copy.particles, copy.cell, copy.bonds, 8e-6);
  EXPECT_FALSE(copy.neighbours.parked());
  ASSERT_EQ(copy.neighbours.size(), nl.size());
  const std::vector<PairHistory> restored = copy.neighbours.ExportHistory();
  ASSERT_EQ(restored.size(), before.size());
  for (std::size_t k = 0; k < before.size(); ++k) {
    EXPECT_EQ(restored[k].i, before[k].i);
    EXPECT_EQ(restored[k].j, before[k].j);
    EXPECT_NEAR((restored[k].xi - R * before[k].xi).norm(), 0.0, 1e-24);
  }

  // With another particle count the indices name other particles: the history lapses.
  World fewer = KeptCopy(w);
  fewer.particles.Add(Vec3(0.25e-3, 0.25e-3, 0.05e-3), 5e-6, 1e-12, -1);
  fewer.neighbours.Build(fewer.particles, fewer.cell, fewer.bonds, 8e-6);
  EXPECT_TRUE(fewer.neighbours.ExportHistory().empty());
}

TEST(NeighbourList, IsRebuiltWhenAParticleMovesHalfTheSkin) {
  World w;
  w.cell.lo = Vec3(0.0, 0.0, -1e-3);
  w.cell.hi = Vec3(1e-3, 1e-3, 1e-3);
  w.physics.contacts = true;
  w.contact.Derive();
  const double R = 16e-6, skin = 8e-6;
  w.settings.skin = skin;
  // Two spheres 2R + 1.2 skin apart: outside the list's reach at the first build.
  w.particles.Add(Vec3(0.5e-3, 0.5e-3, 0.0), R, 8e-12, 0);
  w.particles.Add(Vec3(0.5e-3 + 2 * R + 1.2 * skin, 0.5e-3, 0.0), R, 8e-12, 1);
  // A third near the periodic face, to cross it.
  w.particles.Add(Vec3(1e-3 - 0.05 * skin, 0.2e-3, 0.0), R, 8e-12, 2);
  Simulation sim(w);
  sim.Prepare();
  const std::size_t builds = w.neighbours.builds();
  EXPECT_EQ(w.neighbours.size(), 0u);

  // Crossing the periodic face by a tenth of the skin is a small move, not a jump of Lx.
  w.particles.x[2].x() += 0.1 * skin;
  w.cell.Wrap(w.particles.x[2]);
  ASSERT_LT(w.particles.x[2].x(), 0.5e-3);
  // Just under half the skin: no rebuild.
  w.particles.x[1].x() -= 0.49 * skin;
  EXPECT_FALSE(w.neighbours.NeedsRebuild(w.particles, w.cell));
  sim.ComputeForces();
  EXPECT_EQ(w.neighbours.builds(), builds);
  // Past half the skin: rebuilt, and the pair, now overlapping, is found and pushes.
  w.particles.x[1].x() -= 0.72 * skin;  // now 2R - 0.01 skin apart
  EXPECT_TRUE(w.neighbours.NeedsRebuild(w.particles, w.cell));
  sim.ComputeForces();
  EXPECT_EQ(w.neighbours.builds(), builds + 1);
  EXPECT_EQ(w.neighbours.size(), 1u);
  EXPECT_GT(w.particles.force[1].x(), 0.0);
  EXPECT_LT(w.particles.force[0].x(), 0.0);
}

// A straight chain of n bonded spheres along x.
void AddChain(World& w, int n, double spacing) {
  const std::int32_t type = w.bonds.AddType(BeamBondParams::FromBeam(10e9, 3e9, 16e-6, spacing));
  const std::size_t first = w.particles.size();
  for (int k = 0; k < n; ++k)
    w.particles.Add(Vec3(k * spacing, 0.0, 0.0) + Vec3(1e-4, 1e-4, 0.0), 16e-6, 8e-12, 0);
  for (int k = 0; k + 1 < n; ++k) {
    const auto a = static_cast<std::int32_t>(first + k);
    w.bonds.Add(a, a + 1, type, BondKind::kFibre,
                MakeBondState(Vec3(spacing, 0, 0), Quat::Identity(), Quat::Identity()));
  }
}

World ChainWorld() {
  World w;
  w.cell.lo = Vec3(0.0, 0.0, -1e-3);
  w.cell.hi = Vec3(1e-3, 1e-3, 1e-3);
  AddChain(w, 6, 32e-6);
  return w;
}

TEST(TimeStep, TooLargeAStepIsReducedWithAWarning) {
  World w = ChainWorld();
  const double dt_crit = CriticalTimeStep(w).dt_crit;
  ASSERT_GT(dt_crit, 0.0);
  w.settings.policy = TimeStepPolicy::kReduce;
  w.settings.dt = 10.0 * w.settings.safety * dt_crit;
  Simulation sim(w);
  const std::string warning = sim.Prepare();
  EXPECT_NE(warning.find("exceeds"), std::string::npos) << warning;
  EXPECT_NE(warning.find("reduced"), std::string::npos) << warning;
  EXPECT_DOUBLE_EQ(w.settings.dt, w.settings.safety * dt_crit);
}

TEST(TimeStep, TooLargeAStepIsRefusedWithARunError) {
  World w = ChainWorld();
  const double dt_crit = CriticalTimeStep(w).dt_crit;
  w.settings.policy = TimeStepPolicy::kRefuse;
  w.settings.dt = 10.0 * w.settings.safety * dt_crit;
  Simulation sim(w);
  try {
    sim.Prepare();
    FAIL() << "a step 10x too large was accepted";
  } catch (const RunError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("exceeds"), std::string::npos) << what;
    EXPECT_NE(what.find("bond"), std::string::npos) << what;  // names what limits the step
  }
}

TEST(TimeStep, AStepWithinTheLimitIsKeptAndZeroChoosesOne) {
  World w = ChainWorld();
  const double dt_crit = CriticalTimeStep(w).dt_crit;
  w.settings.policy = TimeStepPolicy::kRefuse;
  w.settings.dt = 0.3 * dt_crit;
  Simulation sim(w);
  EXPECT_EQ(sim.Prepare(), "");
  EXPECT_EQ(w.settings.dt, 0.3 * dt_crit);

  World automatic = ChainWorld();
  Simulation sim2(automatic);
  EXPECT_EQ(sim2.Prepare(), "");
  EXPECT_DOUBLE_EQ(automatic.settings.dt, automatic.settings.safety * dt_crit);
}

// A stretch dashpot at zeta of critical on the pair's reduced mass scales the limit by
// sqrt(1 + zeta^2) - zeta, the damped oscillator's under symplectic Euler; the time step
// keeps below it whatever the safety. Without dashpots the limit is dt_crit itself.
TEST(TimeStep, BondDashpotsLowerTheLimitAsForADampedOscillator) {
  World w = ChainWorld();
  const TimeStepInfo undamped = CriticalTimeStep(w);
  EXPECT_EQ(undamped.dt_damped, undamped.dt_crit);
  const double m_reduced = 0.5 * 8e-12;
  for (double zeta : {0.1, 1.0}) {
    World damped = ChainWorld();
    BeamBondParams& t = damped.bonds.types[0];
    t.damping_n = 2.0 * zeta * std::sqrt(t.k_n * m_reduced);
    const TimeStepInfo info = CriticalTimeStep(damped);
    EXPECT_DOUBLE_EQ(info.dt_crit, undamped.dt_crit);
    const double limit = undamped.dt_crit * (std::sqrt(1.0 + zeta * zeta) - zeta);
    EXPECT_NEAR(info.dt_damped, limit, 1e-12 * limit) << zeta;
    EXPECT_NE(info.damped_limited_by.find("stretch dashpot of bond"), std::string::npos)
        << info.damped_limited_by;
    damped.settings.safety = 0.9;
    Simulation sim(damped);
    EXPECT_EQ(sim.Prepare(), "");
    EXPECT_DOUBLE_EQ(damped.settings.dt, std::min(0.9 * undamped.dt_crit, limit)) << zeta;
  }
}

TEST(TimeStep, HardCoresOfContactsAndSurfacesShortenTheStep) {
  World w;
  w.cell.hi = Vec3(1e-3, 1e-3, 1e-3);
  w.particles.Add(Vec3(5e-4, 5e-4, 5e-4), 16e-6, 8e-12, -1);
  w.physics.contacts = true;
  w.physics.friction = false;
  const double soft = CriticalTimeStep(w).dt_crit;
  // A lone sphere: omega^2 = (2 bound k_contact + k_surfaces) / m, times m R^2 / I = 2.5 for
  // the contacts' rotational stiffness, which limits; the cores add to the stiffnesses.
  const VanWykParams& vw = w.contact.normal;
  const double k_cap = vw.C * vw.g * std::pow(1.0 / vw.linear_below, vw.g) / (vw.linear_below * 32e-6);
  const double bound2 = 2.0 * w.settings.contacts_per_particle_bound;
  auto expected = [&](double k_contact, double k_surfaces) {
    return 2.0 / std::sqrt(2.5 * (bound2 * k_contact + k_surfaces) / 8e-12);
  };
  EXPECT_NEAR(soft, expected(k_cap, 0.0), 1e-12 * soft);
  w.contact.normal.hard_stiffness = 1.5e4;
  const double hard = CriticalTimeStep(w).dt_crit;
  EXPECT_NEAR(hard, expected(k_cap + 1.5e4, 0.0), 1e-12 * hard);
  Wall wall;
  wall.hard_stiffness = 3e4;
  w.walls.push_back(wall);
  const double with_wall = CriticalTimeStep(w).dt_crit;
  EXPECT_NEAR(with_wall, expected(k_cap + 1.5e4, 3e4), 1e-12 * with_wall);
  // Friction adds the tangential spring at the law's stiffness only: the core stiffens the
  // normal spring alone.
  w.physics.friction = true;
  w.contact.tangential_ratio = 0.8;
  const double with_friction = CriticalTimeStep(w).dt_crit;
  EXPECT_NEAR(with_friction, expected(1.8 * k_cap + 1.5e4, 3e4), 1e-12 * with_friction);
}

void ExpectRunErrorNaming(Simulation& sim, std::int64_t step, std::size_t particle) {
  try {
    sim.Run(10);
    FAIL() << "a non-finite state did not stop the run";
  } catch (const RunError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(fmt::format("step {}", step)), std::string::npos) << what;
    EXPECT_NE(what.find(fmt::format("particle {} ", particle)), std::string::npos) << what;
    EXPECT_NE(what.find("non-finite"), std::string::npos) << what;
  }
}

TEST(Instability, NaNInABondedParticleStopsTheRunNamingStepAndParticle) {
  World w = ChainWorld();
  w.physics.contacts = true;
  w.contact.Derive();
  Simulation sim(w);
  sim.Prepare();
  sim.Run(5);
  w.particles.x[3].y() = std::nan("");
  ExpectRunErrorNaming(sim, 5, 3);
}

TEST(Instability, NaNInALoneParticleStopsTheRun) {
  World w = ChainWorld();
  const std::size_t lone = w.particles.Add(Vec3(5e-4, 5e-4, 0.0), 16e-6, 8e-12, 1);
  Simulation sim(w);
  sim.Prepare();
  sim.Run(2);
  w.particles.v[lone].z() = std::numeric_limits<double>::infinity();
  ExpectRunErrorNaming(sim, 2, lone);
}

// Every component of every state array, with each kind of non-finite value: the state check
// tests each particle once (a component times zero is NaN for an infinity or a NaN).
TEST(Instability, EveryNonFiniteComponentOfEveryArrayStopsTheRun) {
  const double inf = std::numeric_limits<double>::infinity();
  for (const double bad : {std::nan(""), inf, -inf}) {
    for (int array = 0; array < 4; ++array) {
      for (int component = 0; component < (array == 2 ? 4 : 3); ++component) {
        World w = ChainWorld();
        Simulation sim(w);
        sim.Prepare();
        sim.Run(2);
        Particles& p = w.particles;
        if (array == 0) p.x[3][component] = bad;
        if (array == 1) p.v[3][component] = bad;
        if (array == 2) p.q[3].coeffs()[component] = bad;
        if (array == 3) p.omega[3][component] = bad;
        SCOPED_TRACE(fmt::format("array {}, component {}, value {}", array, component, bad));
        ExpectRunErrorNaming(sim, 2, 3);
      }
    }
  }
}

// Two crossing chains falling on a floor with friction: bonds, contacts, walls, gravity.
World BusyWorld() {
  World w;
  w.cell.lo = Vec3(0.0, 0.0, -1e-3);
  w.cell.hi = Vec3(0.4e-3, 0.4e-3, 1e-3);
  w.physics.gravity = true;
  w.physics.g = Vec3(0.0, 0.0, -5e3);  // strong, so that contacts form within a short run
  w.physics.contacts = true;
  w.physics.friction = true;
  w.contact.restitution = 0.5;
  w.contact.Derive();
  w.walls.push_back(Wall{});
  AddChain(w, 12, 32e-6);
  const std::size_t first = w.particles.size();
  AddChain(w, 12, 32e-6);
  std::mt19937 rng(5);
  std::normal_distribution<double> n(0.0, 1.0);
  for (std::size_t i = first; i < w.particles.size(); ++i) {
    // Rotate the second chain by 90 degrees about z, lift it, and cross the periodic face.
    const Vec3 x = w.particles.x[i] - Vec3(1e-4, 1e-4, 0.0);
    w.particles.x[i] = Vec3(2e-4, 0.3e-3 + x.x(), 33e-6);  // 1 um above the lower chain
    w.cell.Wrap(w.particles.x[i]);
  }
  for (std::size_t i = 0; i < w.particles.size(); ++i) {
    w.particles.x[i].z() += 17e-6;
    w.particles.v[i] = 0.05 * Vec3(n(rng), n(rng), n(rng));
    if (i >= first) w.particles.v[i].z() -= 5.0;  // the upper chain hits the lower one
  }
  // Rebuild the second chain's bond rest states from its new layout.
  for (std::size_t b = 11; b < w.bonds.size(); ++b) {
    const auto a = w.bonds.i[b], c = w.bonds.j[b];
    w.bonds.state[b] = MakeBondState(w.cell.Delta(w.particles.x[a], w.particles.x[c]),
                                     w.particles.q[a], w.particles.q[c]);
  }
  return w;
}

TEST(Determinism, SameSetupAndThreadCountGiveBitIdenticalPositions) {
  const int saved = ThreadCount();
  SetThreadCount(2);
  std::vector<Vec3> runs[2];
  std::size_t contacts = 0;
  for (auto& positions : runs) {
    World w = BusyWorld();
    Simulation sim(w);
    sim.Prepare();
    sim.Run(600);
    positions = w.particles.x;
    for (std::size_t i = 0; i < w.particles.size(); ++i)
      for (std::size_t k = w.neighbours.RowBegin(i); k < w.neighbours.RowEnd(i); ++k)
        contacts += w.neighbours.History(k).norm() > 0.0;  // touching with friction history
  }
  SetThreadCount(saved);
  EXPECT_GT(contacts, 0u);
  EXPECT_GT(runs[0][0].norm(), 0.0);
  ASSERT_EQ(runs[0].size(), runs[1].size());
  EXPECT_EQ(std::memcmp(runs[0].data(), runs[1].data(), runs[0].size() * sizeof(Vec3)), 0);
}

// Bonds breaking on impact: the steps that add the broken bonds' pairs to the rows give the
// positions of steps that build the list again after each break, bit for bit, with fewer
// builds.
TEST(Determinism, BrokenBondPairsAddedGiveTheResultsOfABuild) {
  std::vector<Vec3> runs[2];
  std::size_t builds[2] = {0, 0}, broke = 0;
  for (int run = 0; run < 2; ++run) {
    World w = BusyWorld();
    for (BeamBondParams& type : w.bonds.types) {
      type.failure = BondFailure::kHill;
      type.F_r0 = 2e-4;
      type.F_s0 = 4e-5;
      type.HillDefaults();
    }
    Simulation sim(w);
    sim.Prepare();
    for (int step = 0; step < 600; ++step) {
      const std::size_t events = w.bonds.events.size();
      sim.Step();
      if (run == 1 && w.bonds.events.size() > events)
        w.neighbours.Build(w.particles, w.cell, w.bonds, w.settings.skin);
    }
    runs[run] = w.particles.x;
    builds[run] = w.neighbours.builds();
    broke = w.bonds.events.size();
  }
  EXPECT_GT(broke, 0u);
  EXPECT_LT(builds[0], builds[1]);
  ASSERT_EQ(runs[0].size(), runs[1].size());
  EXPECT_EQ(std::memcmp(runs[0].data(), runs[1].data(), runs[0].size() * sizeof(Vec3)), 0);
}

// Preparing a simulation makes every thread of the team flush denormal results to zero
// (engine/core/float_mode.h): a product below the smallest normal double comes out as 0.
TEST(FloatMode, PrepareFlushesDenormalsToZeroOnEveryThread) {
  const int saved = ThreadCount();
  SetThreadCount(2);
  World w = ChainWorld();
  Simulation sim(w);
  sim.Prepare();
  int threads = 0, flushing = 0, zero_products = 0;
  volatile double smallest_normal = std::numeric_limits<double>::min();
#pragma omp parallel reduction(+ : threads, flushing, zero_products)
  {
    threads += 1;
    flushing += FlushesDenormals() ? 1 : 0;
    zero_products += smallest_normal * 0.25 == 0.0 ? 1 : 0;
  }
  SetThreadCount(saved);
  EXPECT_GE(threads, 1);
  EXPECT_EQ(flushing, threads);
  EXPECT_EQ(zero_products, threads);
}

// The skin only decides how often the list is built and how many pairs it checks: pairs
// beyond contact add nothing, so the trajectory is the same bit for bit.
TEST(NeighbourList, TheSkinChangesNoResultBitForBit) {
  std::vector<Vec3> positions[2];
  std::size_t builds[2] = {0, 0};
  const double skins[2] = {0.5, 2.0};
  for (int run = 0; run < 2; ++run) {
    World w = BusyWorld();
    w.settings.skin_radii = skins[run];
    Simulation sim(w);
    sim.Prepare();
    sim.Run(600);
    positions[run] = w.particles.x;
    builds[run] = w.neighbours.builds();
  }
  EXPECT_GT(builds[0], builds[1]);
  ASSERT_EQ(positions[0].size(), positions[1].size());
  EXPECT_EQ(std::memcmp(positions[0].data(), positions[1].data(),
                        positions[0].size() * sizeof(Vec3)), 0);
}

// Local damping on a linear oscillator (a free sphere on an axial bond to a pinned one). From
// an extreme at rest the force drives the motion and is cut by alpha on the way in; past the
// rest length it opposes the motion and grows by alpha on the way out. Energy then gives the
// next extreme on the other side: A1 / A0 = sqrt((1 - alpha) / (1 + alpha)). Every joule taken
// out is booked, so the ledger still balances (checked at the turning points, where the
// integrator's staggered kinetic energy does not blur it).
std::vector<double> OscillatorExtremes(double alpha, double* balance_error) {
  World w;
  w.cell.lo = Vec3(0.0, 0.0, -1e-3);
  w.cell.hi = Vec3(1e-3, 1e-3, 1e-3);
  AddChain(w, 2, 32e-6);
  w.particles.Fix(0);
  const double a0 = 0.5e-6;  // 1.6% of the bond length: linear axial range
  w.particles.x[1].x() += a0;
  w.physics.local_damping = alpha;
  w.settings.safety = 0.05;
  Simulation sim(w);
  sim.Prepare();
  const double rest_x = w.particles.x[0].x() + 32e-6;
  const double initial = MeasureEnergy(w).Accounted(w.energy);
  std::vector<double> extremes = {a0};
  double worst = 0.0;
  for (int step = 0; step < 20000 && extremes.size() < 4; ++step) {
    const double v_before = w.particles.v[1].x();
    sim.Step();
    if (v_before != 0.0 && (v_before > 0.0) != (w.particles.v[1].x() > 0.0)) {
      extremes.push_back(w.particles.x[1].x() - rest_x);
      // At a turning point, where the staggered kinetic energy of the step is near zero.
      worst = std::max(worst, std::abs(MeasureEnergy(w).Accounted(w.energy) - initial));
    }
  }
  *balance_error = worst / initial;
  return extremes;
}

TEST(LocalDamping, ExtremesDecayAsTheAnalyticRatioAndTheLedgerBalances) {
  for (double alpha : {0.0, 0.3, 0.7}) {
    double balance = 0.0;
    const std::vector<double> a = OscillatorExtremes(alpha, &balance);
    ASSERT_EQ(a.size(), 4u) << "alpha " << alpha;
    const double expected = std::sqrt((1.0 - alpha) / (1.0 + alpha));
    for (std::size_t k = 1; k < a.size(); ++k) {
      EXPECT_LT(a[k] * a[k - 1], 0.0) << "alpha " << alpha << ": extremes alternate";
      EXPECT_NEAR(std::abs(a[k] / a[k - 1]), expected, 0.02 * expected)
          << "alpha " << alpha << ", extreme " << k;
    }
    EXPECT_LT(balance, 0.01) << "alpha " << alpha;
  }
}

// Galilean invariance: a free two-sphere oscillator drifting along its axis at several times
// its peak oscillation speed. Measured against a reference moving with the drift, the damping
// sees only the oscillation: each sphere oscillates about the centre of mass, so the extremes
// of the extension decay as at rest, and the drift is untouched. Measured against rest, the
// motion never changes sign: the force pair is cut on one sphere and raised on the other, and
// the drift itself is braked.
struct DriftingOscillator {
  std::vector<double> extremes;  // extension at the turning points [m]
  double drift_end = 0.0;        // centre-of-mass velocity at the end [m/s]
};

DriftingOscillator DriftingOscillatorRun(double alpha, double drift, bool moving_reference) {
  World w;
  w.cell.lo = Vec3(0.0, 0.0, -1e-3);
  w.cell.hi = Vec3(1e-3, 1e-3, 1e-3);
  AddChain(w, 2, 32e-6);
  const double a0 = 0.5e-6;
  w.particles.x[1].x() += a0;
  for (Vec3& v : w.particles.v) v = Vec3(drift, 0.0, 0.0);
  w.physics.local_damping = alpha;
  // A field uniform over the cell: its span ends far to the left of it.
  if (moving_reference) w.damping_reference = AffineField{0, -1.0, 1e-9, drift};
  w.settings.safety = 0.05;
  Simulation sim(w);
  sim.Prepare();
  const Particles& p = w.particles;
  auto extension = [&] { return w.cell.Delta(p.x[0], p.x[1]).x() - 32e-6; };
  DriftingOscillator out;
  out.extremes = {extension()};
  for (int step = 0; step < 20000 && out.extremes.size() < 4; ++step) {
    const double rate_before = p.v[1].x() - p.v[0].x();
    sim.Step();
    const double rate = p.v[1].x() - p.v[0].x();
    if (rate_before != 0.0 && (rate_before > 0.0) != (rate > 0.0))
      out.extremes.push_back(extension());
  }
  out.drift_end = 0.5 * (p.v[0].x() + p.v[1].x());
  return out;
}

TEST(LocalDamping, AReferenceMovingWithTheSheetMakesItGalileanInvariant) {
  const double alpha = 0.7, drift = 200.0;  // the oscillation peaks near 40 m/s
  const double expected = std::sqrt((1.0 - alpha) / (1.0 + alpha));
  const DriftingOscillator moving = DriftingOscillatorRun(alpha, drift, true);
  ASSERT_EQ(moving.extremes.size(), 4u);
  for (std::size_t k = 1; k < moving.extremes.size(); ++k)
    EXPECT_NEAR(std::abs(moving.extremes[k] / moving.extremes[k - 1]), expected, 0.02 * expected)
        << "extreme " << k;
  EXPECT_NEAR(moving.drift_end, drift, 1e-9 * drift);

  const DriftingOscillator at_rest = DriftingOscillatorRun(alpha, drift, false);
  EXPECT_LT(at_rest.drift_end, 0.99 * drift) << "measured against rest, the drift is braked";
}

// An imposed stretch: the two spheres of a bonded pair fly apart at the speed of an affine
// field, and their bond brakes them. Measured against the field, the spheres lag it, so the
// bond's pull drives the motion beyond it and is cut by alpha all the way to the turn; measured
// against rest, the pull opposes the motion and is raised by alpha. Energy then puts the peak
// extensions in the ratio sqrt((1 + alpha) / (1 - alpha)).
double PeakExtensionOfAStretch(double alpha, bool against_the_field) {
  World w;
  w.cell.lo = Vec3(0.0, 0.0, -1e-3);
  w.cell.hi = Vec3(1e-3, 1e-3, 1e-3);
  AddChain(w, 2, 32e-6);
  const double speed = 1.0;  // [m/s]; the extension stays near 1e-8 m, in the linear range
  w.particles.v[0] = Vec3(-speed, 0.0, 0.0);
  w.particles.v[1] = Vec3(speed, 0.0, 0.0);
  w.physics.local_damping = alpha;
  // The field reaches +-speed at the spheres and stays uniform beyond them.
  const double centre = 0.5 * (w.particles.x[0].x() + w.particles.x[1].x());
  if (against_the_field) w.damping_reference = AffineField{0, centre, 16e-6, speed};
  w.settings.safety = 0.05;
  Simulation sim(w);
  sim.Prepare();
  const Particles& p = w.particles;
  auto extension = [&] { return w.cell.Delta(p.x[0], p.x[1]).x() - 32e-6; };
  for (int step = 0; step < 20000; ++step) {
    const double rate_before = p.v[1].x() - p.v[0].x();
    sim.Step();
    if (rate_before > 0.0 && p.v[1].x() - p.v[0].x() <= 0.0) return extension();
  }
  return 0.0;
}

TEST(LocalDamping, AnAffineReferenceLetsTheImposedStretchThrough) {
  const double alpha = 0.5;
  const double against_field = PeakExtensionOfAStretch(alpha, true);
  const double against_rest = PeakExtensionOfAStretch(alpha, false);
  ASSERT_GT(against_rest, 0.0) << "the stretch turns";
  const double expected = std::sqrt((1.0 + alpha) / (1.0 - alpha));
  EXPECT_NEAR(against_field / against_rest, expected, 0.02 * expected);
}

}  // namespace
}  // namespace fibrenet
