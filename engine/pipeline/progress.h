// Progress lines and run control shared by the pipeline stages. A stage reports through a
// callback (the CLI prints to stderr); the engine itself never prints.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "engine/core/simulation.h"
#include "engine/core/stopwatch.h"

namespace fibrenet::pipeline {

struct Progress {
  std::function<void(const std::string&)> report;  // may be empty: silent
  double interval_s = 5.0;                          // wall time between periodic lines

  void Say(const std::string& line) const {
    if (report) report(line);
  }
};

// Steps `sim` in chunks of `check_every` steps until `done()` is true (checked after each
// chunk) or `max_steps` have run; prints `status()` every progress interval. Returns the
// number of steps run.
std::int64_t RunUntil(Simulation& sim, std::int64_t max_steps, std::int64_t check_every,
                      const std::function<bool()>& done, const std::function<std::string()>& status,
                      const Progress& progress);

}  // namespace fibrenet::pipeline
