#!/usr/bin/env python3
"""Speed against error of the validation suite: one line per case through its fidelities,
and the table of every case and fidelity (Markdown, on stdout).

Usage: fibrenet validate --json > validation.json
       scripts/plot_validation.py validation.json docs/figures/validation_speed_error.png
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(argv):
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    with open(argv[1]) as f:
        cases = json.load(f)["cases"]
    by_name = {}
    for c in cases:
        by_name.setdefault(c["name"], []).append(c)
    fig, ax = plt.subplots(figsize=(8, 6))
    floor = 1e-16  # exact cases (error 0) are drawn at the floor
    colours = plt.cm.tab20.colors
    markers = "osD^v<>"
    for k, (name, runs) in enumerate(sorted(by_name.items())):
        runs.sort(key=lambda r: r["wall_s"])
        wall = [max(r["wall_s"], 1e-4) for r in runs]
        err = [max(r["error"], floor) for r in runs]
        line, = ax.plot(wall, err, "-" + markers[k % len(markers)], label=name, markersize=4,
                        color=colours[k % len(colours)])
        for r, w, e in zip(runs, wall, err):
            if r["default"]:
                ax.plot([w], [e], "*", color=line.get_color(), markersize=12)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time of the case [s]")
    ax.set_ylabel("relative error against the reference")
    ax.set_title("fibrenet validate: error against wall time (star: default fidelity)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(argv[2], dpi=120)

    print("| case | fidelity | error | tolerance | passed | wall time [s] |")
    print("| --- | --- | --- | --- | --- | --- |")
    for c in cases:
        print(f"| {c['name']} | {c['fidelity']} | {c['error']:.2e} | {c['tolerance']:.0e} | "
              f"{'yes' if c['passed'] else 'NO'} | {c['wall_s']:.3f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
