"""The creping runs on the plane of web strength against coating toughness, one panel per
creping angle: each run a marker at (coating toughness, the web's fibre-fibre bond strength),
coloured by the fibre-fibre bonds broken in the strip's middle and labelled with the length
delaminated ahead of the blade [um]; circles for 2.5 mm strips (mostly the start), squares for
5 mm strips (the steady state in the middle).
Usage: /usr/bin/python3 scripts/plot_creping_regimes.py OUT.png RUN:WEB_mN:ANGLE_deg:STRIP_mm ...
where RUN is FOLDER/NAME of a creping run (FOLDER/NAME.json, as the study scripts write it)."""
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.ticker import NullFormatter, ScalarFormatter

from creping_runs import details


def parse(spec):
    try:
        run, web, angle, strip = spec.rsplit(":", 3)
        return run, float(web), float(angle), float(strip)
    except ValueError:
        sys.exit(f"error: '{spec}': expected RUN:WEB_mN:ANGLE_deg:STRIP_mm")


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    runs = []
    for spec in argv[2:]:
        run, web, angle, strip = parse(spec)
        d = details(os.path.dirname(run) or ".", os.path.basename(run))
        runs.append((angle, web, strip, d))
    angles = sorted({r[0] for r in runs})
    fig, axes = plt.subplots(1, len(angles), figsize=(6 * len(angles), 4.6), squeeze=False)
    for ax, angle in zip(axes[0], angles):
        for _, web, strip, d in (r for r in runs if r[0] == angle):
            # 5 mm strips drawn a little above their web's row so both stay readable.
            y = web * (1.12 if strip > 3 else 1.0)
            dots = ax.scatter(d["coating_toughness_J_per_m2"], y, c=[d["bonds_broken_fraction"]],
                              cmap="inferno_r", vmin=0.0, vmax=0.7, s=140,
                              marker="s" if strip > 3 else "o", edgecolors="k")
            ax.annotate(f"{d['delaminated_length_um']:.0f}",
                        (d["coating_toughness_J_per_m2"], y), textcoords="offset points",
                        xytext=(9, 4), fontsize=8)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlim(25, 200)
        ax.set_ylim(18, 140)
        ax.set_xticks([30, 45, 67, 100, 135])
        ax.set_yticks([25, 50, 100])
        for axis in (ax.xaxis, ax.yaxis):
            axis.set_major_formatter(ScalarFormatter())
            axis.set_minor_formatter(NullFormatter())
        ax.set_xlabel("coating toughness [J/m^2]")
        ax.set_ylabel("fibre-fibre bond strength of the web [mN]")
        ax.set_title(f"creping angle {angle:g} deg", fontsize=10)
    fig.suptitle("label: length delaminated ahead of the blade [um]; "
                 "circles 2.5 mm strips, squares 5 mm strips", fontsize=9)
    fig.colorbar(dots, ax=axes[0].tolist(), label="fibre-fibre bonds broken (middle)")
    fig.savefig(argv[1], dpi=90)


if __name__ == "__main__":
    main(sys.argv)
