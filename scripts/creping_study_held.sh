#!/usr/bin/env bash
# The creping study of docs/creping.md on webs the coating holds to the blade: the generic
# tissue (generic-tissue-creped.toml) with fibre-fibre bonds of shear strength 25 mN, pressed to
# 89 um (the web of scripts/delamination_generic.sh), creped at creping angles 75, 85, 95 deg on
# coatings of 10, 7.5 and 5 MPa (shear modulus 0.3 of it; toughness 33.7, 44.9, 67.4 J/m^2, all
# above the draw's lift-off), 30 m/s, run-in 500 um. One thread a run, two side by side; a run
# whose JSON is already in OUT_DIR is kept, so an interrupted study goes on where it stopped.
# Usage: scripts/creping_study_held.sh OUT_DIR [FIBRENET]   (about 45 min on 2 cores)
# Then:  /usr/bin/python3 scripts/plot_creping_study_held.py OUT_DIR docs/figures
set -euo pipefail
source "$(dirname "$0")/study_start.sh" campaigns/scenes/generic-tissue-creped.toml "$@"

# run NAME ARGS...: one fibrenet run into NAME/, its JSON in NAME.json, unless already there.
run() {
  local name=$1; shift
  [[ -s "$name.json" ]] && return 0
  "$fibrenet" run "$@" --out "$name" --json > "$name.json.part" 2> "$name.err"
  mv "$name.json.part" "$name.json"
}
# Keeps at most two runs going (wait -n also returns for a job that has already ended).
throttle() { while (( $(jobs -rp | wc -l) >= 2 )); do wait -n; done; }

run form "$scene" --until forming --threads 2
run p89s "$scene" --from form/snapshots/forming.h5 --until pressing --threads 2 \
  --set pressing.target_thickness_um=89 --set pressing.bonding.F_s0_mN=25

for modulus in 10 7.5 5; do
  shear=$(awk "BEGIN { print 0.3 * $modulus }")
  for angle in 75 85 95; do
    run "angle${angle}_e${modulus}" "$scene" --from p89s/snapshots/pressing.h5 --until creping \
      --threads 1 --set creping.creping_angle_deg="$angle" \
      --set creping.adhesion.modulus_MPa="$modulus" \
      --set creping.adhesion.shear_modulus_MPa="$shear" --set creping.run_in_length_um=500 &
    throttle
  done
done
wait_all
echo "creping study on held webs written to $out"
