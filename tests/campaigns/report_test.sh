#!/usr/bin/env bash
# `fibrenet report` writes the three PNG plots of a campaign. Skipped (77) without matplotlib.
# Usage: report_test.sh FIBRENET CAMPAIGN.toml
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
fibrenet=$1
campaign=$2
python3 -c "import matplotlib" 2>/dev/null || /usr/bin/python3 -c "import matplotlib" 2>/dev/null \
  || { echo "matplotlib missing: skipped"; exit 77; }
enter_scratch
"$fibrenet" campaign run "$campaign" --db r.db --quiet > /dev/null
"$fibrenet" report --db r.db --out plots > files.txt
for kind in objective softness_strength variables_vs_metrics; do
  f=plots/doe-mpi_$kind.png
  [ -s "$f" ] || fail "$f missing"
  head -c 8 "$f" | od -An -c | grep -q "P   N   G" || fail "$f is not a PNG"
done
expect_exit 2 "" "$fibrenet" report --db r.db --out plots --campaign nope
echo "report test passed"
