# Vector instructions of the build: FIBRENET_SIMD = AUTO (the best level the build machine
# runs), AVX2 or BASE (the compiler's default target, e.g. SSE2 on any x86-64). As in other
# MD codes, the level is fixed at configure time; a binary built for AVX2 refuses, with a
# clear message, to start on a processor without it (app/cpu_check.cpp).
#
# AVX2 without fused multiply-add: a 4-wide double vector (the bond lanes,
# engine/interactions/beam_bond_lanes.h) is one register instead of two, while every
# operation keeps its IEEE rounding, so results are the same bit for bit at every level.
# Contraction into FMA is off everywhere for the same reason (and it lengthened the bond's
# dependency chain on this AMD EPYC, docs/performance.md).
set(FIBRENET_SIMD "AUTO" CACHE STRING "Vector instructions: AUTO, AVX2 or BASE")
set_property(CACHE FIBRENET_SIMD PROPERTY STRINGS AUTO AVX2 BASE)

set(fibrenet_simd_level "${FIBRENET_SIMD}")
if(fibrenet_simd_level STREQUAL "AUTO")
  set(fibrenet_simd_level "BASE")
  if(CMAKE_SYSTEM_PROCESSOR MATCHES "^(x86_64|AMD64|amd64)$")
    try_run(avx2_runs avx2_compiles ${CMAKE_BINARY_DIR}/simd_probe
            ${CMAKE_CURRENT_LIST_DIR}/avx2_probe.cpp)
    if(avx2_compiles AND avx2_runs EQUAL 0)
      set(fibrenet_simd_level "AVX2")
    endif()
  endif()
elseif(NOT fibrenet_simd_level MATCHES "^(AVX2|BASE)$")
  message(FATAL_ERROR "FIBRENET_SIMD=${FIBRENET_SIMD}: must be AUTO, AVX2 or BASE")
endif()

add_compile_options(-ffp-contract=off)
if(fibrenet_simd_level STREQUAL "AVX2")
  add_compile_options(-mavx2 -mno-fma)
endif()
set(FIBRENET_SIMD_LEVEL "${fibrenet_simd_level}")
message(STATUS "fibrenet SIMD level: ${FIBRENET_SIMD_LEVEL} (FIBRENET_SIMD=${FIBRENET_SIMD})")
