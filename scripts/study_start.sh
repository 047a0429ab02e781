# The common start of the study scripts, sourced by them with their scene and arguments:
#   source "$(dirname "$0")/study_start.sh" SCENE "$@"      (run from the repository root)
# Reads OUT_DIR and the optional FIBRENET executable (default build/fibrenet), sets `out`,
# `fibrenet` and `scene` (both made absolute), creates OUT_DIR and moves into it, and defines
# wait_all, run_kept and throttle for the scripts that run series side by side, and
# write_tensile_scene for the creping studies. The caller has set -euo pipefail, so a missing
# OUT_DIR stops it with the usage line.
scene=$(realpath "$1")
shift
out=${1:?usage: $(basename "$0") OUT_DIR [FIBRENET]}
fibrenet=$(realpath "${2:-build/fibrenet}")
mkdir -p "$out"
cd "$out"

# Waits for every background job and fails if any of them failed (a bare `wait` returns 0).
wait_all() {
  local pid status=0
  for pid in $(jobs -p); do wait "$pid" || status=$?; done
  return "$status"
}

# run_kept NAME ARGS...: one fibrenet run into NAME/, its JSON in NAME.json, unless that is
# already there (an interrupted study goes on where it stopped).
run_kept() {
  local name=$1; shift
  [[ -s "$name.json" ]] && return 0
  "$fibrenet" run "$@" --out "$name" --json > "$name.json.part" 2> "$name.err"
  mv "$name.json.part" "$name.json"
}

# Keeps at most two background runs going (wait -n also returns for a job that has already
# ended).
throttle() { while (( $(jobs -rp | wc -l) >= 2 )); do wait -n; done; }

# Writes tensile.toml: the scene up to its [creping] table, with an MD tensile test from the
# pressing snapshot, for the pressed web's tensile stiffness E h (the creping studies).
write_tensile_scene() {
  sed '/^\[creping/,$d' "$scene" > tensile.toml
  printf '[tensile]\ndirection = "MD"\nloading_steps = 100000\nsamples = 100\n' >> tensile.toml
}
