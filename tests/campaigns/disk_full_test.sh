#!/usr/bin/env bash
# A full disk, or a folder that cannot be written, in the middle of a run (docs/campaigns.md,
# "Full disk").
#
# The results database: the campaign stops with exit code 1 and a message that names the file
# and the cause; the file passes PRAGMA integrity_check; the candidate being written is left
# pending or running, and the same command with room again evaluates it, replays the others
# and ends with the results of an uninterrupted run. The disk fills up two ways: a file-size
# limit (ulimit -f, with SIGXFSZ ignored so that writes fail with EFBIG instead of killing
# the process), and a real full file system (ENOSPC), a 512 KiB tmpfs mounted in a private
# mount namespace, where unshare may make one (as root with CAP_SYS_ADMIN, or in a user
# namespace); without one that case is skipped, and said so.
#
# The stage cache folder and `run --out`: a stage cache folder that becomes unwritable
# mid-run costs the reuse, not the evaluation (exit 0, the same results); `run --out` whose
# snapshot folder cannot be made fails with exit code 1, naming it. As root a chmod does
# not stop writes, so the folder is replaced by a plain file, which stops them for anyone.
#
# With PART = full-snapshots it checks a full disk under the snapshots instead: a stage cache
# on a full tmpfs costs the reuse only, and `run --out` over the file-size limit fails with
# exit 1, naming the snapshot and the cause, and leaves no cut-off snapshot in its place.
# Usage: disk_full_test.sh FIBRENET DATA_DIR TINY_SCENE [full-snapshots]
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
fibrenet=$1
data=$2
scene=$3
part=${4:-}
case $part in "" | full-snapshots) ;; *) fail "unknown part '$part'; accepted: full-snapshots" ;; esac
enter_scratch

# with_file_limit KIB COMMAND...: COMMAND with files limited to KIB KiB (writes past it fail).
with_file_limit() { (trap '' XFSZ; ulimit -f "$1"; shift; exec "$@"); }
# on_tmpfs KIB DIR COMMAND...: COMMAND with a KIB KiB tmpfs mounted on DIR, in a private mount
# namespace; the files left there are copied to DIR.kept (the tmpfs goes with the namespace).
on_tmpfs() {
  mkdir -p "$2" "$2.kept"
  unshare --mount sh -c 'mount -t tmpfs -o "size=$1k" tmpfs "$0" || exit 99; shift
    rc=0; "$@" || rc=$?; cp -R "$0"/. "$0.kept"/; exit $rc' "$2" "$1" "${@:3}"
}
tmpfs_works() { on_tmpfs 64 probe true 2> /dev/null; }
count() { sqlite3 "$1" "SELECT count(*) FROM candidates WHERE $2;"; }
integrity() { [ "$(sqlite3 "$1" 'PRAGMA integrity_check;')" = ok ] || fail "$1: integrity_check"; }

# The stage cache campaign and `run` on the same fast tiny scene (the campaign's overrides).
cp "$scene" scene.toml
cp "$data/stage_cache.toml" stages.toml
fast_scene=(--set fidelity.particle_spacing_diameters=2 --set pressing.speed_m_per_s=0.5
            --set pressing.kinetic_work_tolerance=1.0)
# Results of the scene campaign: also without the scene's own wall time (metric.wall_s).
scene_results() {
  results "$1" stages | python3 -c 'import csv, sys
rows = list(csv.reader(sys.stdin))
k = rows[0].index("metric.wall_s")
csv.writer(sys.stdout, lineterminator="\n").writerows(r[:k] + r[k + 1:] for r in rows)'
}
"$fibrenet" campaign run stages.toml --db ref.db --stage-cache ref.stages --quiet > /dev/null
scene_results ref.db > ref.csv
kept=$(find ref.stages -name '*.h5' | wc -l)
[ "$kept" = 5 ] || fail "the uninterrupted scene campaign kept $kept networks, expected 5"

if [ "$part" = full-snapshots ]; then
  tmpfs_works || { echo "no mount namespace for a tmpfs here: skipped"; exit 77; }
  # 400 KiB hold the formed network and one pressed one (about 190 KiB each), not four.
  on_tmpfs 400 small "$fibrenet" campaign run stages.toml --db small.db --stage-cache small \
    --quiet > /dev/null 2> small.err \
    || { cat small.err; fail "a full stage cache failed the campaign"; }
  scene_results small.db > small.csv
  diff ref.csv small.csv || fail "a full stage cache changed the results"
  find small.kept -name '*.partial.*' | grep -q . && fail "partial snapshots left in the stage cache"
  # 100 KiB take metrics, profiles and particles, not a snapshot (about 180 KiB).
  mkdir out
  expect_exit 1 "out/snapshots/forming.h5.*\(File too large\|No space left\)" \
    with_file_limit 100 "$fibrenet" run scene.toml "${fast_scene[@]}" --out out
  [ ! -e out/snapshots/forming.h5 ] || fail "a cut-off snapshot was left as forming.h5"
  echo "disk full test (snapshots) passed"
  exit 0
