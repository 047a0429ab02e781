"""Plots of the creping study (scripts/creping_study.sh): crepe frequency and amplitude, bond
loss, dust and bulk against adhesion strength for each creping angle; the bond-loss curve
over time (paper Fig. 7) of the reference run (85 deg, 10 mN), and the crepe profile of the
run whose creped sheet is the longest among those with a fold train (the longest of all if
none has one): the height, its waviness and the crepe band.
Usage: /usr/bin/python3 scripts/plot_creping_study.py OUT_DIR FIGURE_DIR"""
import csv
import json
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

out, figures = sys.argv[1], sys.argv[2]
angles, adhesions = [75, 85, 95], [3, 10, 30]


def details(name):
    with open(os.path.join(out, name + ".json")) as f:
        run = json.load(f)
    return next(s for s in run["stages"] if s["name"] == "creping")["details"]


def column(path, name):
    with open(path) as f:
        return [float(r[name]) for r in csv.DictReader(f)]


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

reference = os.path.join(out, "angle85_adh10")
fig, (left, right) = plt.subplots(1, 2, figsize=(12, 3.6))
curve = os.path.join(reference, "curves", "creping_bond_loss.csv")
t = column(curve, "time_us")
t = [x - t[0] for x in t]  # from the first sample (older runs counted from the forming start)
left.plot(t, column(curve, "fibre_fibre_broken_fraction"), label="fibre-fibre bonds")
left.plot(t, column(curve, "adhesive_broken_fraction"), label="adhesive bonds (Yankee)")
left.set_xlabel("time since the blade met the sheet [us]")
left.set_ylabel("fraction broken")
left.legend()


def profile_of(name):
    with open(os.path.join(out, name, "curves", "crepe_profile.csv")) as f:
        rows_ = list(csv.DictReader(f))
    return {key: [float(r[key]) for r in rows_] for key in rows_[0]}


names = [f"angle{angle}_adh{a}" for angle, a, _ in rows]
folded = [n for n, (_, _, d) in zip(names, rows) if d["crepe_frequency_per_mm"] > 0]
profiles = {n: profile_of(n) for n in names}
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
