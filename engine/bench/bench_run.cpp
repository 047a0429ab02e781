#include "engine/bench/bench_run.h"

#include <malloc.h>
#include <sys/resource.h>

#include <fstream>
#include <string>

#include <fmt/format.h>

#include "engine/core/energy.h"
#include "engine/core/error.h"
#include "engine/core/parallel.h"
#include "engine/core/simulation.h"
#include "engine/core/stopwatch.h"

namespace fibrenet::bench {

namespace {

// User plus system CPU time of the process, all threads [s].
double CpuSeconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

}  // namespace

std::string BenchOptions::Validate() const {
  if (steps < 1 || steps > 1'000'000'000)
    return fmt::format("steps = {}: must be in [1, 1000000000]", steps);
  if (warmup < 0 || warmup > 1'000'000'000)
    return fmt::format("warmup = {}: must be in [0, 1000000000]", warmup);
  if (threads < 0 || threads > 1024) return fmt::format("threads = {}: must be in [1, 1024]", threads);
  return bed.Validate();
}

double PeakRssBytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) * 1024.0;  // kB
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) * 1024.0;  // kB on Linux
}

bool ResetPeakRss() {
#ifdef __GLIBC__
  // Hand the heap's free memory back first: the high-water mark restarts from the resident
  // set, which otherwise keeps what an earlier, larger run freed.
  malloc_trim(0);
#endif
  std::ofstream clear("/proc/self/clear_refs");
  if (!clear) return false;
  clear << "5";
  return static_cast<bool>(clear);
}

BenchResult RunFibreBedBench(const BenchOptions& options) {
  if (std::string m = options.Validate(); !m.empty()) throw InputError("bench: " + m);
  if (options.threads > 0) SetThreadCount(options.threads);
  BenchResult r;
  r.threads = ThreadCount();
  r.steps = options.steps;
  r.warmup = options.warmup;

  Stopwatch clock;
  World w;
  r.bed = BuildFibreBed(options.bed, w);
  Simulation sim(w);
  sim.Prepare();
  r.dt_s = w.settings.dt;
  r.build_s = clock.Restart();
  sim.Run(options.warmup);
  if (options.after_warmup) options.after_warmup(w);
  r.warmup_s = clock.Restart();
  const std::size_t builds_before = w.neighbours.builds();
  const double cpu_before = CpuSeconds();
  sim.Run(options.steps);
  r.wall_s = clock.Seconds();
  r.cpu_s = CpuSeconds() - cpu_before;

  const double particle_steps = static_cast<double>(r.bed.particles) * options.steps;
  r.particle_steps_per_s = particle_steps / r.wall_s;
  r.ns_per_particle_step = 1e9 * r.wall_s / particle_steps;
  r.neighbour_builds_total = static_cast<std::int64_t>(w.neighbours.builds());
  r.neighbour_rebuilds = static_cast<std::int64_t>(w.neighbours.builds() - builds_before);
  r.neighbour_pairs = w.physics.contacts ? static_cast<std::int64_t>(w.neighbours.size()) : 0;
  r.contacts_per_particle =
      2.0 * static_cast<double>(CountTouchingPairs(w)) / static_cast<double>(r.bed.particles);
  r.kinetic_energy_j = KineticEnergy(w);
  r.min_contact_ratio = w.min_contact_ratio;
  double z = 0.0;
  for (const Vec3& x : w.particles.x) z += x.z();
  r.mean_z_m = z / static_cast<double>(w.particles.size());
  r.peak_rss_mb = PeakRssBytes() / (1024.0 * 1024.0);
  r.peak_rss_bytes_per_particle = PeakRssBytes() / static_cast<double>(r.bed.particles);
  return r;
}

}  // namespace fibrenet::bench
