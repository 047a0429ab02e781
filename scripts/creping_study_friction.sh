#!/usr/bin/env bash
# The blade's friction and the reel's hold on the steady state of creping (docs/creping.md,
# "The brakes on the sheet leaving the blade"): the 5 mm x 2 mm strip of the generic tissue
# (generic-tissue-creped.toml) pressed to 89 um, with fibre-fibre bonds of 25 mN on a 44.9
# J/m^2 coating (7.5 MPa: a web the coating holds and the blade tears) and of 100 mN on a
# 134.9 J/m^2 coating (2.5 MPa: a web lifted whole at the tip), creped at 85 deg, 30 m/s,
# run-in 500 um, with the sheet's friction on the steel at each of MUS (default "1.0"; the
# contacts' 0.3 is the runs of "Strong webs on strong coatings") and the reel's draw at each
# relaxation time of TAUS_US (default "2", the scene's; shorter holds the drawn sheet closer
# to the reel speed).
# One thread a run, two side by side; a run whose JSON is already in OUT_DIR is kept.
# Usage: MUS="0.3 1.0" TAUS_US="2 0.2" scripts/creping_study_friction.sh OUT_DIR [FIBRENET]
#        (measured on 2 cores beside other jobs: forming 23 min, each pressing 30-40 min; a
#        creping run of the 5 mm strip 28-32 min, two side by side)
set -euo pipefail
source "$(dirname "$0")/study_start.sh" campaigns/scenes/generic-tissue-creped.toml "$@"

run_kept form5 "$scene" --set cell.size_x_mm=5 --set cell.size_y_mm=2 --until forming
run_kept p25 "$scene" --from form5/snapshots/forming.h5 --until pressing \
  --set pressing.target_thickness_um=89 --set pressing.bonding.F_s0_mN=25
run_kept p100 "$scene" --from form5/snapshots/forming.h5 --until pressing \
  --set pressing.target_thickness_um=89 --set pressing.bonding.F_s0_mN=100 \
  --set pressing.bonding.F_r0_mN=100

for tau in ${TAUS_US:-2}; do
  for mu in ${MUS:-1.0}; do
    for web in "25 7.5" "100 2.5"; do
      read -r bond modulus <<< "$web"
      shear=$(awk "BEGIN { print 0.3 * $modulus }")
      run_kept "w${bond}_mu${mu}_tau${tau}" "$scene" --from "p${bond}/snapshots/pressing.h5" \
        --until creping --threads 1 --set creping.blade_friction_mu="$mu" \
        --set creping.takeaway_time_us="$tau" --set creping.adhesion.modulus_MPa="$modulus" \
        --set creping.adhesion.shear_modulus_MPa="$shear" --set creping.run_in_length_um=500 &
      throttle
    done
  done
done
wait_all
echo "blade friction and reel study written to $out"
