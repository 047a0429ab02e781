// Runs the fibre bed benchmark: builds the bed, warms it up (the layers land and contacts
// form), then times `steps` steps of Simulation::Step and reports throughput, memory and
// the state reached. Timing covers the steps only, neighbour rebuilds included.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "engine/bench/fibre_bed.h"

namespace fibrenet::bench {

struct BenchOptions {
  FibreBedSpec bed;
  std::int64_t steps = 200;   // timed steps, >= 1
  std::int64_t warmup = 200;  // untimed steps first, >= 0
  int threads = 0;            // OpenMP threads; 0 = the OpenMP default
  // Called with the bed after the warmup, before the timed steps (e.g. to export the state
  // that other codes then time from).
  std::function<void(const World&)> after_warmup;

  // Empty when valid; otherwise names the field and its accepted range.
  std::string Validate() const;
};

struct BenchResult {
  FibreBedInfo bed;
  std::int64_t steps = 0, warmup = 0;
  int threads = 0;
  double dt_s = 0.0;
  double build_s = 0.0;   // building the bed and Simulation::Prepare [s]
  double warmup_s = 0.0;  // [s]
  double wall_s = 0.0;    // the timed steps [s]
  double cpu_s = 0.0;     // CPU time of the process (all threads) during the timed steps [s]
  double particle_steps_per_s = 0.0;
  double ns_per_particle_step = 0.0;  // per thread-independent wall time [ns]
  // Non-bonded touching pairs at the end, counted for both partners, per particle.
  double contacts_per_particle = 0.0;
  std::int64_t neighbour_pairs = 0;     // entries of the neighbour list at the end
  std::int64_t neighbour_rebuilds = 0;  // during the timed steps
  std::int64_t neighbour_builds_total = 0;
  double peak_rss_mb = 0.0;             // peak resident set of the process [MiB]
  double peak_rss_bytes_per_particle = 0.0;
  double kinetic_energy_j = 0.0;        // at the end, for before/after comparisons
  double min_contact_ratio = 1.0;       // smallest d / (R_i + R_j) reached
  double mean_z_m = 0.0;                // mean particle height at the end [m]
};

// Throws InputError on invalid options and RunError when the run becomes unstable.
BenchResult RunFibreBedBench(const BenchOptions& options);

// Peak resident set size of this process [bytes] (VmHWM, else getrusage), and a reset of
// the peak to the current resident set where Linux allows it (/proc/self/clear_refs);
// returns false when it could not reset.
double PeakRssBytes();
bool ResetPeakRss();

}  // namespace fibrenet::bench
