#!/usr/bin/env bash
# `fibrenet bench --write-bed`: the warmed-up bed as CSV, one row per particle in fibre order,
# and its conversion to a LAMMPS data file with one bond between neighbours of a fibre
# (scripts/compare/). The physics switches --drag and --viscoelastic show in the JSON.
# Usage: bench_export_test.sh FIBRENET SCRIPTS_COMPARE_DIR
set -euo pipefail
fibrenet=$1
compare=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }

"$fibrenet" bench --json --particles 400 --steps 2 --warmup 5 --drag --viscoelastic \
  --write-bed bed.csv > bench.json
python3 - bench.json bed.csv << 'PY'
import csv, json, sys
d = json.load(open(sys.argv[1]))
physics = d["physics"]
assert physics["drag_coefficient_N_s_per_m"] > 0, physics
assert physics["maxwell_tau_s"] > 0, physics
lines = open(sys.argv[2]).read().splitlines()
header = [l for l in lines if l.startswith("#")]
assert len(header) == 3 and "dt" in header[0] and header[1].startswith("# cell"), header
assert "contact_C" in header[2] and "contact_g" in header[2], header[2]
rows = list(csv.DictReader(l for l in lines if not l.startswith("#")))
assert len(rows) == d["particles"] == 400, (len(rows), d["particles"])
fibres = [int(r["fibre"]) for r in rows]
assert fibres == sorted(fibres) and len(set(fibres)) == 20, "fibre order"
assert all(float(r["z"]) > 0 and float(r["radius"]) > 0 and float(r["mass"]) > 0 for r in rows)
PY
python3 "$compare/bed_to_lammps.py" bed.csv bed.data > vars.txt
grep -q "^400 atoms$" bed.data || fail "LAMMPS data: atom count"
grep -q "^380 bonds$" bed.data || fail "LAMMPS data: one bond between neighbours of 20 fibres"
grep -q -- "-var dt " vars.txt || fail "no LAMMPS variables printed"
echo "bench export test passed"
