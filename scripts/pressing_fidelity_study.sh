#!/usr/bin/env bash
# The pressing's time-step safety resolved with many paired seeds (docs/performance.md,
# "The pressing with many seeds"). campaigns/scenes/study-fidelity-stages.toml, each seed
# formed once; the pressing then runs from the formed snapshot at the default
# fidelity.time_step_safety 0.5 and at 0.8, each followed by the tests that the pressing's
# key metrics need and nothing else:
#  - seeds 1 to ZD_SEEDS: the MD tensile test and the ZD compression (the ZD modulus needs
#    about 5 paired seeds, stage-by-stage study);
#  - the other seeds up to SEEDS: the tensile test only (the tensile modulus needs about 38).
# One run per core on one thread each; a run whose result is in OUT_DIR is not repeated.
# Usage: scripts/pressing_fidelity_study.sh OUT_DIR [FIBRENET]      (about 45 min on 2 cores)
#        SEEDS (default 36) and ZD_SEEDS (default 10) from the environment
# Then:  /usr/bin/python3 scripts/plot_pressing_fidelity.py OUT_DIR docs/figures
set -euo pipefail
seeds=${SEEDS:-36}
zd_seeds=${ZD_SEEDS:-10}
source "$(dirname "$0")/study_start.sh" campaigns/scenes/study-fidelity-stages.toml "$@"
# The scene's tests are its last tables, [compression] then [softness].
sed '/^\[softness\]/,$d' "$scene" > tensile_compression.toml
sed '/^\[compression\]/,$d' "$scene" > tensile.toml
grep -q '^\[compression\]' tensile_compression.toml
if grep -q '^\[compression\]\|^\[softness\]' tensile.toml; then exit 1; fi
run() {  # SCENE NAME SEED [ARGS ...]
  local scene=$1 name=$2 seed=$3
  shift 3
  [[ -s ${name}_s$seed.json ]] && return 0
  "$fibrenet" run "$scene" --json --threads 1 --set seed="$seed" "$@" \
    > "${name}_s$seed.json" 2> "${name}_s$seed.err"
}
series() {  # SEED
  local seed=$1 tests=$PWD/tensile.toml
  ((seed <= zd_seeds)) && tests=$PWD/tensile_compression.toml
  run "$tests" default "$seed" --out "network_s$seed"
  run "$tests" pressing_safety_0.8 "$seed" --from "network_s$seed/snapshots/forming.h5" \
    --set fidelity.time_step_safety=0.8
}
odd() { for ((s = 1; s <= seeds; s += 2)); do series "$s"; done; }
even() { for ((s = 2; s <= seeds; s += 2)); do series "$s"; done; }
odd &
even &
wait_all
echo "pressing fidelity study ($seeds seeds, ZD on 1-$zd_seeds) written to $out"
