#!/usr/bin/env bash
# The delamination study of docs/creping.md on the generic tissue: one formed web
# (generic-tissue-creped.toml) pressed to 89 um twice, with fibre-fibre bonds of shear strength
# 5 mN (the scene's) and 25 mN; each web's MD tensile stiffness E h from a tensile test on its
# pressing snapshot; then both creped at 30 m/s and 7 mN on coatings of several moduli (the
# shear modulus 0.3 of it), i.e. several toughnesses, with the blade at full speed from the
# start and with a run-in of 500 um (the leading end zone). One thread a run, two side by side; a
# run whose JSON is already in OUT_DIR is kept, so an interrupted study goes on where it stopped.
# Usage: scripts/delamination_generic.sh OUT_DIR [FIBRENET]   (about 60 min on 2 cores)
# Then:  /usr/bin/python3 scripts/plot_delamination_criterion.py STUDY_OUT OUT_DIR docs/figures
set -euo pipefail
source "$(dirname "$0")/study_start.sh" campaigns/scenes/generic-tissue-creped.toml "$@"

run_kept form "$scene" --until forming --threads 2
press=(--from form/snapshots/forming.h5 --until pressing --threads 1
       --set pressing.target_thickness_um=89)
run_kept p89 "$scene" "${press[@]}" &
run_kept p89s "$scene" "${press[@]}" --set pressing.bonding.F_s0_mN=25 &
wait_all

write_tensile_scene
for web in p89 p89s; do
  run_kept "t_$web" tensile.toml --from "$web/snapshots/pressing.h5" --threads 1 &
done
wait_all

# web:coating modulus [MPa], in the order that brackets the lift-off first; the blade at full
# speed from the start (NAME), then with a run-in over the leading end zone (NAME_r500).
for run_in in 0 500; do
  for job in p89s:15 p89:100 p89s:10 p89:50 p89s:7.5 p89:70 p89s:12 p89:30 p89s:30 p89s:5; do
    web=${job%:*} modulus=${job#*:}
    shear=$(awk "BEGIN { print 0.3 * $modulus }")
    name="${web}_e${modulus}"
    if (( run_in > 0 )); then name+="_r${run_in}"; fi
    run_kept "$name" "$scene" --from "$web/snapshots/pressing.h5" --until creping --threads 1 \
      --set creping.adhesion.modulus_MPa="$modulus" \
      --set creping.adhesion.shear_modulus_MPa="$shear" --set creping.run_in_length_um="$run_in" &
    throttle
  done
done
wait_all
echo "generic-tissue delamination study written to $out"
