#!/usr/bin/env bash
# `fibrenet run --out` writes a snapshot per network stage (HDF5 + XDMF), the last one
# coloured by the fibres' strain energy at the tensile peak; `fibrenet run --from` continues
# from a snapshot and ends where the uninterrupted run ended (from a creping snapshot it runs
# only the virtual tests, on the creped sheet); `--until` stops after a stage; snapshots
# that do not fit the scene are refused with exit code 2. Usage: run_snapshots_test.sh FIBRENET TINY_SCENE
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
fibrenet=$1
scene=$2
enter_scratch

# The tiny scene with a short MD tensile test after pressing.
cp "$scene" scene.toml
printf '\n[tensile]\ndirection = "MD"\nloading_steps = 1500\nsamples = 40\n' >> scene.toml

"$fibrenet" run scene.toml --out full --json > full.json 2> full.err
for f in forming.h5 forming.xdmf pressing.h5 pressing.xdmf; do
  [ -s "full/snapshots/$f" ] || fail "missing snapshot file $f"
done
grep -q 'Name="tensile_peak_fibre_energy_J"' full/snapshots/pressing.xdmf \
  || fail "the last snapshot lacks the tensile-peak fibre energy field"
grep -q 'Name="fibre"' full/snapshots/forming.xdmf || fail "no fibre id in the XDMF"

# The bonding-threshold study reads the pressing snapshot: at gap_tolerance 0 it counts the
# bonds the run reported after pressing.
# Debian's python3 (scripts/setup.sh installs python3-h5py for it).
/usr/bin/python3 "$(dirname "${BASH_SOURCE[0]}")/../../scripts/bond_threshold_study.py" \
  full/snapshots/pressing.h5 > thresholds.txt
python3 - full.json thresholds.txt <<'PY' || fail "bond_threshold_study.py disagrees with the run"
import json, sys
pressing = json.load(open(sys.argv[1]))["stages"][1]
assert pressing["name"] == "pressing", pressing["name"]
row = [l.split() for l in open(sys.argv[2]) if l.split()[:1] == ["0.00"]][0]
want = pressing["metrics"]["bonds_per_fibre"], pressing["metrics"]["bonded_pairs_per_fibre"]
assert abs(float(row[1]) - want[0]) < 0.006 and abs(float(row[2]) - want[1]) < 0.006, (row, want)
PY

# Continue after forming: the same pressing and tensile results, bit for bit.
"$fibrenet" run scene.toml --from full/snapshots/forming.h5 --out cont --json > cont.json 2> cont.err
python3 - full.json cont.json <<'PY' || fail "the continued run differs from the uninterrupted one"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
assert a["metrics"] == b["metrics"], "metrics differ"
assert [s["name"] for s in a["stages"]] == [s["name"] for s in b["stages"]], "stages differ"
assert a["stages"][0]["metrics"] == b["stages"][0]["metrics"], "forming report not carried over"
PY
[ -s cont/snapshots/pressing.h5 ] || fail "the continued run wrote no pressing snapshot"
[ ! -e cont/snapshots/forming.h5 ] || fail "the continued run rewrote the forming snapshot"

# --until pressing stops before the tests, with the same pressing report and snapshot as the
# whole run, so that the tests can run later from it; a stage the scene lacks is refused.
"$fibrenet" run scene.toml --until pressing --out upto --json > upto.json 2> upto.err
python3 - full.json upto.json <<'PY' || fail "--until pressing differs from the whole run's first stages"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
assert [s["name"] for s in b["stages"]] == ["forming", "pressing"], b["stages"]
assert "tensile_strength_N_per_m" not in b["metrics"], "the tests ran"
assert a["stages"][1]["metrics"] == b["stages"][1]["metrics"], "pressing differs"
PY
/usr/bin/python3 - full/snapshots/pressing.h5 upto/snapshots/pressing.h5 <<'PY' \
  || fail "--until pressing wrote another pressing snapshot"
import sys, h5py, numpy
a, b = (h5py.File(p, "r") for p in sys.argv[1:3])
for name in ("particles/x", "particles/q", "bonds/ij", "bonds/L0"):
    assert numpy.array_equal(a[name][()], b[name][()]), name
PY
expect_exit 2 "--until creping: scene.toml has no such stage; accepted: forming, pressing" \
  "$fibrenet" run scene.toml --until creping

# Creped: the tests run on the creped sheet from its snapshot give the uninterrupted run's
# metrics, and the creping report is carried over.
cp scene.toml creped.toml
printf '\n[creping]\nyankee_speed_m_per_s = 30\ncreping_angle_deg = 85\n' >> creped.toml
"$fibrenet" run creped.toml --out creped --json > creped.json 2> creped.err
[ -s creped/snapshots/creping.h5 ] || fail "missing snapshot file creping.h5"
"$fibrenet" run creped.toml --from creped/snapshots/creping.h5 --json > retest.json 2> retest.err
python3 - creped.json retest.json <<'PY' || fail "tests from the creping snapshot differ"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
assert [s["name"] for s in b["stages"]] == ["forming", "pressing", "creping", "tests"], b["stages"]
assert "tensile_strength_N_per_m" in b["metrics"] and "crepe_frequency_per_mm" in b["metrics"]
assert a["metrics"] == b["metrics"], "metrics differ"
# Carried over from the snapshot, its wall time included: creping did not run again.
assert a["stages"][2] == b["stages"][2], "creping report differs (was it run again?)"
PY

# A snapshot after pressing cannot continue a scene without pressing.
python3 - scene.toml > unpressed.toml <<'PY'
import re, sys
text = open(sys.argv[1]).read()
print(re.sub(r"\[pressing\].*?(?=\[tensile\])", "", text, flags=re.S))
PY
expect_exit 2 "full/snapshots/pressing.h5: holds the network after pressing" \
  "$fibrenet" run unpressed.toml --from full/snapshots/pressing.h5

# An override of a table the snapshot's stages were made from would change nothing: refused.
expect_exit 2 "--set contact.friction_mu: full/snapshots/pressing.h5 holds the network after pressing" \
  "$fibrenet" run scene.toml --from full/snapshots/pressing.h5 --set contact.friction_mu=0
expect_exit 2 "--set pressing.speed_m_per_s: full/snapshots/pressing.h5 holds the network after pressing" \
  "$fibrenet" run scene.toml --from full/snapshots/pressing.h5 --set pressing.speed_m_per_s=1

# A file that is not a snapshot.
echo "not hdf5" > bogus.h5
expect_exit 2 "bogus.h5: not an HDF5 file" "$fibrenet" run scene.toml --from bogus.h5
echo "run snapshots test passed"
