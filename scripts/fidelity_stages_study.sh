#!/usr/bin/env bash
# The stage-by-stage speed-against-error study of docs/performance.md on
# campaigns/scenes/study-fidelity-stages.toml. Each seed's network is made once; every variant
# then starts from the state before the stage it changes, so it differs from the default run
# only by that stage (common random numbers):
#  - test settings, from the pressed snapshot: tensile.loading_steps 400000 (reference),
#    200000 (default), 100000; compression.loading_steps 40000 (reference), 20000 (default),
#    10000;
#  - pressing settings, from the formed snapshot: pressing.mass_scale 10000 against the
#    default 1000, and fidelity.time_step_safety 0.8 against the default 0.5 (the tests choose
#    their own time step from their loading steps, so that setting reaches the pressing only).
# Each stage has its own noise probe, a change of the discretisation far below any in the
# table: the tests with 0.5% fewer loading steps; the pressing with the time step 0.2% shorter
# (fidelity.time_step_safety 0.499).
# Seeds 1-4, one run per core on one thread each. A run whose result is already in OUT_DIR is
# not repeated, so an interrupted study goes on where it stopped.
# Usage: scripts/fidelity_stages_study.sh OUT_DIR [FIBRENET]   (about 30 min on 2 cores)
# Then:  /usr/bin/python3 scripts/plot_fidelity_stages.py OUT_DIR docs/figures
set -euo pipefail
source "$(dirname "$0")/study_start.sh" campaigns/scenes/study-fidelity-stages.toml "$@"
run() {  # NAME SEED [ARGS ...]
  local name=$1 seed=$2
  shift 2
  [[ -s ${name}_s$seed.json ]] && return 0
  "$fibrenet" run "$scene" --json --threads 1 --set seed="$seed" "$@" \
    > "${name}_s$seed.json" 2> "${name}_s$seed.err"
}
series() {  # SEED
  local seed=$1 formed=network_s$1/snapshots/forming.h5 pressed=network_s$1/snapshots/pressing.h5
  run default "$seed" --out "network_s$seed"
  run tensile_400000 "$seed" --from "$pressed" --set tensile.loading_steps=400000
  run tensile_100000 "$seed" --from "$pressed" --set tensile.loading_steps=100000
  run tensile_probe "$seed" --from "$pressed" --set tensile.loading_steps=199000
  run compression_40000 "$seed" --from "$pressed" --set compression.loading_steps=40000
  run compression_10000 "$seed" --from "$pressed" --set compression.loading_steps=10000
  run compression_probe "$seed" --from "$pressed" --set compression.loading_steps=19900
  run pressing_probe "$seed" --from "$formed" --set fidelity.time_step_safety=0.499
  run pressing_mass_10000 "$seed" --from "$formed" --set pressing.mass_scale=10000
  run pressing_safety_0.8 "$seed" --from "$formed" --set fidelity.time_step_safety=0.8
}
(series 1; series 3) &
(series 2; series 4) &
wait_all
echo "stage-by-stage fidelity study written to $out"
