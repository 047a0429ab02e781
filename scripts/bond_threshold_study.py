"""Fibre-fibre bonds per fibre against the bonding threshold (docs/network.md).

With `rest_length = "current"` a fibre-fibre bond keeps as its rest length L0 the centre
distance at which it formed during the pressing hold, so a pressing snapshot tells which of
its bonds a stricter rule would have made: with gap_tolerance g a pair bonds when its
distance is below (R_i + R_j)(1 + g), i.e. when L0 / (R_i + R_j) < 1 + g. Prints, for each g,
the particle bonds per fibre (2 x bonds / fibres, the `bonds_per_fibre` metric) and the
bonded fibre pairs per fibre (`bonded_pairs_per_fibre`), and plots both.

Usage: /usr/bin/python3 scripts/bond_threshold_study.py SNAPSHOT.h5 [FIGURE.png]
SNAPSHOT.h5 is `snapshots/pressing.h5` of `fibrenet run SCENE --out DIR` for a scene whose
pressing bonds with gap_tolerance 0 and rest_length "current".
"""
import sys

import h5py
import numpy as np


def thresholds_table(path, tolerances):
    with h5py.File(path, "r") as f:
        ij = f["bonds/ij"][:]
        rest = f["bonds/L0"][:]
        broken = f["bonds/broken"][:].astype(bool)
        radius = f["particles/radius"][:]
        fibre = f["particles/fibre"][:]
    fibres = len(np.unique(fibre))
    between = (fibre[ij[:, 0]] != fibre[ij[:, 1]]) & ~broken
    ratio = rest[between] / (radius[ij[between, 0]] + radius[ij[between, 1]])
    pairs = np.sort(fibre[ij[between]], axis=1)
    rows = []
    for g in tolerances:
        kept = ratio < 1.0 + g
        bonded_pairs = len(np.unique(pairs[kept], axis=0)) if kept.any() else 0
        rows.append((g, 2.0 * kept.sum() / fibres, 2.0 * bonded_pairs / fibres))
    return rows, np.percentile(ratio, [5, 25, 50, 75, 95])


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    tolerances = [0.0, -0.05, -0.1, -0.15, -0.2, -0.25, -0.3, -0.35, -0.4, -0.42, -0.44,
                  -0.46, -0.48, -0.5]
    rows, quantiles = thresholds_table(sys.argv[1], tolerances)
    print("L0 / (R_i + R_j) of the bonds, percentiles 5/25/50/75/95: " +
          " ".join(f"{q:.3f}" for q in quantiles))
    print("gap_tolerance  bonds_per_fibre  bonded_pairs_per_fibre")
    for g, bonds, pairs in rows:
        print(f"{g:13.2f}  {bonds:15.2f}  {pairs:22.2f}")
    if len(sys.argv) == 3:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        g = [r[0] for r in rows]
        fig, ax = plt.subplots(figsize=(6, 4))
        ax.plot(g, [r[1] for r in rows], "o-", label="particle bonds per fibre")
        ax.plot(g, [r[2] for r in rows], "s-", label="bonded fibre pairs per fibre")
        ax.axhline(3.2, color="grey", ls="--", label="paper's generic network (3.2)")
        ax.set_yscale("log")
        ax.set_xlabel("gap_tolerance (bond when d < (R_i + R_j)(1 + g))")
        ax.set_ylabel("per fibre")
        ax.legend()
        fig.tight_layout()
        fig.savefig(sys.argv[2], dpi=120)


if __name__ == "__main__":
    main()
