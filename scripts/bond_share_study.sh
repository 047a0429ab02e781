#!/usr/bin/env bash
# Bonds per crossing against bonds per particle pair (docs/network.md, "Bonds per crossing"):
# campaigns/scenes/study-fidelity.toml (the 1 mm proxy of the generic tissue with its tests)
# at particle spacings of 1 and 0.5 diameters, with the fibre-fibre bond properties belonging
# to each particle bond (share = "particle", the scenes' default) or to each crossing
# ("crossing"), and per crossing with twice the tensile loading steps. Seeds 1 and 2, one run
# per core on one thread each; runs already in OUT_DIR are kept.
# Usage: scripts/bond_share_study.sh OUT_DIR [FIBRENET]   (about 30 min on 2 cores)
# Then:  /usr/bin/python3 scripts/plot_bond_share_study.py OUT_DIR docs/figures
set -euo pipefail
source "$(dirname "$0")/study_start.sh" campaigns/scenes/study-fidelity.toml "$@"
run() {  # SCENE NAME SEED [--set KEY=VALUE ...]; a run whose result is there is skipped
  local scene=$1 name=$2 seed=$3
  shift 3
  [ -s "${name}_s$seed.json" ] && return 0
  "$fibrenet" run "$scene" --json --threads 1 --set seed="$seed" "$@" \
    > "${name}_s$seed.json" 2> "${name}_s$seed.err"
}
# --set takes numbers only: the per-crossing scene is a copy with the share written in.
sed 's/^\[pressing.bonding\]$/&\nshare = "crossing"/' "$scene" > crossing.toml
grep -q '^share = "crossing"$' crossing.toml
series() {  # SEED
  local seed=$1 share spacing
  for share in crossing particle; do
    for spacing in 1 0.5; do
      local share_scene=$scene
      [ "$share" = crossing ] && share_scene=$PWD/crossing.toml
      run "$share_scene" "${share}_${spacing}" "$seed" \
        --set fidelity.particle_spacing_diameters="$spacing"
    done
  done
  # Per crossing at 0.5 the particle bonds are soft and the tensile guard reads 0.017-0.021
  # at the scene's 200,000 loading steps: both spacings again at twice the steps.
  for spacing in 1 0.5; do
    run "$PWD/crossing.toml" "crossing_slow_${spacing}" "$seed" \
      --set fidelity.particle_spacing_diameters="$spacing" --set tensile.loading_steps=400000
  done
}
series 1 &
series 2 &
wait_all
echo "bond share study written to $out"
