#!/usr/bin/env bash
# The delamination study of docs/creping.md on campaigns/scenes/study-creping.toml: one formed
# and pressed sheet, creped at adhesion strengths 3, 5, 10 mN (peel = shear) on coatings of
# 10 and 100 MPa (shear modulus 0.3 of it) at Yankee speeds 15, 30 and 60 m/s: the coating's
# toughness against the scraped sheet's momentum flux rho_A V^2, and how far ahead of the
# blade the web comes off; and the pressed sheet's MD tensile stiffness E h (t_base), which the
# lift-off criterion of scripts/plot_delamination_criterion.py needs. Two runs side by side,
# one thread each.
# Usage: scripts/delamination_study.sh OUT_DIR [FIBRENET]   (about 10 min on 2 cores)
# Then:  /usr/bin/python3 scripts/plot_delamination_study.py OUT_DIR docs/figures
set -euo pipefail
source "$(dirname "$0")/study_start.sh" campaigns/scenes/study-creping.toml "$@"
"$fibrenet" run "$scene" --until pressing --out base --json --threads 2 > base.json 2> base.err
run() {
  local name=$1; shift
  "$fibrenet" run "$scene" --from base/snapshots/pressing.h5 --until creping --json --threads 1 \
    --out "$name" "$@" > "$name.json" 2> "$name.err"
}
for speed in 15 30 60; do
  for moduli in 10:3 100:30; do
    modulus=${moduli%:*}
    for strength in 3 5 10; do
      run "v${speed}_e${modulus}_f${strength}" --set creping.yankee_speed_m_per_s=$speed \
        --set creping.adhesion.modulus_MPa=$modulus \
        --set creping.adhesion.shear_modulus_MPa=${moduli#*:} \
        --set creping.adhesion.F_r0_mN=$strength --set creping.adhesion.F_s0_mN=$strength &
      if (( $(jobs -r | wc -l) >= 2 )); then wait -n; fi
    done
  done
done
write_tensile_scene
"$fibrenet" run tensile.toml --from base/snapshots/pressing.h5 --json --threads 1 --out t_base \
  > t_base.json 2> t_base.err &
wait_all
echo "delamination study written to $out"
