#!/usr/bin/env bash
# The campaign and db commands end to end: run, resume (after kill -9), query, export, and the
# exit codes of bad input. Usage: cli_campaign_test.sh FIBRENET DATA_DIR
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
fibrenet=$1
data=$2
enter_scratch

# An uninterrupted run, then the same command again: nothing is evaluated the second time.
# (fast.toml is the campaign without its per-evaluation sleep, which changes no result.)
with_sleep 0.0 "$data/resume.toml" > fast.toml
"$fibrenet" campaign run fast.toml --db full.db --json --quiet > full.json
[ "$(json 'd["status"]' < full.json)" = done ] || fail "status"
"$fibrenet" campaign run fast.toml --db full.db --json --quiet > again.json
[ "$(json 'd["evaluated"]' < again.json)" = 0 ] || fail "a finished campaign evaluated again"
[ "$(json 'd["best"]["candidate_id"]' < again.json)" = "$(json 'd["best"]["candidate_id"]' < full.json)" ] \
  || fail "best changed on replay"

# kill -9 half way, then resume: the stored results equal the uninterrupted run's.
"$fibrenet" campaign run "$data/resume.toml" --db killed.db --quiet > /dev/null 2>&1 &
pid=$!
for _ in $(seq 1 400); do
  sleep 0.1
  done_count=$("$fibrenet" db list --db killed.db --json 2>/dev/null \
    | json 'sum(c["counts"]["done"] for c in d["campaigns"])' 2>/dev/null || echo 0)
  [ "$done_count" -ge 10 ] && break
done
kill -9 "$pid" || fail "the campaign ended before it could be killed"
wait "$pid" 2>/dev/null || true
"$fibrenet" db list --db killed.db --json > killed.json
total=$(json 'd["campaigns"][0]["counts"]["done"]' < killed.json)
[ "$total" -ge 10 ] || fail "the campaign was not half way when killed ($total done)"
"$fibrenet" campaign run "$data/resume.toml" --db killed.db --json --quiet > resumed.json
[ "$(json 'd["replayed"]' < resumed.json)" -ge 10 ] || fail "nothing replayed"
[ "$(json 'd["replayed"] + d["evaluated"]' < resumed.json)" = "$(json 'd["candidates"]' < full.json)" ] \
  || fail "evaluations lost or repeated"
# Everything but wall times and reasons must be equal.
results full.db resume > full.csv
results killed.db resume > killed.csv
diff full.csv killed.csv || fail "resumed results differ from the uninterrupted run"

# Queries.
"$fibrenet" db best --db full.db --campaign resume -n 3 --json | json 'len(d["best"])' | grep -qx 3 \
  || fail "db best"
id=$(json 'd["best"]["candidate_id"]' < full.json)
"$fibrenet" db show "$id" --db full.db --json | json 'd["status"]' | grep -qx done || fail "db show"
"$fibrenet" db export --db full.db --campaign resume --format json | json 'len(d["candidates"])' \
  | grep -qx "$(json 'd["candidates"]' < full.json)" || fail "db export json"
"$fibrenet" db best --db full.db --campaign resume | grep -q "goal <= 2.5: met" || fail "goals shown"

# Bad input: exit code 2 and a message naming the file and key.
sed 's/max_evaluations = 30/max_evals = 30/' "$data/resume.toml" > typo.toml
expect_exit 2 "typo.toml:.*budget.max_evals: unknown key; did you mean 'max_evaluations'?" \
  "$fibrenet" campaign run typo.toml --db typo.db
[ ! -e typo.db ] || fail "a bad campaign file left a database behind"
expect_exit 2 "no such file" "$fibrenet" campaign run missing.toml --db x.db
expect_exit 2 "no such campaign" "$fibrenet" db best --db full.db --campaign nope
expect_exit 2 "no candidate with id 9999" "$fibrenet" db show 9999 --db full.db
expect_exit 2 "accepted: csv, json" "$fibrenet" db export --db full.db --campaign resume --format xml
sed 's/sum = { max = 2.5 }/sum = { max = 2.4 }/' fast.toml > changed.toml
expect_exit 2 "started from a different campaign file" \
  "$fibrenet" campaign run changed.toml --db full.db
echo "cli campaign test passed"
