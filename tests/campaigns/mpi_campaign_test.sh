#!/usr/bin/env bash
# A seeded sweep with replicates and confirmation on 3 MPI ranks stores the same results as the
# serial run. Usage: mpi_campaign_test.sh FIBRENET MPIEXEC CAMPAIGN.toml
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
fibrenet=$1
mpiexec=$2
campaign=$3
enter_scratch
export OMP_NUM_THREADS=1
"$fibrenet" campaign run "$campaign" --db serial.db --json --quiet > serial.json
"$mpiexec" --allow-run-as-root --oversubscribe -n 3 \
  "$fibrenet" campaign run "$campaign" --db mpi.db --json --quiet > mpi.json
grep -Eq '"evaluators": "MPI, 3 ranks \(2 evaluating, [0-9]+ threads? each\)"' mpi.json || { cat mpi.json; fail "not run on 3 ranks"; }
# The coarse level fails above analytic.fail_above = 300, on the evaluating (worker) ranks: the
# campaign must still complete, and store those candidates as failed with the reason.
[ "$(json 'd["status"]' < mpi.json)" = done ] || { cat mpi.json; fail "the MPI campaign did not complete"; }
[ "$(json 'd["failed"]' < mpi.json)" -ge 1 ] || { cat mpi.json; fail "no candidate failed on the MPI ranks"; }
"$fibrenet" db export --db mpi.db --campaign "$(json 'd["campaign"]' < mpi.json)" --format json \
  > mpi_export.json
failures=$(json '"\n".join("%s %s" % (c["id"], c["reason"]) for c in d["candidates"]
                if c["status"] == "failed")' < mpi_export.json)
[ -n "$failures" ] || fail "no candidate stored as failed in mpi.db"
while read -r id reason; do
  case $reason in
    *"exceeds analytic.fail_above = 300"*) ;;
    *) fail "failed candidate $id lacks the analytic.fail_above reason: '$reason'" ;;
  esac
done <<< "$failures"
c='d["campaign"]'
[ "$(json "$c['status'], $c['counts']['pending'], $c['counts']['running']" \
     < mpi_export.json)" = "done 0 0" ] || fail "mpi.db: the campaign is not done, or left candidates pending or running"
name=$(json 'd["campaign"]' < serial.json)
# Everything but wall times (column 7) must match.
"$fibrenet" db export --db serial.db --campaign "$name" --format csv | cut -d, -f1-6,8- > serial.csv
"$fibrenet" db export --db mpi.db --campaign "$name" --format csv | cut -d, -f1-6,8- > mpi.csv
[ "$(wc -l < serial.csv)" -gt 10 ] || fail "too few candidates"
diff serial.csv mpi.csv || fail "MPI results differ from the serial run"
echo "mpi campaign test passed: $(($(wc -l < serial.csv) - 1)) candidates match," \
  "$(wc -l <<< "$failures") failed on the worker ranks"
