// The rigid blade: where a particle meets it (face, tip line, bevel), and a moving blade
// hitting a resting sphere, checked against the elastic collision with a moving wall and the
// energy balance.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "engine/core/energy.h"
#include "engine/core/simulation.h"
#include "tests/engine/one_sphere.h"

namespace fibrenet {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;

TEST(Blade, NearestPointOnFaceTipAndBevel) {
  const Blade vertical = Blade::AtAngle(Vec3(0.0, 0.0, 10e-6), 90.0 * kDegree);
  // In front of the face: distance along -x.
  Blade::Touch t = vertical.Nearest(Vec3(-20e-6, 3e-3, 50e-6));
  EXPECT_NEAR(t.gap, 20e-6, 1e-15);
  EXPECT_NEAR(t.normal.x(), -1.0, 1e-15);
  // Below and in front of the tip: the tip line is nearest.
  t = vertical.Nearest(Vec3(-3e-6, 0.0, 6e-6));
  EXPECT_NEAR(t.gap, 5e-6, 1e-15);
  EXPECT_NEAR(t.normal.z(), -0.8, 1e-12);
  // Under the bottom of a vertical blade: straight down.
  t = vertical.Nearest(Vec3(5e-6, 0.0, 4e-6));
  EXPECT_NEAR(t.gap, 6e-6, 1e-15);
  EXPECT_NEAR(t.normal.z(), -1.0, 1e-15);
  // Inside: negative.
  EXPECT_LT(vertical.Nearest(Vec3(2e-6, 0.0, 40e-6)).gap, 0.0);
  // A face leaning over the sheet (80 degrees): the distance to the tilted plane.
  const Blade leaning = Blade::AtAngle(Vec3::Zero(), 80.0 * kDegree);
  const Vec3 x = 30e-6 * leaning.face_up + 7e-6 * leaning.face_normal;
  t = leaning.Nearest(x);
  EXPECT_NEAR(t.gap, 7e-6, 1e-15);
  EXPECT_NEAR(t.normal.dot(leaning.face_normal), 1.0, 1e-15);
}

// One sphere at rest in front of a vertical blade that moves towards it at speed V.
TEST(Blade, MovingBladeThrowsARestingSphereAtTwiceItsSpeedAndTheWorkBalances) {
  const double V = 30.0, R = 16e-6;
  // Elastic contacts (restitution 1): the sphere leaves at 2 V.
  World w = OneSphere(Vec3(0.0, 0.1e-3, 100e-6), R, 8e-12, 1.0, 1e-3, 0.2e-3);
  Blade blade = Blade::AtAngle(Vec3(R + 1e-6, 0.0, 0.0), 90.0 * kDegree);
  blade.velocity = Vec3(-V, 0.0, 0.0);
  blade.friction = false;
  w.blades.push_back(blade);
  Simulation sim(w);
  sim.Prepare();
  const double before = MeasureEnergy(w).Accounted(w.energy);
  double peak = 0.0;
  for (int k = 0; k < 40000 && w.blades[0].tip.x() - w.particles.x[0].x() < 3.0 * R; ++k) {
    sim.Step();
    peak = std::max(peak, w.blades[0].reaction.x());
  }
  EXPECT_GT(peak, 0.0);
  EXPECT_NEAR(w.particles.v[0].x(), -2.0 * V, 0.01 * V);
  EXPECT_NEAR(w.particles.v[0].z(), 0.0, 1e-9);
  // The blade's work is the sphere's kinetic energy, 2 m V^2.
  EXPECT_NEAR(w.blades[0].work, 2.0 * 8e-12 * V * V, 0.02 * 2.0 * 8e-12 * V * V);
  const double after = MeasureEnergy(w).Accounted(w.energy);
  EXPECT_NEAR(after, before, 1e-3 * w.blades[0].work);
}

// The tangential reaction of a sphere held against a blade face that slides past it, over
// the normal reaction: the Coulomb coefficient, the blade's own where it has one.
double SlidingFrictionRatio(std::optional<double> blade_mu) {
  const double R = 16e-6, load = 1e-5;
  World w = OneSphere(Vec3(0.0, 0.1e-3, 0.0), R, 8e-10, 0.5, 1e-3, 0.2e-3);
  w.physics.friction = true;
  w.physics.applied_loads = true;
  w.contact.mu = 0.3;
  w.particles.inv_inertia[0] = 0.0;  // no rolling: the contact slides throughout
  // A vertical face just touching the sphere, sliding past it along its tip line at 3 m/s;
  // the load presses the sphere onto it, and the sphere, a hundred times the generic
  // particle's mass, stays far from catching up with the face (it would stick).
  Blade blade = Blade::AtAngle(Vec3(R, 0.0, -10.0 * R), 90.0 * kDegree);
  blade.velocity = Vec3(0.0, 3.0, 0.0);
  blade.mu = blade_mu;
  w.blades.push_back(blade);
  w.applied_force.assign(1, Vec3(load, 0.0, 0.0));
  w.applied_torque.assign(1, Vec3::Zero());
  Simulation sim(w);
  sim.Prepare();
  for (int k = 0; k < 2000; ++k) sim.Step();
  const Vec3 reaction = w.blades[0].reaction;
  EXPECT_GT(reaction.x(), 0.5 * load);  // still pressed on the face
  return -reaction.y() / reaction.x();  // the face drags the sphere along, the sphere holds it back
}

TEST(Blade, ASlidingContactCarriesTheBladesOwnFrictionCoefficient) {
  EXPECT_NEAR(SlidingFrictionRatio(std::nullopt), 0.3, 1e-9);  // the contacts' mu
  EXPECT_NEAR(SlidingFrictionRatio(0.8), 0.8, 1e-9);
  EXPECT_NEAR(SlidingFrictionRatio(0.0), 0.0, 1e-12);
}

}  // namespace
}  // namespace fibrenet
