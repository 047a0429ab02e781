#!/usr/bin/env bash
# The creping study of docs/creping.md on campaigns/scenes/study-creping.toml: one formed and
# pressed sheet, creped at creping angles 75, 85, 95 deg x adhesion strengths 3, 10, 30 mN
# (peel = shear), and at 30 and 60 m/s. Creping starts from the pressing snapshot, so every
# run creps the same sheet.
# Usage: scripts/creping_study.sh OUT_DIR [FIBRENET]   (about 15 min on 2 cores)
# Then:  /usr/bin/python3 scripts/plot_creping_study.py OUT_DIR docs/figures
set -euo pipefail
source "$(dirname "$0")/study_start.sh" campaigns/scenes/study-creping.toml "$@"
"$fibrenet" run "$scene" --out base --json > base.json 2> base.err
run() {
  local name=$1; shift
  "$fibrenet" run "$scene" --from base/snapshots/pressing.h5 --json --out "$name" "$@" \
    > "$name.json" 2> "$name.err"
}
for angle in 75 85 95; do
  for adhesion in 3 10 30; do
    run "angle${angle}_adh${adhesion}" --set creping.creping_angle_deg=$angle \
      --set creping.adhesion.F_r0_mN=$adhesion --set creping.adhesion.F_s0_mN=$adhesion
  done
done
run speed60 --set creping.yankee_speed_m_per_s=60
echo "creping study written to $out"
