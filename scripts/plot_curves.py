#!/usr/bin/env python3
"""Plots of the curves the virtual tests write as CSV (`fibrenet run SCENE --out DIR` writes
them under DIR/curves/): one PNG per CSV, or one figure for several CSVs of the same kind with
--overlay (e.g. the compression loops of the attribution variants).

Recognised by their header:
  tensile_*.csv        stress (N/m) against strain, coloured by branch (load, unload, reload),
                       with the strain-energy increments by mode on a second panel
  compression*.csv     ZD pressure (kPa) against strain: loading and unloading (the loop)
  bending_*.csv        moment per width against curvature
  roughness_spectrum*  RMS amplitude against wavelength (log-log)
  height_profile.csv   surface height along x
  *_density_profile.csv  density against height z (--overlay: one line per stage)
  cox_curve.csv        network modulus / affine (Cox) limit against bonded crossings per fibre
  bond_level.csv       tensile modulus and strength against bond level
  anything else        every column against the first

Usage:
  python3 scripts/plot_curves.py DIR_OR_CSV [...] [--out DIR] [--overlay] [--title TEXT]
Needs matplotlib (Debian: python3-matplotlib; use /usr/bin/python3 where another python3
comes first on PATH). Exit codes: 0 success, 2 bad input.
"""
import argparse
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

BRANCH_NAMES = {0: "loading", 1: "unloading", 2: "reloading"}


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if not rows:
        raise ValueError(f"{path}: empty file")
    header = rows[0]
    cols = {name: [] for name in header}
    for row in rows[1:]:
        for name, value in zip(header, row):
            cols[name].append(float(value))
    return header, cols


def kind_of(path, header):
    name = os.path.basename(path)
    if "stress_N_per_m" in header:
        return "tensile"
    if "pressure_Pa" in header:
        return "compression"
    if "moment_N_m_per_m" in header:
        return "bending"
    if "wavelength_um" in header:
        return "spectrum"
    if "height_um" in header:
        return "profile"
    if "density_kg_per_m3" in header:
        return "density"
    if name.startswith("cox_curve"):
        return "cox"
    if name.startswith("bond_level"):
        return "bond_level"
    return "generic"


def split_branches(cols, x, y):
    """Yields (branch, xs, ys) runs of consecutive samples on one branch."""
    branch = cols.get("branch", [0.0] * len(cols[x]))
    start = 0
    for k in range(1, len(branch) + 1):
        if k == len(branch) or branch[k] != branch[start]:
            # Join each run to the previous sample so the path has no gap.
            s = max(start - 1, 0)
            yield int(branch[start]), cols[x][s:k], cols[y][s:k]
            start = k


def plot_tensile(ax, cols, label):
    for b, xs, ys in split_branches(cols, "strain", "stress_N_per_m"):
        name = (label + " " if label else "") + BRANCH_NAMES.get(b, f"branch {b}")
        ax.plot([100 * v for v in xs], ys, label=name)
    ax.set_xlabel("strain (%)")
    ax.set_ylabel("stress (N/m)")


def plot_energy(ax, cols):
    strain = [100 * v for v in cols["strain"]]
    for mode in ("normal", "shear", "bending", "twist"):
        key = f"energy_{mode}_J"
        if key in cols:
            ax.plot(strain, [1e9 * v for v in cols[key]], label=mode)
    ax.set_xlabel("strain (%)")
    ax.set_ylabel("strain energy increment (nJ)")
    ax.legend(fontsize=8)


def plot_compression(ax, cols, label):
    for b, xs, ys in split_branches(cols, "strain", "pressure_Pa"):
        style = "-" if b == 0 else "--"
        name = f"{label} " if label else ""
        ax.plot(xs, [1e-3 * v for v in ys], style, label=name + BRANCH_NAMES.get(b, str(b)))
    ax.set_xlabel("ZD strain")
    ax.set_ylabel("pressure (kPa)")


def plot_generic(ax, header, cols, label):
    x = header[0]
    for y in header[1:]:
        ax.plot(cols[x], cols[y], "o-", ms=3, label=(label + " " if label else "") + y)
    ax.set_xlabel(x)


