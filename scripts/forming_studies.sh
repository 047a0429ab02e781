#!/usr/bin/env bash
# The forming studies of docs/network.md on campaigns/scenes/study-small-cell.toml (each run
# under 4096 particles steps on one thread, so two runs share the 2 cores):
#  - acceleration: the example settings (mass 100, gravity 100, stiffness 0.01) against a
#    10x less accelerated reference (mass 10, gravity 10, stiffness 0.1), seeds 1-3, both
#    pressed the same way;
#  - consistency: forming alone at 1% (seeds 1-6) and 0.15% (seeds 1-3).
# Usage: scripts/forming_studies.sh OUT_DIR [FIBRENET]   (about 1.5 h on 2 cores)
# Then:  /usr/bin/python3 scripts/plot_forming_studies.py OUT_DIR docs/figures
set -euo pipefail
source "$(dirname "$0")/study_start.sh" campaigns/scenes/study-small-cell.toml "$@"
# Forming alone: the scene without its [pressing] tables.
python3 -c "import re,sys; print(re.sub(r'\n\[pressing\].*\Z', '\n', open(sys.argv[1]).read(), flags=re.S))" \
  "$scene" > formed-only.toml
run() { local name=$1; shift; "$fibrenet" run "$@" --json --threads 1 > "$name.json" 2> "$name.err"; }
reference="--set forming.mass_scale=10 --set forming.gravity_scale=10 --set forming.stiffness_scale=0.1"
{
  for seed in 1 2 3; do run "acc_$seed" "$scene" --set seed=$seed --set pressing.speed_m_per_s=0.2; done
  for seed in 1 2 3; do
    # shellcheck disable=SC2086
    run "ref_$seed" "$scene" --set seed=$seed --set pressing.speed_m_per_s=0.2 $reference
  done
} &
{
  for seed in 1 2 3 4 5 6; do run "c100_$seed" formed-only.toml --set seed=$seed; done
  for seed in 1 2 3; do
    run "c015_$seed" formed-only.toml --set seed=$seed --set forming.consistency_percent=0.15
  done
} &
wait_all
echo "forming studies written to $out"
