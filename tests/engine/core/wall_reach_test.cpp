// The particles a wall checks (WallReach, engine/core/forces.cpp): every particle that touches
// a wall is among them at every step, a wall or a particle that jumps is found again, and
// checking them gives the forces of checking every particle, bit for bit.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/parallel.h"
#include "engine/core/simulation.h"
#include "engine/core/time_step.h"

namespace fibrenet {
namespace {

constexpr double kRadius = 16e-6, kMass = 8e-12;

// side x side spheres on a square lattice in x and y, 3 radii apart so that their slight
// sideways drift never brings two together, at random heights between a floor (z = 0) and a
// top platen (z = height) that comes down; they fly up and down at random, with friction on
// the walls.
World GasBetweenPlatens(int side, double height) {
  World w;
  const double spacing = 3.0 * kRadius, width = side * spacing;
  w.cell.lo = Vec3(0.0, 0.0, -1e-3);
  w.cell.hi = Vec3(width, width, 1e-3);
  w.cell.periodic_x = w.cell.periodic_y = true;
  w.physics.friction = true;
  w.contact.restitution = 0.5;
  w.contact.Derive();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int a = 0; a < side; ++a) {
    for (int b = 0; b < side; ++b) {
      const Vec3 x((a + 0.5) * spacing, (b + 0.5) * spacing,
                   kRadius + (height - 2.0 * kRadius) * u(rng));
      const std::size_t i = w.particles.Add(x, kRadius, kMass, a * side + b);
      w.particles.v[i] = Vec3(0.2 * (u(rng) - 0.5), 0.2 * (u(rng) - 0.5), 20.0 * (u(rng) - 0.5));
    }
  }
  Wall floor, top;
  top.z = height;
  top.side = -1;
  top.vz = -2.0;
  w.walls = {floor, top};
  return w;
}

// Centre-to-wall gap of particle i.
double Gap(const World& w, const Wall& wall, std::size_t i) {
  return (w.particles.x[i].z() - wall.z) * wall.side;
}

bool InReach(const Wall& wall, std::size_t i) {
  return std::binary_search(wall.reach.particles.begin(), wall.reach.particles.end(),
                            static_cast<std::int32_t>(i));
}

TEST(WallReach, EveryParticleThatTouchesAWallIsInItsReach) {
  World w = GasBetweenPlatens(24, 8.0 * kRadius);
  w.physics.contacts = true;
  Simulation sim(w);
  sim.Prepare();
  const std::size_t n = w.particles.size();
  std::size_t touches = 0, largest_reach = 0;
  for (int step = 0; step < 2000; ++step) {
    // The step's forces come from the positions before it; its reach is the one it used.
    const std::vector<Vec3> x = w.particles.x;
    const double z[2] = {w.walls[0].z, w.walls[1].z};
    sim.Step();
    for (int side = 0; side < 2; ++side) {
      const Wall& wall = w.walls[side];
      ASSERT_NE(wall.reach.list_build, 0u);
      largest_reach = std::max(largest_reach, wall.reach.particles.size());
      for (std::size_t i = 0; i < n; ++i) {
        if ((x[i].z() - z[side]) * wall.side >= kRadius) continue;
        ++touches;
        ASSERT_TRUE(InReach(wall, i)) << "particle " << i << " touches wall " << side
                                      << " at step " << step << " outside its reach";
      }
    }
  }
  EXPECT_GT(touches, 1000u);
  EXPECT_GT(w.neighbours.builds(), 10u);
  EXPECT_LT(largest_reach, n / 2);  // the reach is a part of the particles, not all of them
}

// A lone sphere 3 skins beyond touching a top platen, at rest, after one step: outside the
// platen's reach.
class WallReachOfALoneSphere : public ::testing::Test {
 protected:
  void SetUp() override {
    w.cell.lo = Vec3(0.0, 0.0, -1e-3);
    w.cell.hi = Vec3(1e-3, 1e-3, 1e-3);
    w.physics.contacts = true;
    w.particles.Add(Vec3(5e-4, 5e-4, 0.0), kRadius, kMass, 0);
    Wall top;
    top.side = -1;
    top.z = kRadius + 3.0 * 0.5 * kRadius;  // skin: 0.5 radii
    w.walls = {top};
    sim.Prepare();
    sim.Step();
    ASSERT_FALSE(InReach(w.walls[0], 0));
    builds = w.neighbours.builds();
  }

  World w;
  Simulation sim{w};
  std::size_t builds = 0;
};

TEST_F(WallReachOfALoneSphere, AWallThatJumpsNearerFindsItsReachAgain) {
  w.walls[0].z = 0.8 * kRadius;  // the platen jumps into the sphere
  sim.Step();
  EXPECT_EQ(w.neighbours.builds(), builds);  // the sphere has not moved: no build
  EXPECT_TRUE(InReach(w.walls[0], 0));
  EXPECT_LT(w.particles.v[0].z(), 0.0);  // pushed down
  EXPECT_GT(w.walls[0].reaction.z(), 0.0);
}

TEST_F(WallReachOfALoneSphere, AParticleThatJumpsIntoAWallIsFound) {
  w.particles.x[0].z() = w.walls[0].z - 0.8 * kRadius;  // the sphere jumps into the platen
  sim.Step();
  EXPECT_GT(w.neighbours.builds(), builds);
  EXPECT_TRUE(InReach(w.walls[0], 0));
  EXPECT_LT(w.particles.v[0].z(), 0.0);
}

// Without contacts there is no neighbour list, and the walls check every particle. The
// lattice keeps the spheres apart, so contacts add nothing: the two runs differ only in the
// particles the walls check, on two threads (above kParallelMinParticles).
TEST(WallReach, CheckingTheReachGivesTheForcesOfCheckingEveryParticleBitForBit) {
  const int saved = ThreadCount();
  SetThreadCount(2);
  World runs[2] = {GasBetweenPlatens(72, 8.0 * kRadius), GasBetweenPlatens(72, 8.0 * kRadius)};
  ASSERT_GE(runs[0].particles.size(), kParallelMinParticles);
  runs[1].physics.contacts = true;
  const double dt = 0.5 * CriticalTimeStep(runs[1]).dt_crit;
  std::size_t touching = 0;
  for (World& w : runs) {
    w.settings.dt = dt;
    Simulation sim(w);
    sim.Prepare();
    for (int step = 0; step < 400; ++step) {
      sim.Step();
      for (const Wall& wall : w.walls)
        for (std::size_t i = 0; i < w.particles.size(); ++i)
          touching += Gap(w, wall, i) < kRadius ? 1 : 0;
    }
  }
  SetThreadCount(saved);
  EXPECT_GT(touching, 1000u);
  EXPECT_EQ(runs[0].walls[1].reach.list_build, 0u);
  EXPECT_NE(runs[1].walls[1].reach.list_build, 0u);
  const std::vector<Vec3>& a = runs[0].particles.x;
  const std::vector<Vec3>& b = runs[1].particles.x;
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)), 0);
  for (int side = 0; side < 2; ++side) {
    EXPECT_EQ(runs[0].walls[side].reaction, runs[1].walls[side].reaction);
    EXPECT_EQ(runs[0].walls[side].work, runs[1].walls[side].work);
  }
  EXPECT_EQ(runs[0].energy.friction, runs[1].energy.friction);
}

}  // namespace
}  // namespace fibrenet
