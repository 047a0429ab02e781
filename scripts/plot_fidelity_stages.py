#!/usr/bin/env python3
"""Table (Markdown, on stdout) and plot of the stage-by-stage speed-against-error study that
scripts/fidelity_stages_study.sh writes. Every variant shares its seed's network up to the
stage it changes, so its difference from that stage's reference is paired on one network. The
table gives the mean over seeds of (run - reference) / |reference| with its standard error
(a bias that stands out of its error is a fidelity error, not noise); the plot gives the mean of
|run - reference| / |reference|. Each stage's probe (a change far below any fidelity change)
is its noise floor. Wall time is the changed stage's, one thread.

Usage: scripts/plot_fidelity_stages.py STUDY_DIR FIGURE_DIR
Needs matplotlib (Debian: python3-matplotlib). Exit codes: 0 success, 2 bad input.
"""
import os
import statistics
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from study_runs import load  # noqa: E402

SHORT = {"thickness_um": "thickness", "bonds_per_fibre": "bonds/fibre",
         "tensile_modulus_N_per_m": "tensile modulus", "tensile_strength_N_per_m": "strength",
         "zd_modulus_kPa": "ZD modulus", "zd_hysteresis_fraction": "ZD hysteresis",
         "zd_residual_strain": "ZD residual strain",
         "zd_peak_pressure_kPa": "ZD peak pressure", "softness_index": "softness index"}
# (stage, its wall-time entry, metrics it can move, probe run, [(run, label)], reference run)
STAGES = [
    ("tensile test", "tests", ["tensile_modulus_N_per_m", "tensile_strength_N_per_m",
                               "softness_index"],
     "tensile_probe", [("tensile_400000", "400000 steps"), ("default", "200000 (default)"),
                       ("tensile_100000", "100000")], "tensile_400000"),
    ("ZD compression", "tests", ["zd_modulus_kPa", "zd_hysteresis_fraction",
                                 "zd_peak_pressure_kPa", "zd_residual_strain", "softness_index"],
     "compression_probe", [("compression_40000", "40000 steps"),
                           ("default", "20000 (default)"),
                           ("compression_10000", "10000")], "compression_40000"),
    ("pressing", "pressing", ["thickness_um", "bonds_per_fibre", "tensile_modulus_N_per_m",
                              "tensile_strength_N_per_m", "zd_modulus_kPa", "softness_index"],
     "pressing_probe", [("default", "mass scale 1000 (default)"),
                        ("pressing_mass_10000", "mass scale 10000"),
                        ("pressing_safety_0.8", "time-step safety 0.8")], "default"),
]


def differences_percent(runs, reference, metric):
    """(run - reference) / |reference| in percent, one per seed both have."""
    return [100.0 * (runs[s]["metrics"][metric] - reference[s]["metrics"][metric]) /
            abs(reference[s]["metrics"][metric]) for s in sorted(runs) if s in reference]


def mean_error(runs, reference, metric):
    return statistics.mean(abs(d) for d in differences_percent(runs, reference, metric))


def stage_wall(runs, stage):
    return statistics.mean(next(st["wall_s"] for st in r["stages"] if st["name"] == stage)
                           for r in runs.values())


def cell(differences):
    """Signed mean and its standard error over the seeds, in percent."""
    if len(differences) < 2:
        return f"{differences[0]:+.2f}%" if differences else "-"
    error = statistics.stdev(differences) / len(differences) ** 0.5
    return f"{statistics.mean(differences):+.2f} ± {error:.2f}%"


def main():
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    folder, figures = sys.argv[1], sys.argv[2]
    if not load(folder, "default"):
        print(f"error: {folder}: no default_s*.json (run scripts/fidelity_stages_study.sh "
              "first)", file=sys.stderr)
        return 2
    fig, axes = plt.subplots(1, len(STAGES), figsize=(5 * len(STAGES), 4.2), sharey=True)
    for (stage, wall_entry, metrics, probe_name, settings, ref_name), ax in zip(STAGES, axes):
        reference, probe = load(folder, ref_name), load(folder, probe_name)
        seeds = len(reference)
        print(f"\n**{stage}** ({seeds} seeds; wall: the {wall_entry} stage, one thread)\n")
        print("| setting | wall [s] | " + " | ".join(SHORT[m] for m in metrics) + " |")
        print("|" + " --- |" * (2 + len(metrics)))
        if ref_name == "default":  # the probe perturbs the reference itself
            probe_ref = reference
        else:
            probe_ref = load(folder, "default")
        floor = {m: mean_error(probe, probe_ref, m) for m in metrics}
        print(f"| noise probe | {stage_wall(probe, wall_entry):.0f} | " +
              " | ".join(cell(differences_percent(probe, probe_ref, m)) for m in metrics) + " |")
        points = []
        for name, label in settings:
            runs = load(folder, name)
            if not runs:
                continue
            wall = stage_wall(runs, wall_entry)
            tag = " (reference)" if name == ref_name else ""
            print(f"| {label}{tag} | {wall:.0f} | " +
                  " | ".join("-" if name == ref_name else
                             cell(differences_percent(runs, reference, m)) for m in metrics) +
                  " |")
            if name != ref_name:
                points.append((label, wall, {m: mean_error(runs, reference, m) for m in metrics}))
        for m in metrics:
            line, = ax.plot([w for _, w, _ in points], [e[m] for _, _, e in points],
                            marker="o", ls="none", label=SHORT[m])
            ax.axhline(max(floor[m], 1e-3), color=line.get_color(), lw=0.6, ls=":")
        for i, (label, wall, _) in enumerate(points):  # staggered: close walls would overlap
            ax.annotate(label, (wall, 0.0015 * 2.5 ** i), fontsize=7, ha="center",
                        backgroundcolor="white")
        ax.axvline(stage_wall(reference, wall_entry), color="gray", lw=0.5)
        ax.axhline(2.0, color="k", lw=0.8, label="2%")
        ax.set_yscale("log")
        ax.set_ylim(1e-3, 100)
        ax.set_xlim(0, 1.15 * max([stage_wall(reference, wall_entry)] +
                                  [w for _, w, _ in points]))
        ax.set_xlabel(f"{wall_entry} stage wall time, 1 thread [s]")
        ax.set_title(f"{stage} (reference: {dict(settings)[ref_name]}; grey line)", fontsize=9)
        ax.legend(fontsize=7, loc="upper right")
    axes[0].set_ylabel("error against the reference, paired on one network [%]")
    fig.suptitle("Speed against error stage by stage, study-fidelity-stages.toml "
                 "(dotted: each stage's noise probe)", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(figures, "fidelity_stages_speed_error.png"), dpi=120)
    return 0


if __name__ == "__main__":
    sys.exit(main())
