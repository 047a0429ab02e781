// Wall-clock stopwatch for the reports of stages, validation cases and benchmarks.
#pragma once

#include <chrono>

namespace fibrenet {

class Stopwatch {
 public:
  // Seconds since construction or the last Restart().
  double Seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  // Seconds since construction or the last Restart(), then starts again from now.
  double Restart() {
    const auto now = std::chrono::steady_clock::now();
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    start_ = now;
    return elapsed;
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace fibrenet
