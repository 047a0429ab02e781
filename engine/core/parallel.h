// The one place that knows whether OpenMP is on. Without it the engine runs one thread
// and the `#pragma omp` lines elsewhere are ignored by the compiler.
#pragma once

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

inline void SetThreadCount(int n) {
#ifdef _OPENMP
  if (n > 0) omp_set_num_threads(n);
#else
  (void)n;
#endif
}

}  // namespace fibrenet
