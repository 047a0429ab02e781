// `fibrenet bench [--json] [--particles N] [--steps S] [--threads T] [--warmup W]
//  [--no-friction] [--no-contacts] [--no-gravity] [--drag] [--viscoelastic] [--write-bed F]
//  [--scaling]`: throughput of the fibre bed
// scene (SPEC section 6). One run by default; --scaling runs the series of
// docs/performance.md (particle counts 1e4 .. 1e6, then 1 against 2 threads at 5e4).
#include <cmath>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "engine/bench/bench_run.h"
#include "engine/core/error.h"
#include "engine/core/parallel.h"

namespace fibrenet::cli {

namespace {

struct BenchCliOptions {
  bool json = false;
  double particles = 50000;  // read as a number so that 1e6 is accepted
  long long steps = 200;
  long long warmup = 200;
  int threads = 0;
  bool no_friction = false, no_contacts = false, no_gravity = false;
  bool drag = false, viscoelastic = false;
  bool shuffled = false;
  bool scaling = false;
  unsigned long long seed = 1;
  std::string write_bed;  // CSV of the bed after the warmup, for other codes
};

// The bed after the warmup as CSV, for running the same state in other DEM codes
// (scripts/compare/): '#' lines give the cell and the physics, then one row per particle
// in fibre order; consecutive particles of one fibre are bonded.
void WriteBed(const std::string& path, const bench::FibreBedSpec& bed, const World& w) {
  std::ofstream out(path);
  if (!out) throw InputError(fmt::format("--write-bed {}: cannot open the file for writing", path));
  const Cell& c = w.cell;
  out << fmt::format("# fibrenet fibre bed after the warmup, step {}, dt {:.17g} s\n", w.step,
                     w.settings.dt);
  out << fmt::format("# cell {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g}\n", c.lo.x(),
                     c.hi.x(), c.lo.y(), c.hi.y(), c.lo.z(), c.hi.z());
  out << fmt::format(
      "# E {:.17g} G {:.17g} mu {:.17g} restitution {:.17g} gravity {:.17g} contact_C {:.17g} "
      "contact_g {:.17g} particles_per_fibre {}\n",
      bed.E, bed.G, bed.mu, bed.restitution, bed.use_gravity ? bed.gravity : 0.0,
      w.contact.normal.C, w.contact.normal.g, bed.particles_per_fibre);
  out << "fibre,x,y,z,vx,vy,vz,wx,wy,wz,radius,mass\n";
  const Particles& p = w.particles;
  for (std::size_t i = 0; i < p.size(); ++i)
    out << fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},"
                       "{:.17g},{:.17g}\n",
                       p.fibre[i], p.x[i].x(), p.x[i].y(), p.x[i].z(), p.v[i].x(), p.v[i].y(),
                       p.v[i].z(), p.omega[i].x(), p.omega[i].y(), p.omega[i].z(), p.radius[i],
                       p.mass[i]);
  if (!out.flush()) throw RunError(fmt::format("--write-bed {}: writing failed", path));
}

