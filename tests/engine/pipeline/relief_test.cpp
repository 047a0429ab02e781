// Patterned walls: the relief patterns have the heights they promise, and a sphere resting
// on a patterned floor sits exactly one pocket depth lower than on a flat floor.
#include "engine/pipeline/relief_pattern.h"

#include <gtest/gtest.h>

#include "engine/core/simulation.h"

namespace fibrenet::pipeline {
namespace {

Cell SquareCell(double side) {
  Cell c;
  c.lo = Vec3(0, 0, -1e-3);
  c.hi = Vec3(side, side, 1e-3);
  c.periodic_x = c.periodic_y = true;
  return c;
}

ReliefPattern Dots() {
  ReliefPattern p;
  p.pitch = 250e-6;
  p.size = 200e-6;
  p.height = 40e-6;
  p.flank = 20e-6;
  return p;
}

TEST(Relief, DotsHaveTheirHeightAtTheCentreAndNoneBetween) {
  // 0.6 mm holds 2.4 pitches of 250 um: the period is fitted to 300 um (2 per side).
  const auto relief = MakeRelief(Dots(), SquareCell(0.6e-3), +1.0);
  EXPECT_DOUBLE_EQ(relief->period_x, 0.3e-3);
  EXPECT_DOUBLE_EQ(relief->period_y, 0.3e-3);
  EXPECT_NEAR(relief->At(0.15e-3, 0.15e-3), 40e-6, 1e-12);       // dot centre
  EXPECT_NEAR(relief->At(0.15e-3 + 80e-6, 0.15e-3), 40e-6, 1e-12);  // still on the flat top
  EXPECT_NEAR(relief->At(0.0, 0.0), 0.0, 1e-12);                  // between dots
  EXPECT_NEAR(relief->At(0.15e-3 + 0.3e-3, 0.15e-3 - 0.6e-3), 40e-6, 1e-12);  // periodic
  // Half height in the middle of the flank (cosine flank, sampled finely).
  EXPECT_NEAR(relief->At(0.15e-3 + 100e-6, 0.15e-3), 20e-6, 0.5e-6);
  // Pockets are the same pattern below the wall.
  const auto pockets = MakeRelief(Dots(), SquareCell(0.6e-3), -1.0);
  EXPECT_NEAR(pockets->At(0.15e-3, 0.15e-3), -40e-6, 1e-12);
  EXPECT_NEAR(ReliefLevel(*pockets, 0.15e-3, 0.15e-3), 1.0, 1e-12);
}

TEST(Relief, LinesRunAlongX) {
  ReliefPattern p = Dots();
  p.shape = ReliefShape::kLines;
  const auto relief = MakeRelief(p, SquareCell(0.6e-3), +1.0);
  for (double x : {0.0, 0.1e-3, 0.37e-3, 0.59e-3}) {
    EXPECT_NEAR(relief->At(x, 0.15e-3), 40e-6, 1e-12);
    EXPECT_NEAR(relief->At(x, 0.0), 0.0, 1e-12);
  }
}

// Height at which a sphere comes to rest under gravity on the floor at z = 0.
double RestHeight(std::shared_ptr<const Relief> relief) {
  World w;
  w.cell = SquareCell(0.6e-3);
  w.physics.gravity = true;
  w.physics.g = Vec3(0, 0, -1e3);
  w.physics.drag = true;
  w.physics.drag_coefficient = 1e-9 / 1e-5;  // relaxation time 10 us
  w.contact.restitution = 0.3;
  w.contact.Derive();
  w.particles.Add(Vec3(0.15e-3, 0.15e-3, 30e-6), 16e-6, 1e-9, 0);
  Wall floor;
  floor.relief = std::move(relief);
  w.walls.push_back(floor);
  Simulation sim(w);
  sim.Prepare();
  sim.Run(200000);
  EXPECT_LT(w.particles.v[0].norm(), 1e-6);
  return w.particles.x[0].z();
}

TEST(Relief, SphereRestsOnePocketDepthLowerOverAPocket) {
  const double flat = RestHeight(nullptr);
  const double pocket = RestHeight(MakeRelief(Dots(), SquareCell(0.6e-3), -1.0));
  EXPECT_LT(flat, 16e-6);  // the weight makes an overlap
  EXPECT_NEAR(pocket - flat, -40e-6, 1e-12);
}

}  // namespace
}  // namespace fibrenet::pipeline