def draw(ax, kind, header, cols, label):
    if kind == "tensile":
        plot_tensile(ax, cols, label)
    elif kind == "compression":
        plot_compression(ax, cols, label)
    elif kind == "bending":
        ax.plot(cols["curvature_per_m"], [1e6 * v for v in cols["moment_N_m_per_m"]], "o-",
                label=label or "moment")
        ax.set_xlabel("curvature (1/m)")
        ax.set_ylabel("moment per width (uN m/m)")
    elif kind == "spectrum":
        ax.loglog(cols["wavelength_um"], cols["amplitude_um"], "o-", ms=3, label=label or None)
        ax.set_xlabel("wavelength (um)")
        ax.set_ylabel("RMS amplitude (um)")
    elif kind == "profile":
        # Surface profiles run along x; the crepe profile along the creped sheet (u), with
        # its waviness and crepe band beside the height.
        x = header[0]
        for y in ("height_um", "waviness_um", "folds_um"):
            if y in cols:
                name = (label + " " if label else "") + y[:-3]
                ax.plot(cols[x], cols[y], label=name)
        ax.set_xlabel(x.replace("_um", " (um)"))
        ax.set_ylabel("height (um)")
        if "waviness_um" in cols:
            ax.legend(fontsize=8)
    elif kind == "density":
        # Height on the vertical axis, as the sheet lies.
        ax.plot(cols["density_kg_per_m3"], cols["z_um"], label=label or None)
        ax.set_xlabel("density (kg/m^3)")
        ax.set_ylabel("z (um)")
    elif kind == "cox":
        x = cols["crossings_per_fibre"]
        for key, name in (("modulus_over_cox", "E / (E_f phi / 3)"),
                          ("c11_over_affine", "C11 / affine C11")):
            if key in cols:
                ax.plot(x, cols[key], "o-", label=name)
        ax.axhline(1.0, color="gray", lw=0.8)
        ax.axhspan(0.9, 1.1, color="gray", alpha=0.15, label="within 10%")
        ax.set_xscale("log")
        ax.set_xlabel("bonded crossings per fibre")
        ax.set_ylabel("network modulus / affine limit")
    elif kind == "bond_level":
        x = header[0]
        for key in header[1:]:
            ax.plot(cols[x], cols[key], "o-", label=key)
        ax.set_xlabel(x)
        ax.set_yscale("log")
    else:
        plot_generic(ax, header, cols, label)


def figure_for(paths, out, title, overlay):
    kinds = []
    data = []
    for p in paths:
        header, cols = read_csv(p)
        kinds.append(kind_of(p, header))
        data.append((p, header, cols))
    two_panels = kinds[0] == "tensile" and not overlay and "energy_normal_J" in data[0][2]
    fig, axes = plt.subplots(1, 2 if two_panels else 1, figsize=(10 if two_panels else 6, 4.2))
    ax = axes[0] if two_panels else axes
    for (p, header, cols), kind in zip(data, kinds):
        label = os.path.splitext(os.path.basename(p))[0] if overlay else ""
        draw(ax, kind, header, cols, label)
    if two_panels:
        plot_energy(axes[1], data[0][2])
    ax.grid(True, alpha=0.3)
    handles, _ = ax.get_legend_handles_labels()
    if handles:
        ax.legend(fontsize=8)
    ax.set_title(title or os.path.splitext(os.path.basename(paths[0]))[0])
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    plt.close(fig)
    return out


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("inputs", nargs="+", help="CSV files or folders holding them")
    ap.add_argument("--out", help="folder for the PNGs (default: next to each CSV)")
    ap.add_argument("--overlay", action="store_true", help="all inputs in one figure")
    ap.add_argument("--title", default="", help="figure title")
    args = ap.parse_args(argv)
    paths = []
    for item in args.inputs:
        if os.path.isdir(item):
            paths += sorted(os.path.join(item, f) for f in os.listdir(item) if f.endswith(".csv"))
        elif os.path.isfile(item):
            paths.append(item)
        else:
            print(f"error: {item}: no such file or folder", file=sys.stderr)
            return 2
    if not paths:
        print("error: no CSV files given", file=sys.stderr)
        return 2
    if args.out:
        os.makedirs(args.out, exist_ok=True)

    def target(path):
        folder = args.out or os.path.dirname(os.path.abspath(path))
        return os.path.join(folder, os.path.splitext(os.path.basename(path))[0] + ".png")

    try:
        if args.overlay:
            print(figure_for(paths, target(paths[0]).replace(".png", "_overlay.png"), args.title, True))
        else:
            for p in paths:
                print(figure_for([p], target(p), args.title, False))
    except (ValueError, KeyError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
