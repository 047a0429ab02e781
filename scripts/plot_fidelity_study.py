#!/usr/bin/env python3
"""Table (Markdown, on stdout) and plot of the speed-against-error study that
scripts/fidelity_study.sh writes: for each fidelity factor, the wall time of each setting and
the relative error of the key metrics against the factor's finest setting, paired seed by
seed, next to the noise floor: the defaults with the time step 0.2% shorter, a perturbation
far below any fidelity change, which still moves the metrics of these chaotic packings.

Usage: scripts/plot_fidelity_study.py STUDY_DIR FIGURE_DIR
Needs matplotlib (Debian: python3-matplotlib). Exit codes: 0 success, 2 bad input.
"""
import os
import statistics
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from study_runs import load  # noqa: E402

METRICS = ["thickness_um", "bonds_per_fibre", "tensile_modulus_N_per_m",
           "tensile_strength_N_per_m", "bulk_softness_um_per_kPa"]
SHORT = {"thickness_um": "thickness", "bonds_per_fibre": "bonds/fibre",
         "tensile_modulus_N_per_m": "tensile modulus", "tensile_strength_N_per_m": "strength",
         "bulk_softness_um_per_kPa": "ZD compliance"}
# The ZD compliance comes from a compression that is not quasi-static (docs/virtual-tests.md):
# it is shown, but the choice of the default leaves it out.
DECIDING = METRICS[:4]
# (factor label, [(run name, value)], reference run name); the defaults run is "default".
FACTORS = [
    ("particle spacing [diameters]", [("spacing_0.5", 0.5), ("default", 1.0), ("spacing_2", 2.0)],
     "spacing_0.5"),
    ("time-step safety", [("safety_0.25", 0.25), ("default", 0.5), ("safety_0.8", 0.8)],
     "safety_0.25"),
    ("pressing mass scale", [("pressing_mass_100", 100), ("default", 1000),
                             ("pressing_mass_10000", 10000)], "pressing_mass_100"),
]


def error_percent(runs, reference, metric):
    """Mean over the paired seeds of |run - reference| / |reference|, in percent."""
    errors = [100.0 * abs(runs[s]["metrics"][metric] - reference[s]["metrics"][metric]) /
              abs(reference[s]["metrics"][metric]) for s in runs if s in reference]
    return statistics.mean(errors) if errors else float("nan")


def main():
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    folder, figures = sys.argv[1], sys.argv[2]
    default, control = load(folder, "default"), load(folder, "control_perturbed")
    if not default:
        print(f"error: {folder}: no default_s*.json (run scripts/fidelity_study.sh first)",
              file=sys.stderr)
        return 2
    floor = {m: error_percent(control, default, m) for m in METRICS} if control else {}

    header = "| factor | value | wall [s] | " + " | ".join(SHORT[m] for m in METRICS) + " |"
    print(header)
    print("|" + " --- |" * (3 + len(METRICS)))
    if floor:
        wall = statistics.mean(r["wall_s"] for r in control.values())
        print(f"| noise floor: time step -0.2% | 0.499 | {wall:.0f} | " +
              " | ".join(f"{floor[m]:.2f}%" for m in METRICS) + " |")
    fig, axes = plt.subplots(1, len(FACTORS), figsize=(5 * len(FACTORS), 4.2), sharey=True)
    for (factor, settings, ref_name), ax in zip(FACTORS, axes):
        reference = load(folder, ref_name)
        points = []
        for name, value in settings:
            runs = load(folder, name)
            if not runs or not reference:
                continue
            wall = statistics.mean(r["wall_s"] for r in runs.values())
            errors = {m: error_percent(runs, reference, m) for m in METRICS}
            tag = (" (reference)" if name == ref_name
                   else " (default)" if name == "default" else "")
            print(f"| {factor} | {value:g}{tag} | {wall:.0f} | " +
                  " | ".join(f"{errors[m]:.2f}%" for m in METRICS) + " |")
            points.append((value, wall, errors))
        for m in METRICS:
            xs = [w for v, w, e in points if v != dict(settings)[ref_name]]
            ys = [e[m] for v, w, e in points if v != dict(settings)[ref_name]]
            style = "--" if m not in DECIDING else "-"
            line, = ax.plot(xs, ys, style, marker="o", label=SHORT[m])
            if m in floor:
                ax.axhline(floor[m], color=line.get_color(), lw=0.6, ls=":")
        for value, wall, _ in points:
            is_ref = value == dict(settings)[ref_name]
            ax.axvline(wall, color="gray", lw=0.5, ls="-" if is_ref else ":")
            ax.annotate(f"{value:g}" + (" (ref.)" if is_ref else ""), (wall, 0.015), fontsize=7,
                        ha="center", backgroundcolor="white")
        ax.axhline(2.0, color="k", lw=0.8, label="2%")
        ax.set_xlim(0, 1.1 * max(w for _, w, _ in points))
        ax.set_yscale("log")
        ax.set_ylim(0.01, 100)
        ax.set_xlabel("wall time per run, 1 thread [s]")
        ax.set_title(f"{factor}\n(reference {dict(settings)[ref_name]:g})", fontsize=10)
    explore = load(folder, "explore")
    if explore:
        wall = statistics.mean(r["wall_s"] for r in explore.values())
        print(f"| safety 0.8 and pressing mass 10000, against the defaults | - | {wall:.0f} | " +
              " | ".join(f"{error_percent(explore, default, m):.2f}%" for m in METRICS) + " |")
    axes[0].set_ylabel("error against the reference [%]")
    axes[-1].legend(fontsize=7, loc="upper right")
    fig.suptitle("Speed against error, study-fidelity.toml (dotted: noise floor, time step "
                 "-0.2%; dashed: ZD compliance, not quasi-static)", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(figures, "fidelity_speed_error.png"), dpi=120)
    return 0


if __name__ == "__main__":
    sys.exit(main())
