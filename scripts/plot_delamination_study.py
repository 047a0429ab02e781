"""Plots of the delamination study (scripts/delamination_study.sh): how far ahead of the blade
the web comes off the Yankee against the coating's toughness and against that toughness over
the scraped sheet's momentum flux rho_A V^2, and the fibre-fibre bonds broken. Prints the table
of docs/creping.md.
Usage: /usr/bin/python3 scripts/plot_delamination_study.py OUT_DIR FIGURE_DIR"""
import json
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

out, figures = sys.argv[1], sys.argv[2]
speeds, moduli, strengths = [15, 30, 60], [10, 100], [3, 5, 10]
markers = {15: "v", 30: "o", 60: "^"}
colours = {10: "tab:blue", 100: "tab:red"}


def details(name):
    with open(os.path.join(out, name + ".json")) as f:
        run = json.load(f)
    return next(s for s in run["stages"] if s["name"] == "creping")["details"]


toughness = "coating_toughness_J_per_m2"
panels = [(toughness, "delaminated_length_um", "coating toughness [J/m^2]",
           "delaminated length ahead of the blade [um]\n(median over the strip's middle)"),
          ("ratio", "delaminated_length_um", "coating toughness / momentum flux rho_A V^2",
           "delaminated length [um]"),
          (toughness, "bonds_broken_fraction", "coating toughness [J/m^2]",
           "fibre-fibre bonds broken (middle)")]
fig, axes = plt.subplots(1, len(panels), figsize=(15, 4))
print("| V [m/s] | coating [MPa] | F [mN] | toughness [J/m^2] | rho_A V^2 [N/m] | ratio | "
      "delaminated [um] | (largest) | ff broken (middle) | dust mass | energy error |")
print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
for speed in speeds:
    for modulus in moduli:
        runs = [details(f"v{speed}_e{modulus}_f{f}") for f in strengths]
        for d in runs:
            d["ratio"] = d[toughness] / d["momentum_flux_N_per_m"]
        for f, d in zip(strengths, runs):
            print(f"| {speed} | {modulus} | {f} | {d[toughness]:.2f} | "
                  f"{d['momentum_flux_N_per_m']:.1f} | {d['ratio']:.3f} | "
                  f"{d['delaminated_length_um']:.0f} | {d['delaminated_length_max_um']:.0f} | "
                  f"{d['bonds_broken_fraction']:.3f} | {d['dust_mass_fraction']:.3f} | "
                  f"{d['energy_balance_error']:.4f} |")
        for ax, (xkey, ykey, _, _) in zip(axes, panels):
            ax.plot([d[xkey] for d in runs], [d[ykey] for d in runs], marker=markers[speed],
                    color=colours[modulus], ls=":", label=f"{speed} m/s, {modulus} MPa coating")
            for f, d in zip(strengths, runs):
                ax.annotate(f"{f}", (d[xkey], d[ykey]), textcoords="offset points",
                            xytext=(4, 3), fontsize=7)
for ax, (_, _, xlabel, ylabel) in zip(axes, panels):
    ax.set_xscale("log")
    ax.set_xlabel(xlabel + "\n(numbers: adhesion strength, mN)")
    ax.set_ylabel(ylabel)
axes[0].set_yscale("log")
axes[1].set_yscale("log")
axes[1].axvline(1.0, color="grey", lw=0.8, ls="--")
axes[0].legend(fontsize=7)
fig.tight_layout()
fig.savefig(os.path.join(figures, "delamination_study.png"), dpi=110)
