#!/usr/bin/env python3
"""Side views (MD against thickness, true scale) of stage snapshots.

    /usr/bin/python3 scripts/plot_side_view.py OUT.png SNAPSHOT.h5[=TITLE] ...

Each snapshot (DIR/snapshots/STAGE.h5 of `fibrenet run --out DIR`) gets one panel: every
particle's centre in the x-z plane, the cell's y folded onto it, so that folds, loops and a
sheet's tilt show as they lie.
"""
import sys

import h5py
import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    out, specs = argv[1], argv[2:]
    panels = []
    for spec in specs:
        path, _, title = spec.partition("=")
        with h5py.File(path, "r") as f:
            x = f["particles/x"][:] * 1e6
        panels.append((title or path, x))
    width = max(np.ptp(p[1][:, 0]) for p in panels)
    heights = [max(np.ptp(x[:, 2]), 0.05 * width) + 40.0 for _, x in panels]
    fig, axes = plt.subplots(len(panels), 1, squeeze=False,
                             figsize=(12, 1.0 + 12 * sum(heights) / width),
                             gridspec_kw={"height_ratios": heights})
    for ax, (title, x) in zip(axes[:, 0], panels):
        ax.scatter(x[:, 0] - x[:, 0].min(), x[:, 2], s=0.2, color="tab:blue")
        ax.set_xlim(0, width)
        ax.set_aspect("equal")
        ax.set_title(title, fontsize=9)
        ax.set_ylabel("z [um]")
    axes[-1, 0].set_xlabel("x (MD) [um]")
    fig.tight_layout()
    fig.savefig(out, dpi=80)


if __name__ == "__main__":
    main(sys.argv)