// Checks the command line (names the option and its range) and turns it into options.
bench::BenchOptions ToOptions(const BenchCliOptions& o) {
  if (!(std::isfinite(o.particles) && o.particles >= 200 && o.particles <= 1e8))
    throw InputError(fmt::format("--particles {}: must be in [200, 1e8]", o.particles));
  if (o.steps < 1 || o.steps > 1'000'000'000)
    throw InputError(fmt::format("--steps {}: must be in [1, 1000000000]", o.steps));
  if (o.warmup < 0 || o.warmup > 1'000'000'000)
    throw InputError(fmt::format("--warmup {}: must be in [0, 1000000000]", o.warmup));
  if (o.threads < 0 || o.threads > 1024)
    throw InputError(fmt::format("--threads {}: must be in [1, 1024] (0 = OpenMP default)",
                                 o.threads));
  bench::BenchOptions b;
  b.bed.particles = static_cast<std::int64_t>(std::llround(o.particles));
  b.bed.friction = !o.no_friction;
  b.bed.contacts = !o.no_contacts;
  b.bed.use_gravity = !o.no_gravity;
  if (o.drag) b.bed.drag_coefficient = bench::kStokesDragOfBedParticle;
  if (o.viscoelastic) b.bed.maxwell_tau = bench::kBenchMaxwellTau;
  b.bed.spatial_order = !o.shuffled;
  b.bed.seed = o.seed;
  b.steps = o.steps;
  b.warmup = o.warmup;
  b.threads = o.threads;
  if (std::string m = b.Validate(); !m.empty()) throw InputError("bench: " + m);
  return b;
}

nlohmann::json ToJson(const bench::BenchOptions& o, const bench::BenchResult& r) {
  return {{"scene", "fibre_bed"},
          {"particles", r.bed.particles},
          {"bonds", r.bed.bonds},
          {"fibres", r.bed.fibres},
          {"layers", r.bed.layers},
          {"cell_side_mm", r.bed.cell_side * 1e3},
          {"contacts_per_particle", r.contacts_per_particle},
          {"steps", r.steps},
          {"warmup", r.warmup},
          {"wall_s", r.wall_s},
          {"cpu_s", r.cpu_s},
          {"particle_steps_per_s", r.particle_steps_per_s},
          {"ns_per_particle_step", r.ns_per_particle_step},
          {"peak_rss_mb", r.peak_rss_mb},
          {"peak_rss_bytes_per_particle", r.peak_rss_bytes_per_particle},
          {"threads", r.threads},
          {"simd", FIBRENET_SIMD_LEVEL},
          {"neighbour_rebuilds", r.neighbour_rebuilds},
          {"neighbour_builds_total", r.neighbour_builds_total},
          {"neighbour_pairs", r.neighbour_pairs},
          {"dt_s", r.dt_s},
          {"build_s", r.build_s},
          {"warmup_s", r.warmup_s},
          {"kinetic_energy_j", r.kinetic_energy_j},
          {"min_contact_ratio", r.min_contact_ratio},
          {"mean_z_um", r.mean_z_m * 1e6},
          {"physics",
           {{"contacts", o.bed.contacts},
            {"friction", o.bed.friction},
            {"gravity", o.bed.use_gravity},
            {"gravity_m_per_s2", o.bed.gravity},
            {"gravity_scale_over_g", o.bed.gravity / 9.81},
            {"approach_speed_m_per_s", o.bed.approach_speed},
            {"initial_gap_m", o.bed.gap},
            {"mu", o.bed.mu},
            {"restitution", o.bed.restitution},
            {"drag_coefficient_N_s_per_m", o.bed.drag_coefficient},
            {"maxwell_tau_s", o.bed.maxwell_tau},
            {"bond_modes", 6}}}};
}

void PrintHuman(const bench::BenchOptions& o, const bench::BenchResult& r) {
  std::cout << fmt::format(
      "fibre bed: {} particles ({} fibres of {}, {} layers, cell {:.3f} mm), {} bonds\n"
      "physics: contacts {}, friction {}, gravity {} ({:.3g} m/s^2 = {:.0f} g, scaled so the "
      "bed lands within the warmup; layers start {:.2g} um apart, closing at {} m/s), drag {}, "
      "viscoelastic bonds {}\n"
      "time step {:.4g} s, {} warmup + {} timed steps on {} thread(s)\n"
      "wall {:.3f} s (CPU {:.3f} s): {:.4g} particle-steps/s ({:.1f} ns per particle-step)\n"
      "contacts per particle {:.3f}, neighbour pairs {}, rebuilds {} (timed) / {} (total), "
      "min d/(R_i+R_j) {:.4f}\n"
      "peak RSS {:.1f} MiB ({:.0f} bytes per particle); kinetic energy {:.6e} J\n",
      r.bed.particles, r.bed.fibres, o.bed.particles_per_fibre, r.bed.layers,
      r.bed.cell_side * 1e3, r.bed.bonds, o.bed.contacts ? "on" : "off",
      o.bed.friction ? "on" : "off", o.bed.use_gravity ? "on" : "off", o.bed.gravity,
      o.bed.gravity / 9.81, o.bed.gap * 1e6, o.bed.approach_speed,
      o.bed.drag_coefficient > 0.0 ? "on" : "off", o.bed.maxwell_tau > 0.0 ? "on" : "off",
      r.dt_s, r.warmup, r.steps,
      r.threads, r.wall_s, r.cpu_s, r.particle_steps_per_s, r.ns_per_particle_step,
      r.contacts_per_particle, r.neighbour_pairs, r.neighbour_rebuilds,
      r.neighbour_builds_total, r.min_contact_ratio, r.peak_rss_mb,
      r.peak_rss_bytes_per_particle, r.kinetic_energy_j);
}

// The scaling series: particle counts at the default thread count, then 1 and 2 threads at
// 5e4. Timed steps shrink with size so that each run is a few seconds to a minute; the
// peak RSS is reset before each run (Linux), so it is that run's own.
int RunScaling(const BenchCliOptions& cli) {
  const bench::BenchOptions base = ToOptions(cli);
  struct Point {
    double particles;
    int threads;
  };
  const int all = base.threads > 0 ? base.threads : ThreadCount();
  std::vector<Point> points = {{1e4, all}, {3e4, all}, {1e5, all}, {3e5, all}, {1e6, all},
                               {5e4, 1},   {5e4, 2}};
  nlohmann::json runs = nlohmann::json::array();
  if (!cli.json)
    std::cout << fmt::format("{:>10} {:>8} {:>7} {:>9} {:>14} {:>10} {:>10} {:>10}\n",
                             "particles", "threads", "steps", "wall_s", "p-steps/s",
                             "ns/p-step", "contacts", "B/particle");
  for (const Point& pt : points) {
    bench::BenchOptions o = base;
    o.bed.particles = static_cast<std::int64_t>(pt.particles);
    o.threads = pt.threads;
    // About 2e7 particle-steps per run unless --steps asks for fewer.
    o.steps = std::max<std::int64_t>(
        20, std::min<std::int64_t>(base.steps, static_cast<std::int64_t>(2e7 / pt.particles)));
    bench::ResetPeakRss();
    const bench::BenchResult r = bench::RunFibreBedBench(o);
    runs.push_back(ToJson(o, r));
    if (cli.json) {
      std::cerr << fmt::format("bench: {} particles, {} thread(s): {:.4g} particle-steps/s\n",
                               r.bed.particles, r.threads, r.particle_steps_per_s);
    } else {
      std::cout << fmt::format("{:>10} {:>8} {:>7} {:>9.3f} {:>14.4g} {:>10.1f} {:>10.3f} {:>10.0f}\n",
                               r.bed.particles, r.threads, r.steps, r.wall_s,
                               r.particle_steps_per_s, r.ns_per_particle_step,
                               r.contacts_per_particle, r.peak_rss_bytes_per_particle)
                << std::flush;
    }
  }
  if (cli.json) std::cout << nlohmann::json{{"scaling", runs}}.dump(2) << "\n";
  return 0;
}

int RunBench(const BenchCliOptions& cli) {
  if (cli.scaling) return RunScaling(cli);
  bench::BenchOptions o = ToOptions(cli);
  if (!cli.write_bed.empty())
    o.after_warmup = [&](const World& w) { WriteBed(cli.write_bed, o.bed, w); };
  const bench::BenchResult r = bench::RunFibreBedBench(o);
  if (cli.json) std::cout << ToJson(o, r).dump(2) << "\n";
  else PrintHuman(o, r);
  return 0;
}

}  // namespace

void AddBenchCommand(CLI::App& app, Context& context) {
  auto o = std::make_shared<BenchCliOptions>();
  CLI::App* cmd = app.add_subcommand("bench", "Throughput benchmark: the fibre bed scene");
  cmd->add_flag("--json", o->json, "Print one JSON document on stdout");
  cmd->add_option("--particles", o->particles, "Particles (whole fibres of 20), 200 .. 1e8")
      ->capture_default_str();
  cmd->add_option("--steps", o->steps, "Timed steps, >= 1")->capture_default_str();
  cmd->add_option("--warmup", o->warmup, "Untimed steps before timing (layers land), >= 0")
      ->capture_default_str();
  cmd->add_option("--threads", o->threads, "OpenMP threads (0 = OpenMP default)")
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "Seed of the fibre placement")->capture_default_str();
  cmd->add_flag("--no-friction", o->no_friction, "Frictionless contacts and floor");
  cmd->add_flag("--no-contacts", o->no_contacts, "No fibre-fibre contacts (floor only)");
  cmd->add_flag("--no-gravity", o->no_gravity, "No gravity");
  cmd->add_flag("--drag", o->drag, "Air drag on every particle (Stokes drag of a 16 um sphere)");
  cmd->add_flag("--viscoelastic", o->viscoelastic,
                "Maxwell dashpot in the fibre bonds' axial mode (relaxation time 1 ms)");
  cmd->add_flag("--shuffled", o->shuffled,
                "Fibres in random memory order instead of sorted by place (what locality is worth)");
  cmd->add_option("--write-bed", o->write_bed,
                  "Write the bed after the warmup as CSV (for scripts/compare/)");
  cmd->add_flag("--scaling", o->scaling,
                "Run the series 1e4 .. 1e6 particles and 1 vs 2 threads at 5e4 (minutes)");
  cmd->callback([o, &context] { context.exit_code = RunBench(*o); });
}

}  // namespace fibrenet::cli
