#include "engine/pipeline/progress.h"

#include <algorithm>

namespace fibrenet::pipeline {

std::int64_t RunUntil(Simulation& sim, std::int64_t max_steps, std::int64_t check_every,
                      const std::function<bool()>& done, const std::function<std::string()>& status,
                      const Progress& progress) {
  Stopwatch clock;
  double next_report = progress.interval_s;
  std::int64_t steps = 0;
  while (steps < max_steps) {
    const std::int64_t chunk = std::min(check_every, max_steps - steps);
    sim.Run(chunk);
    steps += chunk;
    if (done()) break;
    if (progress.report && clock.Seconds() >= next_report) {
      progress.Say(status());
      next_report = clock.Seconds() + progress.interval_s;
    }
  }
  return steps;
}

}  // namespace fibrenet::pipeline
