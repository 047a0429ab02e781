#!/usr/bin/env python3
"""Tables (Markdown, on stdout) and plots of the forming studies that
scripts/forming_studies.sh writes: the acceleration study (accelerated against a less
accelerated reference, after forming and after pressing) and the out-of-plane orientation at
1% and 0.15% consistency.

Usage: scripts/plot_forming_studies.py STUDY_DIR FIGURE_DIR
Needs matplotlib (Debian: python3-matplotlib). Exit codes: 0 success, 2 bad input.
"""
import glob
import json
import os
import statistics
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

METRICS = ["thickness_um", "porosity", "bonds_per_fibre", "bonded_pairs_per_fibre",
           "contacts_per_fibre", "out_of_plane_angle_deg_mean", "orientation_anisotropy"]


def load(folder, prefix):
    runs = []
    for path in sorted(glob.glob(os.path.join(folder, prefix + "_*.json"))):
        with open(path) as f:
            runs.append(json.load(f))
    return runs


def stage_values(runs, stage, metric):
    return [r["stages"][stage]["metrics"][metric] for r in runs]


def mean_sd(values):
    return statistics.mean(values), statistics.stdev(values) if len(values) > 1 else 0.0


def acceleration(folder, figures):
    acc, ref = load(folder, "acc"), load(folder, "ref")
    if not acc or not ref:
        return
    print("| stage | metric | accelerated (mean ± sd) | reference (mean ± sd) | difference |")
    print("| --- | --- | --- | --- | --- |")
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), sharey=True)
    for stage, ax in ((0, axes[0]), (1, axes[1])):
        name = acc[0]["stages"][stage]["name"]
        diffs = []
        for m in METRICS:
            (a, sa), (r, sr) = mean_sd(stage_values(acc, stage, m)), mean_sd(stage_values(ref, stage, m))
            diff = 100.0 * (a - r) / r if r else 0.0
            diffs.append((diff, 100.0 * sr / r if r else 0.0))
            print(f"| {name} | {m} | {a:.4g} ± {sa:.2g} | {r:.4g} ± {sr:.2g} | {diff:+.1f}% |")
        ys = range(len(METRICS))
        ax.barh(ys, [d for d, _ in diffs], xerr=[s for _, s in diffs], color="tab:blue", alpha=0.7)
        ax.axvspan(-5, 5, color="gray", alpha=0.15, label="within 5%")
        ax.axvline(0, color="k", lw=0.8)
        ax.set_yticks(list(ys))
        ax.set_yticklabels(METRICS, fontsize=8)
        ax.set_xlabel("(accelerated - reference) / reference (%)")
        ax.set_title(f"after {name}")
        ax.set_xlim(-40, 100)
        ax.legend(fontsize=8)
    wall_a = statistics.mean(r["stages"][0]["wall_s"] for r in acc)
    wall_r = statistics.mean(r["stages"][0]["wall_s"] for r in ref)
    steps_a = statistics.mean(r["stages"][0]["steps"] for r in acc)
    steps_r = statistics.mean(r["stages"][0]["steps"] for r in ref)
    fig.suptitle(f"Forming acceleration study, {len(acc)} seeds (black bars: seed sd of the "
                 f"reference). Forming: {steps_a:.3g} steps, {wall_a:.0f} s accelerated; "
                 f"{steps_r:.3g} steps, {wall_r:.0f} s reference", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(figures, "forming_acceleration_study.png"), dpi=120)
    plt.close(fig)


def consistency(folder, figures):
    groups = [("1%", load(folder, "c100")), ("0.15%", load(folder, "c015"))]
    if not all(runs for _, runs in groups):
        return
    print()
    print("| consistency | seeds | out-of-plane angle (deg), mean ± se | per seed | forming wall time (s) |")
    print("| --- | --- | --- | --- | --- |")
    fig, ax = plt.subplots(figsize=(5, 4))
    for k, (label, runs) in enumerate(groups):
        values = [r["metrics"]["out_of_plane_angle_deg_mean"] for r in runs]
        mean, sd = mean_sd(values)
        se = sd / len(values) ** 0.5
        wall = statistics.mean(r["wall_s"] for r in runs)
        print(f"| {label} | {len(values)} | {mean:.2f} ± {se:.2f} | "
              f"{', '.join(f'{v:.2f}' for v in values)} | {wall:.0f} |")
        ax.plot([k] * len(values), values, "o", color="tab:gray", alpha=0.7)
        ax.errorbar([k + 0.1], [mean], yerr=[se], fmt="s", color="tab:red", capsize=4)
    ax.set_xticks([0, 1])
    ax.set_xticklabels([label for label, _ in groups])
    ax.set_xlabel("forming consistency")
    ax.set_ylabel("mean out-of-plane angle (deg)")
    ax.set_title("Out-of-plane fibre angle after forming\n(grey: seeds; red: mean ± standard error)")
    fig.tight_layout()
    fig.savefig(os.path.join(figures, "forming_consistency_orientation.png"), dpi=120)
    plt.close(fig)


def main(argv):
    if len(argv) != 3 or not os.path.isdir(argv[1]):
        print(__doc__, file=sys.stderr)
        return 2
    os.makedirs(argv[2], exist_ok=True)
    acceleration(argv[1], argv[2])
    consistency(argv[1], argv[2])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
