#!/usr/bin/env bash
# Readers while a campaign writes: the sqlite3 shell and `fibrenet db` query the database in
# a tight loop during a campaign. Every query must succeed (no "database is locked"), the
# counts they see never go down, and the campaign ends with the results of a run nobody read.
# Usage: concurrent_readers_test.sh FIBRENET RESUME_TOML
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
fibrenet=$1
campaign=$2
enter_scratch

with_sleep 0.05 "$campaign" > campaign.toml
"$fibrenet" campaign run campaign.toml --db quiet.db --quiet > /dev/null
results quiet.db resume > quiet.csv

"$fibrenet" campaign run campaign.toml --db busy.db --quiet > /dev/null 2> campaign.err &
pid=$!
queries=0 last=0
while kill -0 "$pid" 2> /dev/null; do
  [ -e busy.db ] || continue
  # The shell: a plain reader (no -bail needed: a failed query exits non-zero), with the busy
  # timeout docs/database.md asks of readers. The file is never seen before its tables exist.
  n=$(sqlite3 -cmd ".timeout 1000" busy.db "SELECT count(*) FROM candidates;" 2> shell.err) \
    || { cat shell.err; fail "sqlite3 query failed"; }
  [ "$n" -ge "$last" ] || fail "candidate count went down from $last to $n"
  last=$n
  "$fibrenet" db list --db busy.db --json > list.json 2> list.err || { cat list.err; fail "db list failed"; }
  queries=$((queries + 1))
done
wait "$pid" || { cat campaign.err; fail "the campaign failed while being read"; }
[ "$queries" -ge 5 ] || fail "only $queries rounds of queries ran during the campaign"
results busy.db resume > busy.csv
diff quiet.csv busy.csv > /dev/null || fail "results differ from the unread run"
echo "concurrent readers test passed ($queries rounds of queries, last count $last)"
