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
grep -q '"evaluators": "MPI, 3 ranks (2 evaluating)"' mpi.json || { cat mpi.json; fail "not run on 3 ranks"; }
name=$(json 'd["campaign"]' < serial.json)
# Everything but wall times (column 7) must match.
"$fibrenet" db export --db serial.db --campaign "$name" --format csv | cut -d, -f1-6,8- > serial.csv
"$fibrenet" db export --db mpi.db --campaign "$name" --format csv | cut -d, -f1-6,8- > mpi.csv
[ "$(wc -l < serial.csv)" -gt 10 ] || fail "too few candidates"
diff serial.csv mpi.csv || fail "MPI results differ from the serial run"
echo "mpi campaign test passed: $(($(wc -l < serial.csv) - 1)) candidates match"
