// A build for AVX2 (cmake/simd.cmake) stops with a clear message on a processor without
// it, instead of dying on an illegal instruction somewhere. This file is compiled for the
// compiler's base target, and its check runs before the other static initialisers.
#include <cstdio>
#include <cstdlib>

#ifdef FIBRENET_NEEDS_AVX2
namespace {

__attribute__((constructor(101))) void RequireAvx2() {
  __builtin_cpu_init();  // a constructor may run before the processor model is read
  if (__builtin_cpu_supports("avx2")) return;
  std::fputs(
      "error: this fibrenet was built for AVX2 (FIBRENET_SIMD), which this processor lacks; "
      "rebuild with cmake -DFIBRENET_SIMD=BASE\n",
      stderr);
  std::_Exit(1);
}

}  // namespace
#endif
