"""Plots of the creping study on held webs (scripts/creping_study_held.sh): crepe frequency,
folds counted, crepe band amplitude, the Yankee length gathered into the creped sheet, bond
loss, dust and bulk against the coating's toughness for each creping angle, and the crepe band
of every run; prints the study's tables.
Usage: /usr/bin/python3 scripts/plot_creping_study_held.py OUT_DIR FIGURE_DIR"""
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

from creping_runs import curve, stage

out, figures = sys.argv[1], sys.argv[2]
angles, moduli = [75, 85, 95], ["10", "7.5", "5"]  # coating modulus [MPa]: stronger to the right
runs = {(a, m): stage(out, f"angle{a}_e{m}") for a in angles for m in moduli}


def folds_per_mm(d):
    return d["crepe_fold_count"] / (d["crepe_profile_length_um"] * 1e-3)


panels = [(lambda d: d["crepe_frequency_per_mm"], "crepe frequency [1/mm] (0: no fold train)"),
          (folds_per_mm, "folds counted per mm of profile"),
          (lambda d: d["crepe_amplitude_um"], "crepe band amplitude [um]"),
          (lambda d: d["crepe_gathered_ratio"], "Yankee length gathered (1.15: the reel's)"),
          (lambda d: d["bonds_broken_fraction"], "fibre-fibre bonds broken (middle)"),
          (lambda d: d["dust_mass_fraction"], "dust mass fraction"),
          (lambda d: d["bulk_gain"], "bulk gain at rest")]
fig, grid = plt.subplots(2, 4, figsize=(17, 7))
axes = list(grid.flat)
for angle in angles:
    ds = [runs[angle, m]["details"] for m in moduli]
    toughness = [d["coating_toughness_J_per_m2"] for d in ds]
    for ax, (value, label) in zip(axes, panels):
        ax.plot(toughness, [value(d) for d in ds], "o-", label=f"{angle} deg")
        ax.set_xlabel("coating toughness [J/m^2]")
        ax.set_ylabel(label)
grid[0][0].legend(title="creping angle")
grid[1][3].axis("off")
fig.tight_layout()
fig.savefig(os.path.join(figures, "creping_study_held.png"), dpi=110)

fig, grid = plt.subplots(len(moduli), len(angles), figsize=(15, 8), sharey=True)
for row, m in enumerate(moduli):
    for col, angle in enumerate(angles):
        d = runs[angle, m]["details"]
        p = curve(out, f"angle{angle}_e{m}", "crepe_profile")
        ax = grid[row][col]
        ax.plot(p["u_um"], p["folds_um"])
        for level in (-1, 1):
            ax.axhline(level * d["crepe_min_amplitude_um"], color="grey", linestyle="--", lw=0.8)
        ax.set_title(f"{angle} deg, {d['coating_toughness_J_per_m2']:.1f} J/m^2: "
                     f"{d['crepe_fold_count']:.0f} folds, {d['crepe_frequency_per_mm']:.2f}/mm",
                     fontsize=9)
        if row == len(moduli) - 1:
            ax.set_xlabel("position along the creped sheet [um]")
        if col == 0:
            ax.set_ylabel("crepe band [um]")
fig.tight_layout()
fig.savefig(os.path.join(figures, "creping_study_held_profiles.png"), dpi=110)

print("| angle [deg] | toughness [J/m^2] | delaminated [um] | crepe freq [1/mm] | folds (profile "
      "[mm]) | crepe band [um] | ff broken (middle) | (whole strip) | dust mass | bulk at the "
      "blade | bulk at rest | energy error | past the blade | wall [s] |")
print("|" + "---|" * 14)
for m in moduli:
    for angle in angles:
        s = runs[angle, m]
        d = s["details"]
        print(f"| {angle} | {d['coating_toughness_J_per_m2']:.1f} | "
              f"{d['delaminated_length_um']:.0f} | {d['crepe_frequency_per_mm']:.2f} | "
              f"{d['crepe_fold_count']:.0f} ({d['crepe_profile_length_um'] * 1e-3:.2f}) | "
              f"{d['crepe_amplitude_um']:.1f} | {d['bonds_broken_fraction']:.3f} | "
              f"{d['bonds_broken_fraction_all']:.3f} | {d['dust_mass_fraction']:.3f} | "
              f"{d['caliper_at_blade_um'] / d['caliper_before_um']:.2f} | {d['bulk_gain']:.2f} | "
              f"{d['energy_balance_error']:.4f} | {d['particles_past_blade']:.0f} | "
              f"{s['wall_s']:.0f} |")

print()
print("| angle [deg] | toughness [J/m^2] | Yankee length gathered | = curl | x folds | "
      "x in plane |")
print("|" + "---|" * 6)
for m in moduli:
    for angle in angles:
        d = runs[angle, m]["details"]
        print(f"| {angle} | {d['coating_toughness_J_per_m2']:.1f} | "
              f"{d['crepe_gathered_ratio']:.3f} | {d['crepe_curl_ratio']:.3f} | "
              f"{d['crepe_fold_ratio']:.3f} | {d['crepe_in_plane_ratio']:.3f} |")
