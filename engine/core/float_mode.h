// Floating-point mode of the engine's threads.
//
// Denormal results are flushed to zero (FTZ) and denormal inputs read as zero (DAZ).
// Quantities that decay geometrically in a quasi-static test (damped relative motion) reach
// the denormal range, where each operation takes a slow microcode path: the ZD compression of
// the generic tissue ran at half the bench's rate. The bits live in each thread's MXCSR, so
// they are set on the calling thread (threads it starts later inherit them) and on every
// thread of the OpenMP team already running. Nothing the engine reports depends on values
// below 2.2e-308.
#pragma once

#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

namespace fibrenet {

inline void FlushDenormalsToZeroOnThisThread() {
#if defined(__SSE2__)
  constexpr unsigned kDenormalsAreZero = 0x0040;  // MXCSR bit DAZ
  _mm_setcsr(_mm_getcsr() | _MM_FLUSH_ZERO_ON | kDenormalsAreZero);
#endif
}

// On this thread and on every thread of the OpenMP team.
void FlushDenormalsToZero();

// True when this thread flushes denormal results to zero.
inline bool FlushesDenormals() {
#if defined(__SSE2__)
  return (_mm_getcsr() & _MM_FLUSH_ZERO_ON) != 0;
#else
  return false;
#endif
}

}  // namespace fibrenet
