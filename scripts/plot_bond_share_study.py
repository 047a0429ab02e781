#!/usr/bin/env python3
"""Table (Markdown, on stdout) and plot of the bond-share study that
scripts/bond_share_study.sh writes: for fibre-fibre bond properties per particle bond and per
crossing, the key metrics at particle spacings of 1 and 0.5 diameters (mean over the seeds)
and the change from 1 to 0.5, paired seed by seed (mean +- standard error over the seeds).

Usage: scripts/plot_bond_share_study.py STUDY_DIR FIGURE_DIR
Needs matplotlib (Debian: python3-matplotlib). Exit codes: 0 success, 2 bad input.
"""
import math
import os
import statistics
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from study_runs import load  # noqa: E402

METRICS = ["bonds_per_fibre", "bonded_pairs_per_fibre", "thickness_um",
           "tensile_modulus_N_per_m", "tensile_strength_N_per_m", "bulk_softness_um_per_kPa"]
SHORT = {"bonds_per_fibre": "particle bonds/fibre", "bonded_pairs_per_fibre": "bonded pairs/fibre",
         "thickness_um": "thickness", "tensile_modulus_N_per_m": "tensile modulus",
         "tensile_strength_N_per_m": "strength", "bulk_softness_um_per_kPa": "ZD compliance"}
# Run name prefix -> legend: per particle bond, per crossing, per crossing with the tensile test
# at twice the loading steps (its guard warns at the scene's steps with spacing 0.5).
SHARES = {"particle": "bond properties per particle bond",
          "crossing": "per crossing",
          "crossing_slow": "per crossing, tensile at 400,000 steps"}


def change_percent(fine, coarse, metric):
    """Mean and standard error over the paired seeds of fine / coarse - 1, in percent."""
    changes = [100.0 * (fine[s]["metrics"][metric] / coarse[s]["metrics"][metric] - 1.0)
               for s in fine if s in coarse]
    if not changes:
        return float("nan"), float("nan")
    se = statistics.stdev(changes) / math.sqrt(len(changes)) if len(changes) > 1 else float("nan")
    return statistics.mean(changes), se


def main():
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    folder, figures = sys.argv[1], sys.argv[2]
    runs = {(share, spacing): load(folder, f"{share}_{spacing}")
            for share in SHARES for spacing in ("1", "0.5")}
    if not any(runs.values()):
        print(f"error: {folder}: no runs (run scripts/bond_share_study.sh first)", file=sys.stderr)
        return 2

    print("| share | spacing [d] | seeds | wall [s] | " +
          " | ".join(SHORT[m] for m in METRICS) + " |")
    print("|" + " --- |" * (4 + len(METRICS)))
    for (share, spacing), r in runs.items():
        if not r:
            continue
        wall = statistics.mean(d["wall_s"] for d in r.values())
        means = [statistics.mean(d["metrics"][m] for d in r.values()) for m in METRICS]
        print(f"| {share} | {spacing} | {len(r)} | {wall:.0f} | " +
              " | ".join(f"{v:.4g}" for v in means) + " |")
    print()
    print("| share | " + " | ".join(f"{SHORT[m]}, 0.5 against 1" for m in METRICS) + " |")
    print("|" + " --- |" * (1 + len(METRICS)))
    fig, ax = plt.subplots(figsize=(9, 4.2))
    width = 0.8 / len(SHARES)
    for k, (share, legend) in enumerate(SHARES.items()):
        fine, coarse = runs[(share, "0.5")], runs[(share, "1")]
        if not fine or not coarse:
            continue
        stats = [change_percent(fine, coarse, m) for m in METRICS]
        print(f"| {share} | " + " | ".join(f"{m:+.1f} ± {se:.1f}%" for m, se in stats) + " |")
        xs = [i + (k - (len(SHARES) - 1) / 2) * width for i in range(len(METRICS))]
        ax.bar(xs, [m for m, _ in stats], width, yerr=[0 if math.isnan(se) else se
                                                       for _, se in stats],
               capsize=3, label=legend)
    ax.axhline(0.0, color="black", linewidth=0.8)
    ax.set_xticks(range(len(METRICS)))
    ax.set_xticklabels([SHORT[m] for m in METRICS], rotation=20, ha="right")
    ax.set_ylabel("change from spacing 1 to 0.5 diameters [%]")
    ax.set_title("study-fidelity.toml: particle spacing with bonds per particle or per crossing")
    ax.legend()
    fig.tight_layout()
    os.makedirs(figures, exist_ok=True)
    path = os.path.join(figures, "bond_share_spacing.png")
    fig.savefig(path, dpi=120)
    print(f"\nwrote {path}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
