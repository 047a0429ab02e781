"""Bond loss of the generic tissue against coating adhesion (docs/creping.md).

Usage: /usr/bin/python3 scripts/plot_creping_calibration.py CAL_DIR docs/figures
CAL_DIR holds adh<N>.json and adh<N>/curves/creping_bond_loss.csv of the runs
`fibrenet run campaigns/scenes/generic-tissue-creped.toml --from ... --out adh<N> --json`
at adhesion N mN.
"""
import csv
import glob
import json
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt


def creping_details(path):
    with open(path) as f:
        report = json.load(f)
    return next(s for s in report["stages"] if s["name"] == "creping")["details"]


def main(cal_dir, out_dir):
    runs = []
    for path in glob.glob(os.path.join(cal_dir, "adh*.json")):
        adhesion = float(re.search(r"adh([0-9.]+)\.json$", path).group(1))
        curve = os.path.join(cal_dir, f"adh{adhesion:g}", "curves", "creping_bond_loss.csv")
        with open(curve) as f:
            rows = list(csv.DictReader(f))
        runs.append((adhesion, creping_details(path), rows))
    runs.sort(key=lambda r: r[0])

    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4))
    adh = [r[0] for r in runs]
    left.plot(adh, [r[1]["bonds_broken_fraction"] for r in runs], "o-", label="bonds broken, strip middle")
    left.plot(adh, [r[1]["bonds_broken_fraction_all"] for r in runs], "s--", label="bonds broken, whole strip")
    left.plot(adh, [r[1]["dust_mass_fraction"] for r in runs], "^:", label="dust mass fraction")
    left.axhline(0.3, color="grey", lw=0.8)
    left.text(adh[0], 0.32, "paper: about 30% of bonds lost", color="grey", fontsize=8)
    left.set_xlabel("coating adhesion F_r0 = F_s0 [mN]")
    left.set_ylabel("fraction")
    left.legend(fontsize=8)
    for adhesion, _, rows in runs:
        right.plot([float(r["time_us"]) for r in rows],
                   [float(r["fibre_fibre_broken_fraction"]) for r in rows], label=f"{adhesion:g} mN")
    right.set_xlabel("time since the blade met the sheet [us]")
    right.set_ylabel("fibre-fibre bonds broken (strip middle)")
    right.legend(fontsize=8, title="adhesion")
    fig.suptitle("Generic tissue creped at 30 m/s, 85 deg")
    fig.tight_layout()
    out = os.path.join(out_dir, "creping_generic_tissue_adhesion.png")
    fig.savefig(out, dpi=110)
    print(f"wrote {out}")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