fi

# The results database. The uninterrupted run, without the per-evaluation sleep:
with_sleep 0.0 "$data/resume.toml" > fast.toml
"$fibrenet" campaign run fast.toml --db full.db --quiet > /dev/null
results full.db resume > full.csv
total=$(count full.db "1")

# stopped_mid_run DB: checks a database that the full disk stopped, then resumes it with room
# again: nothing lost, nothing repeated, the results of the uninterrupted run.
stopped_mid_run() {
  local db=$1 finished unfinished
  integrity "$db"
  finished=$(count "$db" "status IN ('done', 'failed')")
  unfinished=$(count "$db" "status IN ('pending', 'running')")
  [ "$finished" -gt 0 ] && [ "$finished" -lt "$total" ] \
    || fail "$db: the disk did not fill mid-run ($finished of $total finished)"
  "$fibrenet" campaign run fast.toml --db "$db" --json --quiet > resumed.json \
    || fail "$db: the resume with room again failed"
  [ "$(json 'd["status"]' < resumed.json)" = "done" ] || fail "$db: the resume did not finish"
  [ "$(json 'd["replayed"]' < resumed.json)" = "$finished" ] \
    || fail "$db: the finished candidates were not replayed"
  [ "$(json 'd["replayed"] + d["evaluated"]' < resumed.json)" = "$total" ] \
    || fail "$db: evaluations lost or repeated"
  [ "$(count "$db" "status IN ('pending', 'running')")" = 0 ] \
    || fail "$db: candidates left pending or running"
  integrity "$db"
  results "$db" resume > resumed.csv
  diff full.csv resumed.csv || fail "$db: the resumed results differ from the uninterrupted run"
  echo "$db: stopped with $finished of $total finished ($unfinished pending or running), resumed"
}

# File-size limits from 640 KiB to 1.5 MiB: the write-ahead log reaches them between a third
# and three quarters of the way, while a candidate is being stored, marked running or given
# its results.
for kib in 640 896 1152 1536; do
  expect_exit 1 "results database 'limit$kib.db': .* (File too large)" \
    with_file_limit "$kib" "$fibrenet" campaign run fast.toml --db "limit$kib.db" --quiet
  cat err.txt
  stopped_mid_run "limit$kib.db"
done

# A real full disk: the database on a 512 KiB tmpfs, resumed from a copy where there is room.
if tmpfs_works; then
  expect_exit 1 "results database 'small/tmpfs.db': .*database or disk is full" \
    on_tmpfs 512 small "$fibrenet" campaign run fast.toml --db small/tmpfs.db --quiet
  cat err.txt
  stopped_mid_run small.kept/tmpfs.db
else
  echo "no mount namespace for a tmpfs here: the ENOSPC case is skipped"
fi

# The stage cache folder made unwritable once the first network is in it.
"$fibrenet" campaign run stages.toml --db cut.db --stage-cache cut.stages --quiet \
  > /dev/null 2> cut.err &
pid=$!
until compgen -G 'cut.stages/*/*.h5' > /dev/null; do
  kill -0 "$pid" 2> /dev/null || break
  sleep 0.05
done
mv cut.stages cut.stages.gone && touch cut.stages
wait "$pid" || { cat cut.err; fail "an unwritable stage cache failed the campaign"; }
[ -f cut.stages ] || fail "the campaign made its stage cache folder again before it was cut off"
kept=$(find cut.stages.gone -name '*.h5' | wc -l)
[ "$kept" -lt 5 ] || fail "the stage cache folder was cut off only after the campaign"
integrity cut.db
scene_results cut.db > cut.csv
diff ref.csv cut.csv || fail "an unwritable stage cache changed the results"

# `run --out` writes nothing before the end of the run, so a snapshot folder made unwritable
# before it starts is one that became unwritable mid-run.
mkdir out && touch out/snapshots
expect_exit 1 "cannot create out/snapshots: " "$fibrenet" run scene.toml "${fast_scene[@]}" --out out
echo "disk full test passed"
