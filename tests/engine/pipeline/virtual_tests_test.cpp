// The virtual-test rig on strips whose answer is known in closed form: parallel straight
// fibres along the load (tensile stiffness n E A / W, pure-bending stiffness n E I / W), plus
// the bookkeeping (Gini, top share, CSV curves), the settings' messages, and the quasi-static
// dashpots against a ringing pair's logarithmic decrement.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <algorithm>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/core/quaternion.h"
#include "engine/core/simulation.h"
#include "engine/core/time_step.h"
#include "engine/pipeline/compression_test.h"
#include "engine/pipeline/curves.h"
#include "engine/pipeline/sheet_bending.h"
#include "engine/pipeline/softness.h"
#include "engine/pipeline/strain_energy.h"
#include "engine/pipeline/tensile_test.h"
#include "engine/pipeline/test_rig.h"

namespace fibrenet::pipeline {
namespace {

constexpr double kD = 20e-6, kE = 10e9, kG = 3e9;

FibreProperties StraightFibre(double length) {
  FibreProperties f;
  f.length = length;
  f.diameter = kD;
  f.coarseness = 1e-7;
  f.youngs_modulus = kE;
  f.shear_modulus = kG;
  f.strength = 1e9;
  return f;
}

// `count` straight fibres of 0.9 Lx along x (or along y when along_y) at z = 0, evenly spaced
// across; no bonds between them. Particles one diameter apart.
Network ParallelFibres(int count, bool along_y = false) {
  Network net;
  World& w = net.world;
  const double L = 1.0e-3, W = 0.2e-3;
  w.cell.lo = Vec3(0.0, 0.0, -1e-3);
  w.cell.hi = along_y ? Vec3(W, L, 1e-3) : Vec3(L, W, 1e-3);
  const FibreProperties f = StraightFibre(0.9 * L);
  const int n = 45;
  for (int k = 0; k < count; ++k) {
    std::vector<Vec3> x;
    for (int m = 0; m < n; ++m) {
      const double along = 0.05 * L + (m + 0.5) * f.length / n, across = (k + 0.5) * W / count;
      x.push_back(along_y ? Vec3(across, along, 0.0) : Vec3(along, across, 0.0));
    }
    net.AddFibre(f, x, FibreBondOptions{});
  }
  return net;
}

TensileSettings SmallStrainTensile() {
  TensileSettings s;
  s.max_strain = 0.001;
  s.switches.bond_failure = false;
  s.quasi_static.loading_steps = 2000;
  s.samples = 50;
  return s;
}

TEST(Bookkeeping, GiniAndTopShare) {
  EXPECT_NEAR(Gini({1.0, 1.0, 1.0, 1.0}), 0.0, 1e-12);
  EXPECT_NEAR(Gini({0.0, 0.0, 0.0, 1.0}), 0.75, 1e-12);  // (n - 1) / n
  EXPECT_NEAR(Gini({1.0, 2.0, 3.0}), 2.0 / 9.0, 1e-12);
  EXPECT_NEAR(Gini({}), 0.0, 0.0);
  std::vector<double> v;
  for (int k = 1; k <= 10; ++k) v.push_back(k);
  EXPECT_NEAR(TopShare(v, 0.1), 10.0 / 55.0, 1e-12);
  EXPECT_NEAR(TopShare(v, 0.25), (10.0 + 9.0 + 8.0) / 55.0, 1e-12);  // ceil(2.5) = 3
}

TEST(Bookkeeping, CurvesWriteCsvOnlyWhenGivenADirectory) {
  Curve c{"demo", {"strain", "stress_N_per_m"}, {}};
  c.Add({0.0, 0.0});
  c.Add({0.5, 1.25});
  EXPECT_TRUE(WriteCurves({c}, "").empty());
  const auto dir = std::filesystem::temp_directory_path() / "fibrenet_curves_test";
  std::filesystem::remove_all(dir);
  const auto paths = WriteCurves({c}, dir.string(), "md_");
  ASSERT_EQ(paths.size(), 1u);
  std::ifstream in(paths[0]);
  std::string header, first, second;
  std::getline(in, header);
  std::getline(in, first);
  std::getline(in, second);
  EXPECT_EQ(header, "strain,stress_N_per_m");
  EXPECT_EQ(first, "0,0");
  EXPECT_EQ(second, "0.5,1.25");
  EXPECT_EQ(c.Values("stress_N_per_m")[1], 1.25);
  EXPECT_THROW(c.Column("nope"), Error);
  std::filesystem::remove_all(dir);
}

TEST(Settings, MessagesNameTheKeyAndTheRange) {
  TensileSettings t;
  t.max_strain = 5.0;
  EXPECT_NE(t.Validate().find("max_strain"), std::string::npos);
  EXPECT_NE(t.Validate().find("(0, 2]"), std::string::npos);
  t = TensileSettings{};
  t.cycle_strains = {0.05, 0.02};
  EXPECT_NE(t.Validate().find("cycle_strains"), std::string::npos);
  t = TensileSettings{};
  t.quasi_static.kinetic_work_tolerance = 0.0;
  EXPECT_NE(t.Validate().find("kinetic_work_tolerance"), std::string::npos);
  CompressionSettings c;
  c.max_strain = 0.99;
  EXPECT_NE(c.Validate().find("max_strain"), std::string::npos);
  c = CompressionSettings{};
  c.min_speed_fraction = 0.0;
  EXPECT_NE(c.Validate().find("min_speed_fraction"), std::string::npos);
  c = CompressionSettings{};
  c.toe_kinetic_share = 1.5;
  EXPECT_NE(c.Validate().find("toe_kinetic_share"), std::string::npos);
  BendingSettings b;
  b.levels = 1;
  EXPECT_NE(b.Validate().find("levels"), std::string::npos);
  SoftnessSettings s;
  s.grid_pitch = 0.0;
  EXPECT_NE(s.Validate().find("grid_pitch"), std::string::npos);
  t = TensileSettings{};
  t.strain_rate = -1.0;
  EXPECT_THROW(RunTensileTest(ParallelFibres(2), t), InputError);
}

// Two free bonded pairs, one eight times lighter than the other, ringing in stretch and twist.
struct RingingPairs {
  World w;
  double L0 = 0.0;
};
RingingPairs MakeRingingPairs() {
  RingingPairs r;
  World& w = r.w;
  w.cell.lo = Vec3(-1e-3, -1e-3, -1e-3);
  w.cell.hi = Vec3(1e-3, 1e-3, 1e-3);
  const std::int32_t type = w.bonds.AddType(BeamBondParams::FromBeam(kE, kG, 0.5 * kD, kD));
  r.L0 = kD;
  for (int pair = 0; pair < 2; ++pair) {
    const double m = pair == 0 ? 1e-12 : 0.125e-12, y = 200e-6 * pair;
    const auto i = static_cast<std::int32_t>(w.particles.Add(Vec3(0, y, 0), 0.5 * kD, m, pair));
    const auto j = static_cast<std::int32_t>(w.particles.Add(Vec3(kD, y, 0), 0.5 * kD, m, pair));
    w.bonds.Add(i, j, type, BondKind::kFibre,
                MakeBondState(Vec3(kD, 0, 0), w.particles.q[i], w.particles.q[j]));
    // Stretching and twisting apart.
    w.particles.v[i] = Vec3(-1e-3, 0, 0), w.particles.v[j] = Vec3(1e-3, 0, 0);
    w.particles.omega[i] = Vec3(-10, 0, 0), w.particles.omega[j] = Vec3(10, 0, 0);
  }
  return r;
}

// The damping ratio of a free ringing from its logarithmic decrement over `periods` periods:
// the first and the last of periods + 1 successive peaks of `amplitude`.
double RingingDampingRatio(const std::vector<double>& amplitude, int periods) {
  std::vector<double> peaks;
  for (std::size_t k = 1; k + 1 < amplitude.size() && peaks.size() <= std::size_t(periods); ++k)
    if (amplitude[k] > amplitude[k - 1] && amplitude[k] >= amplitude[k + 1])
      peaks.push_back(amplitude[k]);
  if (peaks.size() <= std::size_t(periods)) return 0.0;
  const double delta = std::log(peaks.front() / peaks.back()) / periods;
  return delta / std::sqrt(4.0 * kPi * kPi + delta * delta);
}

// The quasi-static dashpots damp each bond at the set fraction of its own critical damping:
// a pair eight times lighter than another rings down at the same ratio in stretch (its
// logarithmic decrement), and in twist at the ratio that the type's rotational dashpot
// gives (sized on the stiffer of bending and twist).
TEST(QuasiStaticDamping, EachBondIsDampedAtTheRatioOfItsOwnPair) {
  RingingPairs pairs = MakeRingingPairs();
  World& w = pairs.w;
  const double ratio = 0.1;
  AddBondDamping(w, ratio);
  w.settings.safety = 0.05;  // peaks sampled finely enough to read their heights
  Simulation sim(w);
  sim.Prepare();
  std::vector<double> stretch[2], twist[2];
  for (int step = 0; step < 20000; ++step) {
    sim.Step();
    for (int pair = 0; pair < 2; ++pair) {
      const Particles& p = w.particles;
      const int i = 2 * pair, j = i + 1;
      stretch[pair].push_back((p.x[j] - p.x[i]).norm() - pairs.L0);
      twist[pair].push_back(RotationVector(p.q[i].conjugate() * p.q[j]).x());
    }
  }
  const BeamBondParams& type = w.bonds.types[0];
  const double twist_ratio = ratio * std::sqrt(std::max(type.k_b, type.k_t) / type.k_t);
  for (int pair = 0; pair < 2; ++pair) {
    const double zeta = RingingDampingRatio(stretch[pair], 3);
    const double zeta_twist = RingingDampingRatio(twist[pair], 3);
    std::printf("pair %d: stretch %.4f (set %.4f), twist %.4f (set %.4f)\n", pair, zeta, ratio,
                zeta_twist, twist_ratio);
    EXPECT_NEAR(zeta / ratio, 1.0, 0.05) << "pair " << pair;
    EXPECT_NEAR(zeta_twist / twist_ratio, 1.0, 0.05) << "pair " << pair;
  }
}

// Dashpots at critical damping, with the time step's safety at 0.9: the step keeps below the
// damped stability limit, and the pairs come to rest (the step at 0.9 of the undamped limit
// blew up at step 28). At the quasi-static ratio 0.1 and the default safety 0.5 the dashpots
// do not bind: the step stays half the critical one.
TEST(QuasiStaticDamping, CriticalDashpotsStayStableAtALargeSafety) {
  RingingPairs pairs = MakeRingingPairs();
  World& w = pairs.w;
  AddBondDamping(w, 1.0);
  w.settings.safety = 0.9;
  Simulation sim(w);
  sim.Prepare();
  const TimeStepInfo info = CriticalTimeStep(w);
  EXPECT_LT(w.settings.dt, 0.9 * info.dt_crit);
  EXPECT_EQ(w.settings.dt, info.dt_damped);
  std::printf("critical dashpots: dt = %.3f dt_crit, limited by %s\n", w.settings.dt / info.dt_crit,
              info.damped_limited_by.c_str());
  // The largest stretch of the lighter pair over the first and the last 100 steps.
  double first = 0.0, last = 0.0;
  for (int step = 0; step < 2000; ++step) {
    ASSERT_NO_THROW(sim.Step()) << "step " << step;
    const double stretch = std::abs((w.particles.x[3] - w.particles.x[2]).norm() - pairs.L0);
    if (step < 100) first = std::max(first, stretch);
    if (step >= 1900) last = std::max(last, stretch);
  }
  EXPECT_LT(last, 1e-3 * first);

  RingingPairs gentle = MakeRingingPairs();
  AddBondDamping(gentle.w, 0.1);
  Simulation gentle_sim(gentle.w);
  gentle_sim.Prepare();
  EXPECT_EQ(gentle.w.settings.dt, 0.5 * CriticalTimeStep(gentle.w).dt_crit);
}

// n E A / W: the grips hold each fibre at both ends and the free span is the chain between
// them, so the strip is exactly n springs of stiffness E A / span in parallel.
TEST(TensileTest, ParallelFibresGiveTheExactStripStiffness) {
  const int n = 5;
  const Network net = ParallelFibres(n);
  const TensileResult r = RunTensileTest(net, SmallStrainTensile());
  const double A = kPi * kD * kD / 4.0, W = net.world.cell.Ly();
  EXPECT_NEAR(r.Value("tensile_modulus_N_per_m") / (n * kE * A / W), 1.0, 0.01);
  EXPECT_NEAR(r.Value("energy_share_normal"), 1.0, 1e-3);
  EXPECT_NEAR(r.Value("strain_energy_gini"), 0.0, 0.02);
  EXPECT_NEAR(r.Value("strain_energy_top10_share"), 1.0 / n, 0.01);
  EXPECT_NEAR(r.Value("tensile_lateral_stress_ratio"), 0.0, 0.01);
  EXPECT_TRUE(r.quasi_static) << (r.warnings.empty() ? "" : r.warnings[0]);
  EXPECT_LT(r.Value("tensile_kinetic_work_ratio"), 0.01);
  // TEA of a linear curve: strength * strain / 2.
  EXPECT_NEAR(r.Value("tea_J_per_m2"),
              0.5 * r.Value("tensile_strength_N_per_m") * r.Value("strain_at_break"),
              0.02 * r.Value("tea_J_per_m2"));
  EXPECT_EQ(r.curve.name, "tensile_md");
}

// A strip that comes open along x (a creped strip) with a loose fibre trailing from one end:
// the clamps close where the strip is whole, so the loose fibre does not hold the strip.
TEST(TensileTest, AnOpenStripIsGrippedWhereItIsWholeNotByALooseEnd) {
  const int n = 4;
  Network net = ParallelFibres(n);
  World& w = net.world;
  w.cell.periodic_x = false;
  w.cell.hi.x() = 1.6e-3;
  std::vector<Vec3> loose;
  for (int m = 0; m < 25; ++m) loose.push_back(Vec3(0.97e-3 + m * kD, 0.5 * w.cell.Ly(), 0.0));
  net.AddFibre(StraightFibre(25 * kD), loose, FibreBondOptions{});
  const double first = 0.05e-3 + 0.5 * kD, last = 0.95e-3 - 0.5 * kD;  // the strip's centres
  const StripEnds ends = FindStripEnds(w);
  EXPECT_NEAR(ends.lo, first, 1e-12);
  EXPECT_GE(ends.hi, last);
  EXPECT_LE(ends.hi, last + 2.0 * kD + 1e-12);  // within one bin of two diameters
  // The ends are particle centres, not the edges of the bins.
  const Particles& p = w.particles;
  EXPECT_TRUE(std::any_of(p.x.begin(), p.x.end(), [&](const Vec3& x) { return x.x() == ends.hi; }));
  EXPECT_NEAR(ends.length, ends.hi - ends.lo, 1e-15);
  // Clamped at its outermost centres, the right grip would hold the loose fibre alone.
  const TensileResult r = RunTensileTest(net, SmallStrainTensile());
  const double A = kPi * kD * kD / 4.0, W = w.cell.Ly();
  EXPECT_NEAR(r.Value("tensile_modulus_N_per_m") / (n * kE * A / W), 1.0, 0.01);
  // A periodic sheet's ends are its outermost centres and its length the cell's.
  const StripEnds periodic = FindStripEnds(ParallelFibres(n).world);
  EXPECT_NEAR(periodic.lo, first, 1e-12);
  EXPECT_NEAR(periodic.hi, last, 1e-12);
  EXPECT_EQ(periodic.length, 1e-3);
}

TEST(TensileTest, CrossDirectionTurnsTheSheet) {
  const int n = 5;
  const Network net = ParallelFibres(n, /*along_y=*/true);
  TensileSettings s = SmallStrainTensile();
  s.axis = LoadAxis::kCD;
  const TensileResult cd = RunTensileTest(net, s);
  const double A = kPi * kD * kD / 4.0, W = net.world.cell.Lx();
  EXPECT_NEAR(cd.Value("tensile_modulus_N_per_m") / (n * kE * A / W), 1.0, 0.01);
  EXPECT_EQ(cd.curve.name, "tensile_cd");
  s.axis = LoadAxis::kMD;  // across unbonded fibres nothing carries load
  const TensileResult md = RunTensileTest(net, s);
  EXPECT_LT(md.Value("tensile_strength_N_per_m"), 1e-6 * cd.Value("tensile_strength_N_per_m"));
}

TEST(TensileTest, ElasticStripUnloadsAndReloadsOnTheSameLine) {
  TensileSettings s = SmallStrainTensile();
  s.cycle_strains = {0.0005};
  const TensileResult r = RunTensileTest(ParallelFibres(3), s);
  EXPECT_NEAR(r.Value("reload_modulus_N_per_m") / r.Value("tensile_modulus_N_per_m"), 1.0, 0.02);
  EXPECT_LT(r.Value("cycle_residual_strain"), 2e-5);
  const std::vector<double> branch = r.curve.Values("branch");
  EXPECT_EQ(branch.back(), 2.0);  // load, unload, reload
}

// The mass scale goes as 1 / (safety x loading steps)^2: a larger safety with the loading
// steps cut in proportion keeps the inertia and loads the strip in fewer, longer steps
// (generic-tissue-10mm.toml runs its tests so).
TEST(TensileTest, SafetyAndLoadingStepsTradeAtOneMassScale) {
  const Network net = ParallelFibres(5);
  const TensileResult base = RunTensileTest(net, SmallStrainTensile());
  TensileSettings s = SmallStrainTensile();
  s.quasi_static.time_step_safety = 0.8;
  s.quasi_static.loading_steps = 1250;
  const TensileResult coarse = RunTensileTest(net, s);
  EXPECT_GT(base.mass_scale, 1.0);
  EXPECT_NEAR(coarse.mass_scale / base.mass_scale, 1.0, 1e-12);
  EXPECT_NEAR(coarse.dt / base.dt, 1.6, 1e-12);
  EXPECT_NEAR(static_cast<double>(coarse.steps) / static_cast<double>(base.steps), 0.625, 0.01);
  EXPECT_NEAR(coarse.Value("tensile_modulus_N_per_m") / base.Value("tensile_modulus_N_per_m"),
              1.0, 0.002);
  EXPECT_TRUE(coarse.quasi_static);
}

TEST(TensileTest, BreaksAtTheFibreStrengthAndReportsIt) {
  Network net = ParallelFibres(2);
  const double strength = 0.05;  // [N]: a fibre breaks at strain 0.05 / (E A) ~ 1.6%
  for (BeamBondParams& t : net.world.bonds.types) t.max_tension = strength;
  TensileSettings s;
  s.max_strain = 0.04;
  s.quasi_static.loading_steps = 2000;
  const TensileResult r = RunTensileTest(net, s);
  EXPECT_TRUE(r.failed);
  const double W = net.world.cell.Ly();
  EXPECT_NEAR(r.Value("tensile_strength_N_per_m"), 2 * strength / W, 0.03 * 2 * strength / W);
  s.switches.bond_failure = false;  // the variant without failure does not break
  EXPECT_FALSE(RunTensileTest(net, s).failed);
}

// D = n E I / W for n fibres bent about their own axes.
TEST(BendingTest, ParallelFibresGiveTheBeamStiffness) {
  const int n = 5;
  const Network net = ParallelFibres(n);
  const BendingResult r = RunBendingTest(net, BendingSettings{});
  const double I = kPi * std::pow(kD, 4) / 64.0, W = net.world.cell.Ly();
  const double expected_mN_mm = n * kE * I / W * 1e6;
  EXPECT_NEAR(FindMetric(r.metrics, "bending_stiffness")->value / expected_mN_mm, 1.0, 0.03);
  EXPECT_TRUE(r.settled) << (r.warnings.empty() ? "" : r.warnings[0]);
  // The kinematics leave no net axial force on a homogeneous strip.
  const std::vector<double> axial = r.curve.Values("axial_force_N_per_m");
  const double scale = n * kE * kPi * kD * kD / 4.0 / W;  // tensile stiffness [N/m]
  EXPECT_LT(std::abs(axial.back()), 1e-5 * scale);
}

// Fibres whose bonds break in bending between the last two levels shed the moment there: the
// stiffness is read below that level, still the beams' n E I / W, and the warning names it.
TEST(BendingTest, AStripThatBreaksIsReadBelowTheLevelWhereItBroke) {
  const int n = 5;
  Network net = ParallelFibres(n);
  const double I = kPi * std::pow(kD, 4) / 64.0;
  const BendingSettings s;
  const double breaking_curvature = 0.9 * s.max_curvature;  // between levels 5 and 6 of 6
  for (BeamBondParams& t : net.world.bonds.types) t.max_bending = kE * I * breaking_curvature;
  const BendingResult r = RunBendingTest(net, s);
  const std::vector<double> moment = r.curve.Values("moment_N_m_per_m");
  ASSERT_LT(moment.back(), 0.5 * moment[moment.size() - 2]) << "the bonds broke at the last level";
  const double expected_mN_mm = n * kE * I / net.world.cell.Ly() * 1e6;
  EXPECT_NEAR(FindMetric(r.metrics, "bending_stiffness")->value / expected_mN_mm, 1.0, 0.03);
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings.back().find("the moment fell"), std::string::npos) << r.warnings.back();
  EXPECT_NE(r.warnings.back().find("fitted below 150 1/m"), std::string::npos) << r.warnings.back();
}

}  // namespace
}  // namespace fibrenet::pipeline
