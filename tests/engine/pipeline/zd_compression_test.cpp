// ZD compression with unloading: the van Wyk fit gives back the exponent of a curve of its
// form, the loading stops at a target pressure, the stepped loading follows the slow
// continuous curve of a buckling column, and snap-throughs are counted. A floating mat (fibres
// placed at random in a box, no gravity, no bonds) is the cheap specimen of the stop; the van
// Wyk check on a mat settled under its weight is tests/campaigns/loose_mat_test.cpp.
#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "engine/pipeline/compression_test.h"
#include "engine/pipeline/forming.h"
#include "test_fibre.h"

namespace fibrenet::pipeline {
namespace {

// 100 straight 0.5 mm fibres of 20 um, oriented at random in 3D, in a 1 mm x 1 mm x 1 mm box
// (10 g/m^2 at 1% consistency): fibre volume fraction ~1.6%.
Network FloatingMat() {
  SheetSpec sheet;
  sheet.Lx = sheet.Ly = 1e-3;
  sheet.basis_weight = 0.010;
  sheet.fibres.length = Distribution::Fixed(0.5e-3);
  sheet.fibres.diameter = Distribution::Fixed(20e-6);
  sheet.fibres.coarseness = Distribution::Fixed(2e-7);
  sheet.contact.restitution = 0.5;
  sheet.contact.Derive();
  FormingSettings forming;
  forming.consistency = 0.01;
  std::mt19937_64 rng(11);
  Network net = PlaceFibres(sheet, forming, rng);
  net.world.physics.contacts = true;
  net.world.physics.friction = true;
  return net;
}

CompressionSettings MatCompression() {
  CompressionSettings s;
  s.max_strain = 0.9;
  s.quasi_static.loading_steps = 8000;
  // Constant speed: the slow toe follows the platen work, which stays tiny while the platen
  // sweeps up the floating fibres (about 100x the steps).
  s.min_speed_fraction = 1.0;
  s.samples = 200;
  return s;
}

// A column: one straight fibre of 16 particles standing on the floor, leaning 5 degrees,
// beside a fibre lying on the floor. Under the platen it buckles; once the chord between its
// ends leans past the friction angle its ends slip and it falls (a snap-through), and the
// platen goes on through empty space to the two fibres on the floor.
Network LeaningColumn() {
  Network net;
  World& w = net.world;
  const double d = 32e-6, lean = 5.0 * kPi / 180.0;
  w.cell.lo = Vec3(0.0, 0.0, -1e-3);
  w.cell.hi = Vec3(1.2e-3, 1e-3, 2e-3);
  std::vector<Vec3> column, lying;
  for (int k = 0; k < 16; ++k) {
    column.push_back(Vec3(0.6e-3 + k * d * std::sin(lean), 0.5e-3, 0.5 * d + k * d * std::cos(lean)));
    lying.push_back(Vec3(0.3e-3 + k * d, 0.2e-3, 0.5 * d));
  }
  net.AddFibre(TestFibre(16 * d), column, FibreBondOptions{});
  net.AddFibre(TestFibre(16 * d), lying, FibreBondOptions{});
  w.contact.restitution = 0.5;
  w.contact.Derive();
  w.physics.contacts = true;
  w.physics.friction = w.contact.mu > 0.0;
  return net;
}

// Pressure of the loading branch at `strain`, linearly between the samples.
double LoadingPressureAt(const Curve& c, double strain) {
  const std::vector<double> e = c.Values("strain"), p = c.Values("pressure_Pa"),
                            branch = c.Values("branch");
  for (std::size_t k = 1; k < e.size() && branch[k] == 0.0; ++k)
    if (e[k] >= strain) return p[k - 1] + (p[k] - p[k - 1]) * (strain - e[k - 1]) / (e[k] - e[k - 1]);
  return p.back();
}

// The stepped loading samples rest states: on the buckling column its curve is the slow
// continuous one (constant speed, 40x the loading steps, its guard holding) within 3% of the
// peak at every sample, and its guard holds at a fortieth of the steps, where the continuous
// loading's does not.
TEST(ZdCompression, SteppedLoadingFollowsTheSlowContinuousCurve) {
  CompressionSettings stepped;
  stepped.max_strain = 0.9;
  stepped.samples = 100;
  stepped.quasi_static.loading_steps = 8000;
  stepped.loading = CompressionSettings::Loading::kStepped;
  const CompressionResult r = RunCompressionTest(LeaningColumn(), stepped);
  EXPECT_TRUE(r.quasi_static) << r.Value("zd_kinetic_work_ratio");
  EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
  EXPECT_NEAR(r.Value("zd_max_strain"), 0.9, 0.01);

  CompressionSettings fast = stepped;
  fast.loading = CompressionSettings::Loading::kContinuous;
  fast.min_speed_fraction = 1.0;
  const CompressionResult f = RunCompressionTest(LeaningColumn(), fast);
  EXPECT_FALSE(f.quasi_static);

  CompressionSettings slow = fast;
  slow.quasi_static.loading_steps = 40 * stepped.quasi_static.loading_steps;
  const CompressionResult q = RunCompressionTest(LeaningColumn(), slow);
  ASSERT_TRUE(q.quasi_static) << q.Value("zd_kinetic_work_ratio");
  const double peak = q.Value("zd_peak_pressure_kPa") * 1e3;
  const Curve& c = r.curves[0];
  const std::vector<double> e = c.Values("strain"), p = c.Values("pressure_Pa"),
                            branch = c.Values("branch");
  int compared = 0;
  for (std::size_t k = 0; k < e.size() && branch[k] == 0.0; ++k, ++compared)
    EXPECT_NEAR(p[k], LoadingPressureAt(q.curves[0], e[k]), 0.03 * peak) << "strain " << e[k];
  EXPECT_GT(compared, 90);
  // The figures of docs/virtual-tests.md ("Stepped loading").
  std::printf("column: stepped %lld steps, guard %.4f; continuous %lld steps, guard %.4f; "
              "slow continuous %lld steps, guard %.4f, peak %.1f kPa\n",
              static_cast<long long>(r.steps), r.Value("zd_kinetic_work_ratio"),
              static_cast<long long>(f.steps), f.Value("zd_kinetic_work_ratio"),
              static_cast<long long>(q.steps), q.Value("zd_kinetic_work_ratio"), peak * 1e-3);
}

// Falls of the loading pressure by more than 10% from its highest since the last fall count,
// from the given pressure on; a rise, a plateau and a small dip do not.
TEST(ZdCompression, CountsSnapThroughs) {
  EXPECT_EQ(CountSnapThroughs({0, 100, 200, 300, 400}, 5.0), 0);
  EXPECT_EQ(CountSnapThroughs({0, 100, 200, 195, 200, 300}, 5.0), 0);
  EXPECT_EQ(CountSnapThroughs({0, 335, 10, 0, 0, 50, 400}, 5.0), 1);
  EXPECT_EQ(CountSnapThroughs({0, 335, 10, 50, 400, 300, 500}, 5.0), 2);
  EXPECT_EQ(CountSnapThroughs({0, 4, 1, 4, 1, 100}, 5.0), 0);  // below the floor
}

// A loading curve of exactly the van Wyk form gives back its exponent, and its r2 is 1.
TEST(ZdCompression, VanWykFitRecoversAKnownExponent) {
  // 15: the bonded 10 mm generic tissue reads 12 (docs/virtual-tests.md).
  for (double n : {2.0, 3.0, 5.5, 15.0}) {
    const double phi_h0 = 0.05, k = 2e6;
    Curve c;
    c.columns = {"strain", "pressure_Pa", "branch"};
    for (int i = 0; i <= 100; ++i) {
      const double strain = 0.8 * i / 100.0;
      const double phi = phi_h0 / (1.0 - strain);
      c.Add({strain, k * (std::pow(phi, n) - std::pow(phi_h0, n)), 0.0});
    }
    c.Add({0.7, 1.0, 1.0});  // the unloading branch is left out
    const VanWykFit fit = FitVanWyk(c, phi_h0);
    EXPECT_NEAR(fit.n, n, 0.011);
    EXPECT_NEAR(fit.k, k, 0.05 * k);
    EXPECT_NEAR(fit.phi0, phi_h0, 0.02 * phi_h0);
    EXPECT_GT(fit.r2, 0.9999);
  }
}

// A bonded sheet's curve softens where its bonds start to break: the fit stops at the first
// failure and gives back the exponent of the elastic part. Fitted through the breaking, the
// same curve puts the exponent elsewhere.
TEST(ZdCompression, VanWykFitStopsAtTheFirstBondFailure) {
  const double n = 5.0, phi_h0 = 0.05, k = 2e6;
  auto pressure = [&](double strain) {
    return k * (std::pow(phi_h0 / (1.0 - strain), n) - std::pow(phi_h0, n));
  };
  Curve c;
  c.columns = {"strain", "pressure_Pa", "bonds_broken", "branch"};
  const double first_failure = 0.3;
  for (int i = 0; i <= 100; ++i) {
    const double strain = 0.6 * i / 100.0;
    if (strain <= first_failure) {
      c.Add({strain, pressure(strain), 0.0, 0.0});
    } else {  // breaking: the pressure rises at a fifth of the elastic slope
      const double slope = (pressure(first_failure) - pressure(first_failure - 0.006)) / 0.006;
      c.Add({strain, pressure(first_failure) + 0.2 * slope * (strain - first_failure),
             100.0 * (strain - first_failure), 0.0});
    }
  }
  const VanWykFit fit = FitVanWyk(c, phi_h0);
  EXPECT_NEAR(fit.n, n, 0.011);
  EXPECT_GT(fit.r2, 0.9999);
  EXPECT_NEAR(fit.p_top, pressure(first_failure), 1e-9 * pressure(first_failure));

  Curve without_failures = c;
  without_failures.columns = {"strain", "pressure_Pa", "unrelated", "branch"};
  const VanWykFit through = FitVanWyk(without_failures, phi_h0);
  EXPECT_GT(std::abs(through.n - n), 0.5);
  EXPECT_GT(through.p_top, fit.p_top);
}

// A curve whose exponent changes with the pressure (8 up to 50 kPa, 4 above, the slope
// continuous), as the bonded generic tissue's falls from over 30 to about 5: over the whole
// curve the fit reads neither, over a range within one part it reads that part's, and the
// range it fitted is reported.
TEST(ZdCompression, VanWykFitOverAPressureRangeReadsThatRangesExponent) {
  const double phi_h0 = 0.05, k_low = 2e12, n_low = 8.0, n_high = 4.0, knee = 5e4;
  const double phi_knee = std::pow(knee / k_low + std::pow(phi_h0, n_low), 1.0 / n_low);
  // Above the knee p = knee + k_high (phi^4 - phi_knee^4), k_high matching the slope there.
  const double k_high = k_low * n_low * std::pow(phi_knee, n_low - 1.0) /
                        (n_high * std::pow(phi_knee, n_high - 1.0));
  auto pressure = [&](double phi) {
    return phi <= phi_knee
               ? k_low * (std::pow(phi, n_low) - std::pow(phi_h0, n_low))
               : knee + k_high * (std::pow(phi, n_high) - std::pow(phi_knee, n_high));
  };
  Curve c;
  c.columns = {"strain", "pressure_Pa", "bonds_broken", "branch"};
  for (int i = 0; i <= 400; ++i) {
    const double strain = 0.65 * i / 400.0;  // to about 4 x the knee
    c.Add({strain, pressure(phi_h0 / (1.0 - strain)), 0.0, 0.0});
  }
  const VanWykFit whole = FitVanWyk(c, phi_h0);
  EXPECT_GT(std::abs(whole.n - n_low), 0.5);
  EXPECT_GT(std::abs(whole.n - n_high), 0.5);

  const VanWykFit low = FitVanWyk(c, phi_h0, 0.0, 0.9 * knee);
  EXPECT_NEAR(low.n, n_low, 0.011);
  EXPECT_GT(low.r2, 0.9999);
  EXPECT_LE(low.p_top, 0.9 * knee);
  EXPECT_GT(low.p_top, 0.8 * knee);  // the samples reach the range's top

  const VanWykFit high = FitVanWyk(c, phi_h0, 1.1 * knee, 0.0);
  EXPECT_NEAR(high.n, n_high, 0.011);
  EXPECT_GT(high.r2, 0.9999);
  EXPECT_GE(high.p_bottom, 1.1 * knee);
  EXPECT_LT(high.p_bottom, 1.3 * knee);
  EXPECT_DOUBLE_EQ(high.p_top, whole.p_top);
}

TEST(ZdCompression, StopsAtTheTargetPressure) {
  const CompressionResult full = RunCompressionTest(FloatingMat(), MatCompression());
  CompressionSettings s = MatCompression();
  s.max_pressure = 0.2 * full.Value("zd_peak_pressure_kPa") * 1e3;
  const CompressionResult r = RunCompressionTest(FloatingMat(), s);
  EXPECT_NEAR(r.Value("zd_peak_pressure_kPa") * 1e3 / s.max_pressure, 1.0, 0.15);
  EXPECT_LT(r.Value("zd_max_strain"), 0.9);
}

// A layer of touching spheres in a square grid: 20 fibres of 20 particles along x, side by
// side along y. Periodic, or the same layer as an open strip in a cell three times its length
// (a creped strip's case). Squeezed, every sphere carries the same load in both, so the
// pressure over the strip's footprint is the periodic sheet's; over the open cell's area it
// would be a third of it.
Network SphereLayer(bool open) {
  Network net;
  World& w = net.world;
  const int n = 20;
  const double d = 32e-6, length = n * d;
  w.cell.lo = Vec3(0.0, 0.0, -1e-3);
  w.cell.hi = Vec3(length, length, 1e-3);
  if (open) {
    w.cell.periodic_x = false;
    w.cell.lo.x() -= length;
    w.cell.hi.x() += length;
  }
  for (int row = 0; row < n; ++row) {
    std::vector<Vec3> centres;
    for (int k = 0; k < n; ++k) centres.push_back(Vec3((k + 0.5) * d, (row + 0.5) * d, 0.5 * d));
    net.AddFibre(TestFibre(length), centres, FibreBondOptions{});
  }
  w.contact.restitution = 0.5;
  w.contact.Derive();
  return net;
}

TEST(ZdCompression, AnOpenStripIsLoadedOverItsFootprintNotTheCell) {
  CompressionSettings s;
  s.max_strain = 0.05;
  s.samples = 20;
  s.quasi_static.loading_steps = 4000;
  const CompressionResult periodic = RunCompressionTest(SphereLayer(false), s);
  const CompressionResult open = RunCompressionTest(SphereLayer(true), s);
  const double p = periodic.Value("zd_peak_pressure_kPa");
  ASSERT_GT(p, 0.0);
  EXPECT_NEAR(open.Value("zd_peak_pressure_kPa") / p, 1.0, 1e-6);
  EXPECT_NEAR(open.Value("zd_compression_energy_J_per_m2") /
                  periodic.Value("zd_compression_energy_J_per_m2"), 1.0, 1e-6);
}

// A creped sheet's case: a web (the open sphere layer) with a thin loop standing on the floor
// beside it (16 spheres of 16 um leaning 20 degrees, each `mass_ratio` times as heavy as the
// web's), which folds over under a small load.
// The platen meets the loop's top at about eight times the web's caliper; the web is met near
// strain 0.87, and goes from no load to past the modulus window within less than a move of a
// 20-move loading.
Network LoopBesideAWeb(double mass_ratio = 1.0) {
  Network net = SphereLayer(true);
  const double d = 16e-6, lean = 20.0 * kPi / 180.0, x0 = 30 * 32e-6, y0 = 10 * 32e-6;
  std::vector<Vec3> loop;
  for (int k = 0; k < 16; ++k)
    loop.push_back(Vec3(x0 + k * d * std::sin(lean), y0, 0.5 * d + k * d * std::cos(lean)));
  // A web particle weighs the base coarseness x 32 um, a loop particle coarseness x 16 um.
  FibreProperties thin = TestFibre(16 * d);
  thin.diameter = d;
  thin.coarseness = 2.0 * mass_ratio * TestFibre(16 * d).coarseness;
  net.AddFibre(thin, loop, FibreBondOptions{});
  return net;
}

// Loading samples in the modulus window, and dp / dgap of the window's fit [Pa/m].
struct WindowReading {
  int samples = 0;
  double stiffness = 0.0;
};
WindowReading ReadWindow(const CompressionResult& r, const CompressionSettings& s) {
  const Curve& c = r.curves[0];
  const std::vector<double> p = c.Values("pressure_Pa"), branch = c.Values("branch");
  WindowReading w;
  for (std::size_t k = 0; k < p.size() && branch[k] == 0.0; ++k)
    w.samples += p[k] >= s.modulus_pressure_lo && p[k] <= s.modulus_pressure_hi ? 1 : 0;
  w.stiffness = r.Value("zd_modulus_kPa") * 1e3 / r.h0;
  return w;
}

// The loop beside the web loaded in 20 stepped moves, sized to the curve, to 5 kPa.
CompressionSettings SteppedToTheWeb() {
  CompressionSettings s;
  s.loading = CompressionSettings::Loading::kStepped;
  s.max_strain = 0.95;
  s.max_pressure = 5e3;
  s.samples = 20;
  s.quasi_static.loading_steps = 8000;
  return s;
}

// The web alone loaded to the same pressure in 200 moves of one size: the reference curve.
CompressionSettings WebInFineMoves() {
  CompressionSettings fine = SteppedToTheWeb();
  fine.window_samples = 0;
  fine.max_strain = 0.03;
  fine.samples = 200;
  return fine;
}

// The stepped loading's moves shrink where the curve is steep: with 20 moves to the web, the
// web's stiffness in the window is read from at least 6 rests and equals that of the web
// alone loaded in fine moves within 1%; with moves of one size the window holds at most one
// rest.
TEST(ZdCompression, SteppedMovesShrinkWhereTheWebIsMet) {
  const CompressionSettings s = SteppedToTheWeb();
  const CompressionResult sized = RunCompressionTest(LoopBesideAWeb(), s);
  CompressionSettings one_size = s;
  one_size.window_samples = 0;
  const CompressionResult fixed = RunCompressionTest(LoopBesideAWeb(), one_size);
  const CompressionSettings fine = WebInFineMoves();
  const CompressionResult web = RunCompressionTest(SphereLayer(true), fine);

  const WindowReading a = ReadWindow(sized, s), b = ReadWindow(fixed, one_size),
                      ref = ReadWindow(web, fine);
  std::printf("loop beside a web: sized %d window samples, %.4g Pa/um, %lld steps; one size %d, "
              "%.4g Pa/um, %lld steps; web alone %d, %.4g Pa/um, h0 %.1f / %.1f um\n",
              a.samples, a.stiffness * 1e-6, static_cast<long long>(sized.steps), b.samples,
              b.stiffness * 1e-6, static_cast<long long>(fixed.steps), ref.samples,
              ref.stiffness * 1e-6, sized.h0 * 1e6, web.h0 * 1e6);
  for (const auto& w : sized.warnings) std::printf("  %s\n", w.c_str());
  EXPECT_GE(ref.samples, 6);
  EXPECT_GE(a.samples, 6);
  EXPECT_LE(b.samples, 1);
  EXPECT_NEAR(a.stiffness / ref.stiffness, 1.0, 0.01);
  // Every rest on the web reads the web's pressure at its gap: a rest is read where the
  // platen stopped, not a step before (contact starting in a move's last step read 0).
  const std::vector<double> gap = sized.curves[0].Values("gap_m"),
                            p = sized.curves[0].Values("pressure_Pa"),
                            branch = sized.curves[0].Values("branch");
  const std::vector<double> web_gap = web.curves[0].Values("gap_m"),
                            web_p = web.curves[0].Values("pressure_Pa"),
                            web_branch = web.curves[0].Values("branch");
  std::size_t web_turn = 0;
  while (web_branch[web_turn] == 0.0) ++web_turn;
  int on_web = 0;
  for (std::size_t k = 0; k < gap.size() && branch[k] == 0.0; ++k) {
    if (gap[k] >= web.h0 || gap[k] < web_gap[web_turn - 1]) continue;
    std::size_t m = 1;
    while (web_gap[m] > gap[k]) ++m;
    const double a = (web_gap[m - 1] - gap[k]) / (web_gap[m - 1] - web_gap[m]);
    EXPECT_NEAR(p[k], web_p[m - 1] + a * (web_p[m] - web_p[m - 1]), 0.02 * s.max_pressure)
        << "gap " << gap[k];
    ++on_web;
  }
  EXPECT_GE(on_web, 6);
  EXPECT_TRUE(sized.quasi_static) << sized.Value("zd_kinetic_work_ratio");
}

// A loop of particles fifty times lighter than the web's under the same loading: each bond's
// dashpots are sized on its own particles' masses, so the light loop is damped at the same
// fraction of critical as the web. (Sized on the mean mass, its bonds were damped at about
// seven times that, and under local damping the explicit step went unstable at step 14.)
TEST(ZdCompression, ALightLoopIsDampedAsTheWebIs) {
  const CompressionSettings s = SteppedToTheWeb();
  const CompressionResult light = RunCompressionTest(LoopBesideAWeb(0.02), s);
  const CompressionSettings fine = WebInFineMoves();
  const CompressionResult web = RunCompressionTest(SphereLayer(true), fine);
  const WindowReading a = ReadWindow(light, s), ref = ReadWindow(web, fine);
  std::printf("light loop beside a web: %d window samples, %.4g Pa/um, %lld steps; web alone "
              "%.4g Pa/um\n",
              a.samples, a.stiffness * 1e-6, static_cast<long long>(light.steps),
              ref.stiffness * 1e-6);
  EXPECT_GE(a.samples, 6);
  EXPECT_NEAR(a.stiffness / ref.stiffness, 1.0, 0.01);
  EXPECT_TRUE(light.quasi_static) << light.Value("zd_kinetic_work_ratio");
}

}  // namespace
}  // namespace fibrenet::pipeline
