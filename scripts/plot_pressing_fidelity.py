#!/usr/bin/env python3
"""Table (Markdown, on stdout) and plot of scripts/pressing_fidelity_study.sh: the pressing at
time-step safety 0.8 against the default 0.5, paired on each seed's formed network. For each
key metric: the seeds, the mean of (run - reference) / |reference| with its standard error, the
95% interval (mean +- 1.96 standard errors), and whether that interval lies within +-2%. The plot
shows the running mean and its 95% band against the number of seeds.

Usage: scripts/plot_pressing_fidelity.py STUDY_DIR FIGURE_DIR
Needs matplotlib (Debian: python3-matplotlib). Exit codes: 0 success, 2 bad input.
"""
import os
import statistics
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from plot_fidelity_stages import SHORT, cell, differences_percent, stage_wall  # noqa: E402
from study_runs import load  # noqa: E402

METRICS = ["thickness_um", "bonds_per_fibre", "tensile_modulus_N_per_m",
           "tensile_strength_N_per_m", "zd_modulus_kPa"]
VARIANT = "pressing_safety_0.8"


def present(runs, reference, metric):
    """The runs and the reference restricted to the seeds where both report the metric."""
    seeds = [s for s in runs if s in reference and metric in runs[s]["metrics"]
             and metric in reference[s]["metrics"]]
    return {s: runs[s] for s in seeds}, {s: reference[s] for s in seeds}


def main():
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    folder, figures = sys.argv[1], sys.argv[2]
    reference, variant = load(folder, "default"), load(folder, VARIANT)
    if len(set(reference) & set(variant)) < 2:
        print(f"error: {folder}: fewer than two seeds with both default_s*.json and "
              f"{VARIANT}_s*.json (run scripts/pressing_fidelity_study.sh first)", file=sys.stderr)
        return 2
    print(f"pressing wall, one thread: {stage_wall(reference, 'pressing'):.1f} s at 0.5, "
          f"{stage_wall(variant, 'pressing'):.1f} s at 0.8\n")
    print("| metric | seeds | 0.8 against 0.5 | 95% interval | within 2% |")
    print("| --- | --- | --- | --- | --- |")
    fig, axes = plt.subplots(1, len(METRICS), figsize=(3.2 * len(METRICS), 3.4), sharey=True)
    for metric, ax in zip(METRICS, axes):
        runs, ref = present(variant, reference, metric)
        d = differences_percent(runs, ref, metric)
        if len(d) < 2:
            print(f"| {SHORT[metric]} | {len(d)} | - | - | - |")
            continue
        half = 1.96 * statistics.stdev(d) / len(d) ** 0.5
        mean = statistics.mean(d)
        lo, hi = mean - half, mean + half
        print(f"| {SHORT[metric]} | {len(d)} | {cell(d)} | [{lo:+.2f}, {hi:+.2f}]% | "
              f"{'yes' if -2.0 <= lo and hi <= 2.0 else 'no'} |")
        n = list(range(2, len(d) + 1))
        means = [statistics.mean(d[:k]) for k in n]
        bands = [1.96 * statistics.stdev(d[:k]) / k ** 0.5 for k in n]
        ax.fill_between(n, [m - b for m, b in zip(means, bands)],
                        [m + b for m, b in zip(means, bands)], alpha=0.3)
        ax.plot(n, means, lw=1.2)
        ax.plot(range(1, len(d) + 1), d, ls="none", marker=".", ms=3, color="gray")
        for level in (-2.0, 2.0):
            ax.axhline(level, color="k", lw=0.8, ls="--")
        ax.set_title(SHORT[metric], fontsize=9)
        ax.set_xlabel("paired seeds")
    axes[0].set_ylabel("0.8 against 0.5 [%]")
    fig.suptitle("Pressing time-step safety 0.8 against 0.5, study-fidelity-stages.toml "
                 "(line: running mean, band: its 95% interval, dots: seeds)",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(figures, "pressing_safety_seeds.png"), dpi=120)
    return 0


if __name__ == "__main__":
    sys.exit(main())
