// The Yankee coating's glue bond (glue.h) against the damped oscillator: a particle on its glue
// to a fixed anchor, set moving along the bond, rings at sqrt(k_n / m) sqrt(1 - zeta^2) and
// each period takes its swing down by exp(-2 pi zeta / sqrt(1 - zeta^2)); the energy its
// dashpot takes out is booked.
#include "engine/pipeline/glue.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "engine/core/energy.h"
#include "engine/core/simulation.h"

namespace fibrenet::pipeline {
namespace {

constexpr double kRadius = 16e-6, kDensity = 1500.0, kSpeed = 0.1;

struct Ringing {
  std::vector<double> peak_times, peaks;  // the particle's height above rest at its maxima
  double k_n = 0.0, mass = 0.0;
  double accounted_start = 0.0, accounted_end = 0.0, dissipated = 0.0;
};

// The glued particle (at height R, its anchor at -R) set moving up at kSpeed, followed over
// `periods` undamped periods at 400 steps a period. Its glue type is sized for a particle of
// kRadius and kDensity; the particle itself is `heavier` times that mass, its bond's factors
// fitting the dashpots to it.
Ringing Ring(double zeta, int periods, double heavier = 1.0) {
  World w;
  w.cell.lo = Vec3(-1e-3, -1e-3, -1e-3);
  w.cell.hi = Vec3(1e-3, 1e-3, 1e-3);
  w.cell.periodic_x = w.cell.periodic_y = false;
  Particles& p = w.particles;
  const double type_mass = kDensity * 4.0 / 3.0 * kPi * std::pow(kRadius, 3);
  const double type_inertia = 0.4 * type_mass * kRadius * kRadius, mass = heavier * type_mass;
  const std::size_t sheet = p.Add(Vec3(0.0, 0.0, kRadius), kRadius, mass, 0);
  const std::size_t anchor = p.Add(Vec3(0.0, 0.0, -kRadius), kRadius, mass, -1);
  p.Fix(anchor);
  AdhesionSettings a;
  a.damping_ratio = zeta;
  a.F_r0 = a.F_s0 = 1.0;  // far above what the swing loads it with: the glue holds
  const BeamBondParams glue = GlueBond(a, kRadius, type_mass, type_inertia, 1.0);
  w.bonds.Add(0, 1, w.bonds.AddType(glue), BondKind::kAdhesive,
              MakeBondState(p.x[anchor] - p.x[sheet], p.q[sheet], p.q[anchor]));
  w.bonds.damping_factors = {GlueDampingFactors(mass, p.inertia[sheet], type_mass, type_inertia)};
  p.v[sheet] = Vec3(0.0, 0.0, kSpeed);
  const double omega = std::sqrt(glue.k_n / mass), period = 2.0 * kPi / omega;
  w.settings.dt = period / 400.0;

  Ringing r;
  r.k_n = glue.k_n;
  r.mass = mass;
  Simulation sim(w);
  sim.Prepare();
  r.accounted_start = MeasureEnergy(w).Accounted(w.energy);
  double before = 0.0, now = p.x[sheet].z() - kRadius;
  for (int step = 0; step < 400 * periods; ++step) {
    sim.Step();
    const double next = p.x[sheet].z() - kRadius;
    if (now > before && now >= next && now > 0.0) {
      r.peak_times.push_back(w.time - w.settings.dt);
      r.peaks.push_back(now);
    }
    before = now;
    now = next;
  }
  r.accounted_end = MeasureEnergy(w).Accounted(w.energy);
  r.dissipated = w.energy.Dissipated();
  return r;
}

TEST(Glue, AGluedParticleRingsDownAsADampedOscillator) {
  for (double zeta : {0.05, 0.2}) {
    const Ringing r = Ring(zeta, 6);
    ASSERT_GE(r.peaks.size(), 4u) << "zeta " << zeta;
    const double root = std::sqrt(1.0 - zeta * zeta);
    const double decrement = std::log(r.peaks[1] / r.peaks[3]) / 2.0;
    EXPECT_NEAR(decrement, 2.0 * kPi * zeta / root, 0.01 * 2.0 * kPi * zeta / root)
        << "zeta " << zeta;
    const double period = (r.peak_times[3] - r.peak_times[1]) / 2.0;
    const double damped_period = 2.0 * kPi / (std::sqrt(r.k_n / r.mass) * root);
    EXPECT_NEAR(period, damped_period, 0.01 * damped_period) << "zeta " << zeta;
    // What the swing lost, the ledger booked as dissipated.
    const double start_kinetic = 0.5 * r.mass * kSpeed * kSpeed;
    EXPECT_GT(r.dissipated, 0.5 * start_kinetic) << "zeta " << zeta;
    EXPECT_NEAR(r.accounted_end, r.accounted_start, 0.01 * start_kinetic) << "zeta " << zeta;
  }
}

// Particles of one radius share a glue type but not a mass: the bond's factors keep a particle
// twice as heavy as the one the type was sized for at the same fraction of critical (without
// them it would ring at zeta / sqrt(2)).
TEST(Glue, AHeavierParticleOnTheSameGlueTypeRingsDownAtTheSameRatio) {
  const double zeta = 0.2;
  const Ringing r = Ring(zeta, 6, 2.0);
  ASSERT_GE(r.peaks.size(), 4u);
  const double root = std::sqrt(1.0 - zeta * zeta);
  const double decrement = std::log(r.peaks[1] / r.peaks[3]) / 2.0;
  EXPECT_NEAR(decrement, 2.0 * kPi * zeta / root, 0.01 * 2.0 * kPi * zeta / root);
}

TEST(Glue, WithoutDampingTheSwingKeepsItsSize) {
  const Ringing r = Ring(0.0, 6);
  ASSERT_GE(r.peaks.size(), 5u);
  const double omega = std::sqrt(r.k_n / r.mass);
  for (double peak : r.peaks) EXPECT_NEAR(peak, kSpeed / omega, 0.01 * kSpeed / omega);
  EXPECT_EQ(r.dissipated, 0.0);
}

TEST(Glue, ADampingRatioOutsideZeroToOneIsRefused) {
  AdhesionSettings a;
  a.damping_ratio = 1.5;
  EXPECT_NE(a.Validate().find("damping_ratio"), std::string::npos);
  a.damping_ratio = -0.1;
  EXPECT_NE(a.Validate().find("damping_ratio"), std::string::npos);
  a.damping_ratio = 1.0;
  EXPECT_EQ(a.Validate(), "");
}

}  // namespace
}  // namespace fibrenet::pipeline
