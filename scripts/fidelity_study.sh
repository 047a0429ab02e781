#!/usr/bin/env bash
# The speed-against-error study of docs/performance.md on campaigns/scenes/study-fidelity.toml
# (the small-cell proxy of the generic tissue with its tests). One fidelity setting is varied
# at a time from the scene's defaults; each factor's finest value is its reference:
#  - particle_spacing_diameters 0.5 (reference), 1 (default), 2;
#  - time_step_safety 0.25 (reference), 0.5 (default), 0.8;
#  - pressing.mass_scale 100 (reference), 1000 (default), 10000.
# Seeds 1 and 2, one run per core on one thread each. A control run with the time step 0.2%
# shorter (time_step_safety 0.499: a change of the discretisation error far below any in the
# table) measures how far a mere perturbation moves the metrics of these chaotic packings:
# errors at or below that floor are noise, not fidelity. (Thread count is no such probe: one
# and two threads give bit-identical results.)
# Usage: scripts/fidelity_study.sh OUT_DIR [FIBRENET]   (about 45 min on 2 cores)
# Then:  /usr/bin/python3 scripts/plot_fidelity_study.py OUT_DIR docs/figures
set -euo pipefail
source "$(dirname "$0")/study_start.sh" campaigns/scenes/study-fidelity.toml "$@"
run() {  # NAME SEED THREADS [--set KEY=VALUE ...]
  local name=$1 seed=$2 threads=$3
  shift 3
  "$fibrenet" run "$scene" --json --threads "$threads" --set seed="$seed" "$@" \
    > "${name}_s$seed.json" 2> "${name}_s$seed.err"
}
series() {  # SEED
  local seed=$1
  run default "$seed" 1
  run spacing_0.5 "$seed" 1 --set fidelity.particle_spacing_diameters=0.5
  run spacing_2 "$seed" 1 --set fidelity.particle_spacing_diameters=2
  run safety_0.25 "$seed" 1 --set fidelity.time_step_safety=0.25
  run safety_0.8 "$seed" 1 --set fidelity.time_step_safety=0.8
  run pressing_mass_100 "$seed" 1 --set pressing.mass_scale=100
  run pressing_mass_10000 "$seed" 1 --set pressing.mass_scale=10000
  # The two cheapest settings together, against the defaults: the campaigns' explore level.
  run explore "$seed" 1 --set fidelity.time_step_safety=0.8 --set pressing.mass_scale=10000
}
series 1 &
series 2 &
wait_all
run control_perturbed 1 1 --set fidelity.time_step_safety=0.499 &
run control_perturbed 2 1 --set fidelity.time_step_safety=0.499 &
wait_all
echo "fidelity study written to $out"
