#!/usr/bin/env bash
# Fuzzes the scene and campaign readers: builds the libFuzzer targets of tests/fuzz/ (clang,
# with AddressSanitizer and UndefinedBehaviorSanitizer over the readers and every library they
# link) and runs each for FIBRENET_FUZZ_SECONDS (default 60) from the example files. Bad input
# must end in an InputError: any other exception, a crash, undefined behaviour, a leak or an
# input slower than 30 s is a finding; the script then exits 1 and the input lies in
# TREE/findings/. docs/reliability.md.
# Usage: scripts/fuzz.sh     (after scripts/setup.sh, which installs the build dependencies:
#                             configures and builds TREE = build-fuzz/)
#        scripts/fuzz.sh build-asan   (a tree configured by scripts/sanitize.sh, which already
#                                      has the fuzz targets' flags)
#        FIBRENET_FUZZ_SECONDS=600 FIBRENET_JOBS=1 scripts/fuzz.sh   (longer runs; build jobs)
set -euo pipefail
cd "$(dirname "$0")/.."

# clang, and its runtime libraries (libFuzzer, the sanitizers), which clang only recommends.
packages=(clang libclang-rt-dev)
source scripts/install_packages.sh
install_packages "${packages[@]}"

seconds="${FIBRENET_FUZZ_SECONDS:-60}"
jobs="${FIBRENET_JOBS:-$(nproc)}"
tree="${1:-build-fuzz}"
start=$SECONDS
if [ $# -eq 0 ]; then
  # The readers use neither threads nor MPI: both off keeps the build small (and libomp out).
  flags="-O1 -g -fno-omit-frame-pointer -fsanitize=fuzzer-no-link,address,undefined"
  flags+=" -fno-sanitize-recover=undefined"
  CC=clang CXX=clang++ cmake -S . -B "$tree" -DCMAKE_BUILD_TYPE=Debug \
    -DFIBRENET_BUILD_FUZZERS=ON -DFIBRENET_BUILD_TESTS=OFF -DFIBRENET_BUILD_BENCHMARKS=OFF \
    -DFIBRENET_ENABLE_OPENMP=OFF -DFIBRENET_ENABLE_MPI=OFF \
    -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" > /dev/null
fi
cmake --build "$tree" -j "$jobs" --target scene_fuzz campaign_fuzz
echo "== fuzz: build $((SECONDS - start)) s"

# The seed folders are read, never written: libFuzzer keeps new inputs in the first folder.
seeds=(campaigns/scenes campaigns/examples tests/app/data tests/campaigns/data tests/fuzz/regressions)
mkdir -p "$tree/findings"
status=0
for target in scene_fuzz campaign_fuzz; do
  corpus="$tree/corpus/$target"
  log="$tree/$target.log"
  mkdir -p "$corpus"
  echo "== $target: ${seconds} s (log: $log)"
  if "$tree/$target" -max_total_time="$seconds" -timeout=30 -print_final_stats=1 \
      -dict=tests/fuzz/toml.dict -artifact_prefix="$tree/findings/$target-" \
      "$corpus" "${seeds[@]}" > "$log" 2>&1; then
    grep -E "^(Done|stat::new_units_added)" "$log" || true
  else
    status=1
    echo "$target: FINDING (input kept in $tree/findings/; reproduce with" \
         "$tree/$target FILE):"
    grep -v "^#[0-9]" "$log" | tail -n 40
  fi
done
exit "$status"
