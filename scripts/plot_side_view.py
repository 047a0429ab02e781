#!/usr/bin/env python3
"""Side views (MD against thickness, true scale) of stage snapshots.

    /usr/bin/python3 scripts/plot_side_view.py [--speed VMAX] OUT.png SNAPSHOT.h5[=TITLE] ...

Each snapshot (DIR/snapshots/STAGE.h5 of `fibrenet run --out DIR`) gets one panel: every
particle's centre in the x-z plane, the cell's y folded onto it, so that folds, loops and a
sheet's tilt show as they lie.

With --speed the particles are coloured by their speed (0 to VMAX m/s, as paper Fig. 6 colours
the creping impact) and every panel keeps the snapshot's own x, so that the impact frames of
one run (DIR/snapshots/creping_frame_NNN.h5) line up along the Yankee; without it each panel
starts at its sheet's first particle. A snapshot that holds a blade (creping's frames) shows
its face as a grey line from the tip.
"""
import sys

import h5py
import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_panels(specs, with_speed):
    panels = []
    for spec in specs:
        path, _, title = spec.partition("=")
        with h5py.File(path, "r") as f:
            x = f["particles/x"][:] * 1e6
            speed = np.linalg.norm(f["particles/v"][:], axis=1) if with_speed else None
            # tip x, z and the face's direction up, x and z (blades/state's columns 0-8)
            blades = f["blades/state"][:][:, [0, 2, 6, 8]] if "blades/state" in f else []
        panels.append((title or path, x, speed, [b * [1e6, 1e6, 1, 1] for b in blades]))
    return panels


def main(argv):
    args = argv[1:]
    speed_max = None
    if args[:1] == ["--speed"]:
        if len(args) < 2:
            sys.exit(__doc__)
        try:
            speed_max = float(args[1])
        except ValueError:
            sys.exit(f"error: --speed: '{args[1]}' is not a number of m/s")
        args = args[2:]
    if len(args) < 2:
        sys.exit(__doc__)
    out, panels = args[0], read_panels(args[1:], speed_max is not None)
    if speed_max is None:
        starts = [x[:, 0].min() for _, x, _, _ in panels]
        panels = [(t, x - [x0, 0.0, 0.0], s, [b - [x0, 0.0, 0.0, 0.0] for b in bl])
                  for x0, (t, x, s, bl) in zip(starts, panels)]
    left = min(x[:, 0].min() for _, x, _, _ in panels)
    right = max(x[:, 0].max() for _, x, _, _ in panels)
    width = right - left
    heights = [max(np.ptp(x[:, 2]), 0.05 * width) + 40.0 for _, x, _, _ in panels]
    fig, axes = plt.subplots(len(panels), 1, squeeze=False,
                             figsize=(12, 1.0 + 12 * sum(heights) / width),
                             gridspec_kw={"height_ratios": heights})
    for ax, (title, x, speed, blades) in zip(axes[:, 0], panels):
        for tip_x, tip_z, up_x, up_z in blades:
            reach = (x[:, 2].max() - tip_z) / up_z if up_z > 0 else 0.0
            ax.plot([tip_x, tip_x + reach * up_x], [tip_z, tip_z + reach * up_z], color="0.5",
                    linewidth=1.5, zorder=3)
        if speed_max is None:
            ax.scatter(x[:, 0], x[:, 2], s=0.2, color="tab:blue")
        else:
            dots = ax.scatter(x[:, 0], x[:, 2], s=0.2, c=speed, cmap="viridis", vmin=0.0,
                              vmax=speed_max)
            fig.colorbar(dots, ax=ax, label="speed [m/s]", pad=0.01, fraction=0.02)
        ax.set_xlim(left, right)
        ax.set_aspect("equal")
        ax.set_title(title, fontsize=9)
        ax.set_ylabel("z [um]")
    axes[-1, 0].set_xlabel("x (MD) [um]")
    fig.tight_layout()
    fig.savefig(out, dpi=80)


if __name__ == "__main__":
    main(sys.argv)
