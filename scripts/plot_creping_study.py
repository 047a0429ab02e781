"""Plots of the creping study (scripts/creping_study.sh): crepe frequency and amplitude, bond
loss, dust and bulk against adhesion strength for each creping angle; the bond-loss curve
over time (paper Fig. 7) of the reference run (85 deg, 10 mN), and the crepe profile of the
run whose creped sheet is the longest among those with a fold train (the longest of all if
none has one): the height, its waviness and the crepe band.
Usage: /usr/bin/python3 scripts/plot_creping_study.py OUT_DIR FIGURE_DIR"""
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

from creping_runs import curve, details as details_in

out, figures = sys.argv[1], sys.argv[2]
angles, adhesions = [75, 85, 95], [3, 10, 30]


def details(name):
    return details_in(out, name)


panels = [("crepe_frequency_per_mm", "crepe frequency [1/mm] (0: no fold train)"),
          ("crepe_amplitude_um", "crepe band amplitude [um]"),
          ("bonds_broken_fraction", "fibre-fibre bonds broken"),
          ("dust_mass_fraction", "dust mass fraction"),
          ("bulk_gain", "bulk gain at rest (caliper after / before)")]
fig, axes = plt.subplots(1, len(panels), figsize=(20, 3.6))
rows = []
for angle in angles:
    runs = [details(f"angle{angle}_adh{a}") for a in adhesions]
    for a, d in zip(adhesions, runs):
        rows.append((angle, a, d))
    for ax, (key, label) in zip(axes, panels):
        ax.plot(adhesions, [d[key] for d in runs], "o-", label=f"{angle} deg")
        ax.set_xscale("log")
        ax.set_xlabel("adhesion strength F_r0 = F_s0 [mN]")
        ax.set_ylabel(label)
axes[0].legend(title="creping angle")
fig.tight_layout()
fig.savefig(os.path.join(figures, "creping_study.png"), dpi=110)

fig, (left, right) = plt.subplots(1, 2, figsize=(12, 3.6))
loss = curve(out, "angle85_adh10", "creping_bond_loss")
# From the first sample (older runs counted from the forming start).
t = [x - loss["time_us"][0] for x in loss["time_us"]]
left.plot(t, loss["fibre_fibre_broken_fraction"], label="fibre-fibre bonds")
left.plot(t, loss["adhesive_broken_fraction"], label="adhesive bonds (Yankee)")
left.set_xlabel("time since the blade met the sheet [us]")
left.set_ylabel("fraction broken")
left.legend()

names = [f"angle{angle}_adh{a}" for angle, a, _ in rows]
folded = [n for n, (_, _, d) in zip(names, rows) if d["crepe_frequency_per_mm"] > 0]
profiles = {n: curve(out, n, "crepe_profile") for n in names}
shown = max(folded or names, key=lambda n: len(profiles[n]["u_um"]))
p = profiles[shown]
right.plot(p["u_um"], p["height_um"], label="top surface")
right.plot(p["u_um"], p["waviness_um"], label="waviness (the sheet's shape)")
base = min(p["waviness_um"]) - 2 * max(abs(v) for v in p["folds_um"])
right.plot(p["u_um"], [base + v for v in p["folds_um"]], label="crepe band (shifted down)")
d = details(shown)
right.set_title(f"{shown.replace('angle', '').replace('_adh', ' deg, ')} mN: "
                f"{d['crepe_frequency_per_mm']:.2f} folds/mm, {d['crepe_amplitude_um']:.0f} um",
                fontsize=10)
right.set_xlabel("position along the creped sheet [um]")
right.set_ylabel("height [um]")
right.legend(fontsize=8)
fig.tight_layout()
fig.savefig(os.path.join(figures, "creping_bond_loss_and_profile.png"), dpi=110)

print("| angle [deg] | adhesion [mN] | crepe freq [1/mm] | amplitude [um] | ff bonds broken | "
      "dust mass | bulk gain | energy error | wall [s] |")
print("|---|---|---|---|---|---|---|---|---|")
for angle, a, d in rows:
    print(f"| {angle} | {a} | {d['crepe_frequency_per_mm']:.2f} | {d['crepe_amplitude_um']:.1f} | "
          f"{d['bonds_broken_fraction']:.3f} | {d['dust_mass_fraction']:.3f} | {d['bulk_gain']:.2f} | "
          f"{d['energy_balance_error']:.4f} | |")
fast = details("speed60")
print(f"60 m/s: frequency {fast['crepe_frequency_per_mm']:.2f}/mm, bonds broken "
      f"{fast['bonds_broken_fraction']:.3f}, past blade {fast['particles_past_blade']:.0f}, "
      f"energy error {fast['energy_balance_error']:.4f}")
