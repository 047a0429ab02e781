#!/usr/bin/env bash
# The creping study of docs/creping.md on webs the coating holds to the blade: the generic
# tissue (generic-tissue-creped.toml) with fibre-fibre bonds of shear strength 25 mN, pressed to
# 89 um (the web of scripts/delamination_generic.sh), creped at creping angles 75, 85, 95 deg on
# coatings of 10, 7.5 and 5 MPa (shear modulus 0.3 of it; toughness 33.7, 44.9, 67.4 J/m^2: the
# least coating that holds the 5 and 10 mm strips against the reel's draw, and two stronger ones),
# 30 m/s, run-in 500 um.
# One thread a run, two side by side; a run whose JSON is already in OUT_DIR is kept, so an
# interrupted study goes on where it stopped.
# Usage: scripts/creping_study_held.sh OUT_DIR [FIBRENET]   (about 35 min on 2 cores)
# Then:  /usr/bin/python3 scripts/plot_creping_study_held.py OUT_DIR docs/figures
set -euo pipefail
source "$(dirname "$0")/study_start.sh" campaigns/scenes/generic-tissue-creped.toml "$@"

run_kept form "$scene" --until forming --threads 2
# Pressed on one thread, as scripts/delamination_generic.sh presses it.
run_kept p89s "$scene" --from form/snapshots/forming.h5 --until pressing --threads 1 \
  --set pressing.target_thickness_um=89 --set pressing.bonding.F_s0_mN=25

for modulus in 10 7.5 5; do
  shear=$(awk "BEGIN { print 0.3 * $modulus }")
  for angle in 75 85 95; do
    run_kept "angle${angle}_e${modulus}" "$scene" --from p89s/snapshots/pressing.h5 \
      --until creping --threads 1 --set creping.creping_angle_deg="$angle" \
      --set creping.adhesion.modulus_MPa="$modulus" \
      --set creping.adhesion.shear_modulus_MPa="$shear" --set creping.run_in_length_um=500 &
    throttle
  done
done
wait_all
echo "creping study on held webs written to $out"
