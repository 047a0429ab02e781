// The one place that knows whether OpenMP is on. Without it the engine runs one thread
// and the `#pragma omp` lines elsewhere are ignored by the compiler.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace fibrenet {

inline int ThreadCount() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

inline int ThreadId() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

// Threads of the enclosing parallel region (1 outside one).
inline int TeamSize() {
#ifdef _OPENMP
  return omp_get_num_threads();
#else
  return 1;
#endif
}

inline void SetThreadCount(int n) {
#ifdef _OPENMP
  if (n > 0) omp_set_num_threads(n);
#else
  (void)n;
#endif
}

// Sets the thread count for its scope and restores the previous one when it ends.
class ScopedThreadCount {
 public:
  explicit ScopedThreadCount(int n) : saved_(ThreadCount()) { SetThreadCount(n); }
  ~ScopedThreadCount() { SetThreadCount(saved_); }
  ScopedThreadCount(const ScopedThreadCount&) = delete;
  ScopedThreadCount& operator=(const ScopedThreadCount&) = delete;

 private:
  int saved_;
};

// The share [first, end) of n iterations that `thread` of a team of `team` takes under
// OpenMP's static schedule without a chunk size, as libgomp splits it: n / team each, the
// first n % team threads one more. A loop over a subset of the particles that takes, on each
// thread, the members of that thread's share of all of them sums its reductions in the order
// a loop over all of them would.
inline std::pair<std::int64_t, std::int64_t> StaticShare(std::int64_t n, int thread, int team) {
  const std::int64_t each = n / team, extra = n % team, t = thread;
  const std::int64_t first = t * each + std::min(t, extra);
  return {first, first + each + (t < extra ? 1 : 0)};
}

// Worlds with fewer particles than this step on one thread: below it the fork and join of
// each parallel region costs more than the work it shares (docs/performance.md), and a core
// taken by another process stalls every barrier. Serial steps are also bit-identical
// whatever the thread count.
constexpr std::size_t kParallelMinParticles = 4096;

// The rule above as a test, for the `if` clause of a per-particle loop that runs outside a
// SerialWhenSmall scope (e.g. every step of a test rig, beside Simulation::Step).
inline bool ThreadsPay(std::size_t particles) { return particles >= kParallelMinParticles; }

// Limits the parallel regions started in its scope to one thread when `particles` is below
// kParallelMinParticles; restores the thread count when it ends.
class SerialWhenSmall {
 public:
  explicit SerialWhenSmall(std::size_t particles) {
    if (!ThreadsPay(particles) && ThreadCount() > 1) {
      saved_ = ThreadCount();
      SetThreadCount(1);
    }
  }
  ~SerialWhenSmall() { SetThreadCount(saved_); }
  SerialWhenSmall(const SerialWhenSmall&) = delete;
  SerialWhenSmall& operator=(const SerialWhenSmall&) = delete;

 private:
  int saved_ = 0;  // 0: nothing to restore
};

}  // namespace fibrenet
