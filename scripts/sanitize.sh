#!/usr/bin/env bash
# The sanitizer job: builds fibrenet, its tests and the fuzz targets with AddressSanitizer,
# LeakSanitizer and UndefinedBehaviorSanitizer (clang, -O1, assertions on) in build-asan/,
# runs the fast tests under them, then fuzzes the scene and campaign readers from the same
# tree (scripts/fuzz.sh build-asan). Exits non-zero on any sanitizer report, failed test or
# fuzzer finding. About 18 minutes on 2 idle cores (docs/reliability.md).
# Usage: scripts/sanitize.sh     (after scripts/setup.sh, which installs the build dependencies;
#                                 this script installs clang and its runtimes)
#        FIBRENET_JOBS=N scripts/sanitize.sh   (parallel jobs; default: every core)
set -euo pipefail
cd "$(dirname "$0")/.."

# clang, its runtime libraries (the sanitizers, libFuzzer), which clang only recommends, and
# its OpenMP.
packages=(clang libclang-rt-dev libomp-dev)
source scripts/install_packages.sh
install_packages "${packages[@]}"

jobs="${FIBRENET_JOBS:-$(nproc)}"
start=$SECONDS
# clang compiles the sanitized code 1.3 to 2.3 times faster than gcc, and one tree then serves
# the tests and the fuzzers: fuzzer-no-link gives every library the coverage libFuzzer steers
# by. Debug keeps the assertions; -O1 and line tables only (-g1) are enough for readable
# sanitizer reports.
flags="-O1 -g1 -fno-omit-frame-pointer -fsanitize=address,undefined,fuzzer-no-link"
flags+=" -fno-sanitize-recover=undefined"
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DFIBRENET_BUILD_BENCHMARKS=OFF -DFIBRENET_BUILD_FUZZERS=ON \
  -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_C_FLAGS_DEBUG= \
  -DCMAKE_CXX_FLAGS_DEBUG= -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined" > /dev/null
cmake --build build-asan -j "$jobs"
echo "== sanitize: build $((SECONDS - start)) s"

# Leaks are findings, except Open MPI's own (tests/sanitizers/lsan.supp).
supp="$PWD/tests/sanitizers/lsan.supp"
export LSAN_OPTIONS="suppressions=$supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"

# Left out: the long pipeline, creping, stage-cache and command-line runs and the longest
# validation cases (2 s or more each in a Release build; those timed under the sanitizers took
# 26 s to 14 minutes); the Release ctest of scripts/setup.sh runs them. The MPI test runs on
# its own.
slow=(
  'SceneCampaign\..*'
  'ThroughAir\..*'
  'StageCache\..*'
  'StageSnapshot\.ContinuesARunBitForBit'
  'Embossing\..*'
  'Pipeline\..*'
  'VirtualTests\..*'
  'NetworkChecks\..*'
  'ZdCompression\.(StopsAtTheTargetPressure|TheSlowToeKeepsAPressedSheetQuasiStatic|ALoopStoppedAtALowPressureReturnsNoMoreWorkThanItTook|SteppedMovesShrinkWhereTheWebIsMet|ALightLoopIsDampedAsTheWebIs)'
  'ZdCompression\.(TheTaperedApproachSlowsAsThePressureRises|FeedbackFromTheWindowStartSpeedsTheWindowUp|SteppedLoadingFollowsTheSlowContinuousCurve|AnOpenStripIsLoadedOverItsFootprintNotTheCell)'
  'LooseMat\..*'
  'Relief\.SphereRestsOnePocketDepthLowerOverAPocket'
  'Creping\..*'
  'Validation/BeamCases\..*/(cantilever_elastica|euler_buckling|bending_frequency) .*'
  'Validation/ParticleCases\..*/(rigid_motion|conservation) .*'
  'campaigns_(run_snapshots|kill_resume|cli|report|concurrent_readers|disk_full.*)_test'
)
mpi_test='campaigns_mpi_matches_serial_test'
exclude="^($(IFS='|'; echo "${slow[*]}")|$mpi_test)\$"
start=$SECONDS
# A test that runs past 5 minutes here (the longest fast one takes 30 s) is a long run missing
# from the list above: it fails, naming itself, rather than eat the job's time.
ASAN_OPTIONS="detect_leaks=1" \
  ctest --test-dir build-asan --output-on-failure -j "$jobs" -E "$exclude" --timeout 300
# Open MPI's libraries have no frame pointers and unload their components before the leak
# check: only whole stacks (the slow unwinder) show that a leak is Open MPI's.
ASAN_OPTIONS="detect_leaks=1:fast_unwind_on_malloc=0" \
  ctest --test-dir build-asan --output-on-failure -R "^$mpi_test\$"
echo "== sanitize: tests $((SECONDS - start)) s"

scripts/fuzz.sh build-asan
