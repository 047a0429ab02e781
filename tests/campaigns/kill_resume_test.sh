#!/usr/bin/env bash
# kill -9 at random moments of a campaign, ten times: every resume completes, the database
# passes PRAGMA integrity_check, and the stored results equal those of an uninterrupted run
# (no candidate lost or duplicated). The kill moments come from a fixed seed, so a failure
# can be repeated. Usage: kill_resume_test.sh FIBRENET RESUME_TOML
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
fibrenet=$1
campaign=$2
enter_scratch

# 0.05 s per evaluation: a full run takes about 2 s, so the kills land all over it.
with_sleep 0.05 "$campaign" > campaign.toml
"$fibrenet" campaign run campaign.toml --db full.db --quiet > /dev/null
results full.db resume > full.csv
rows=$(wc -l < full.csv)
[ "$rows" -gt 20 ] || fail "the uninterrupted run stored only $rows rows"

RANDOM=20261124
for trial in $(seq 1 10); do
  db="trial$trial.db"
  # One or two kills per trial (the second one lands in the resumed run).
  for kill in $(seq 1 $((1 + RANDOM % 2))); do
    "$fibrenet" campaign run campaign.toml --db "$db" --quiet > /dev/null 2>&1 &
    pid=$!
    ms=$((RANDOM % 2500))
    sleep "$(printf '%d.%03d' $((ms / 1000)) $((ms % 1000)))"
    kill -9 "$pid" 2>/dev/null || true
    wait "$pid" 2>/dev/null || true
  done
  "$fibrenet" campaign run campaign.toml --db "$db" --json --quiet > resumed.json \
    || fail "trial $trial: the resume did not complete"
  [ "$(sqlite3 "$db" 'PRAGMA integrity_check;')" = ok ] || fail "trial $trial: integrity_check"
  results "$db" resume > trial.csv
  diff full.csv trial.csv > /dev/null || { diff full.csv trial.csv | head; fail "trial $trial: results differ"; }
  echo "trial $trial: $(json 'd["replayed"], "replayed,", d["evaluated"], "evaluated"' < resumed.json) on resume"
done
echo "kill and resume test passed"
