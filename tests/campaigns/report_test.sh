#!/usr/bin/env bash
# `fibrenet report` writes the three PNG plots of a campaign. Skipped (77) without matplotlib.
# Usage: report_test.sh FIBRENET CAMPAIGN.toml
set -euo pipefail
fibrenet=$1
campaign=$2
python3 -c "import matplotlib" 2>/dev/null || /usr/bin/python3 -c "import matplotlib" 2>/dev/null \
  || { echo "matplotlib missing: skipped"; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }
"$fibrenet" campaign run "$campaign" --db r.db --quiet > /dev/null
"$fibrenet" report --db r.db --out plots > files.txt
for kind in objective softness_strength variables_vs_metrics; do
  f=plots/doe-mpi_$kind.png
  [ -s "$f" ] || fail "$f missing"
  head -c 8 "$f" | od -An -c | grep -q "P   N   G" || fail "$f is not a PNG"
done
set +e
"$fibrenet" report --db r.db --out plots --campaign nope 2> err.txt
rc=$?
set -e
[ $rc = 2 ] || fail "unknown campaign: exit code $rc"
echo "report test passed"
