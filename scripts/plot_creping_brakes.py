"""The brakes on the creped sheet over time (scripts/creping_study_friction.sh): one column per
web, rows for the blade's MD load, the reel's pull along the face (negative: it holds back)
and the distance of the peel front ahead of the tip, one line per setting of the blade's
friction mu and the reel's draw time tau. The grey band is the steady window T0_US-T1_US
(default 100-165 us: the tip over the second half of the 5 mm strip's middle), over which
the legend gives each run's mean blade load.
Prints the table of docs/creping.md ("Then on the steady state") for every run, those on
other coatings (cWEB_eMODULUS_muMU_tauTAU, not plotted) included.
Usage: /usr/bin/python3 scripts/plot_creping_brakes.py OUT.png FOLDER [T0_US T1_US]
where FOLDER holds the runs wWEB_muMU_tauTAU.json with their curves."""
import glob
import math
import os
import re
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

from creping_runs import (curve, gathered_split, mean_over, median_over, stage,
                          stored_energy_ratio)

# wWEB_...: the study script's runs on the web's own coating; cWEB_eMODULUS_...: other coatings.
RUN_NAME = re.compile(r"([wc])(\d+)(?:_e[\d.]+)?_mu([\d.]+)_tau([\d.]+)\.json$")


def runs_in(folder):
    """{web_mN: [(mu, tau, name, on_own_coating)]} of the finished runs, sorted by setting."""
    webs = {}
    for path in glob.glob(os.path.join(folder, "*_mu*_tau*.json")):
        match = RUN_NAME.fullmatch(os.path.basename(path))
        if match:
            web, mu, tau = int(match[2]), float(match[3]), float(match[4])
            webs.setdefault(web, []).append((mu, tau, match[0][:-5], match[1] == "w"))
    if not any(own for runs in webs.values() for *_, own in runs):
        sys.exit(f"error: {folder}: no run wWEB_muMU_tauTAU.json")
    return {web: sorted(runs) for web, runs in sorted(webs.items())}


def steady_band(folder, name):
    """sqrt(2) x the RMS of the crepe band over the first 70% of the creped profile (the steady
    part; the rest is the start)."""
    folds = curve(folder, name, "crepe_profile")["folds_um"]
    steady = folds[:int(0.7 * len(folds))]
    return math.sqrt(2.0 * sum(f * f for f in steady) / len(steady))


def print_table(folder, webs, t0, t1):
    print("| web, coating [J/m^2] | blade mu | draw tau [us] | delaminated, middle (steady) [um] "
          "| ff broken (middle) | dust mass | crepe [1/mm] | folds | band, first 70% [um] | "
          "gathered = curl x folds x in plane | blade MD load (steady) [N/m] | reel (steady) "
          "[N/m] | N^2 / (2 S toughness) | bulk at rest | energy error | wall [s] |")
    print("|" + "---|" * 16)
    for web, runs in webs.items():
        # The web's own coating first (by mu, then the longer draw first), then the others by name.
        for mu, tau, name, _ in sorted(runs, key=lambda r: (not r[3], r[0], -r[1], r[2])):
            s = stage(folder, name)
            d = s["details"]
            c = curve(folder, name, "creping_bond_loss")
            load = mean_over(c["time_us"], c["blade_force_N_per_m"], t0, t1)
            ratio = stored_energy_ratio(load, d["coating_toughness_J_per_m2"])
            print(f"| {web} mN, {d['coating_toughness_J_per_m2']:.1f} | {mu:g} | {tau:g} | "
                  f"{d['delaminated_length_um']:.0f} "
                  f"({median_over(c['time_us'], c['delaminated_length_um'], t0, t1):.0f}) | "
                  f"{d['bonds_broken_fraction']:.3f} | {d['dust_mass_fraction']:.3f} | "
                  f"{d['crepe_frequency_per_mm']:.2f} | {d['crepe_fold_count']:.0f} | "
                  f"{steady_band(folder, name):.1f} | {gathered_split(d)} | {load:.0f} | "
                  f"{mean_over(c['time_us'], c['reel_force_N_per_m'], t0, t1):.0f} | "
                  f"{ratio:.3g} | {d['bulk_gain']:.2f} | {d['energy_balance_error']:.3f} | "
                  f"{s['wall_s']:.0f} |")


def main(argv):
    if len(argv) not in (3, 5):
        sys.exit(__doc__)
    out, folder = argv[1], argv[2]
    t0, t1 = (float(argv[3]), float(argv[4])) if len(argv) == 5 else (100.0, 165.0)
    webs = runs_in(folder)
    rows = [("blade_force_N_per_m", "blade MD load [N/m]"),
            ("reel_force_N_per_m", "reel pull [N/m]"),
            ("delaminated_length_um", "front ahead of tip [um]")]
    fig, axes = plt.subplots(len(rows), len(webs), figsize=(6.5 * len(webs), 9), sharex=True,
                             squeeze=False)
    for column, (web, runs) in enumerate(webs.items()):
        for mu, tau, name, _ in (r for r in runs if r[3]):
            c = curve(folder, name, "creping_bond_loss")
            load = mean_over(c["time_us"], c["blade_force_N_per_m"], t0, t1)
            label = f"mu {mu:g}, tau {tau:g} us (blade {load:.0f} N/m)"
            for ax, (key, _) in zip(axes[:, column], rows):
                ax.plot(c["time_us"], c[key], lw=1, label=label)
        for ax, (_, ylabel) in zip(axes[:, column], rows):
            ax.axvspan(t0, t1, color="0.9", zorder=0)
            ax.set_ylabel(ylabel)
        axes[0, column].set_title(f"{web} mN web", fontsize=10)
        axes[0, column].legend(fontsize=7)
        axes[-1, column].set_xlabel("time [us]")
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print_table(folder, webs, t0, t1)


if __name__ == "__main__":
    main(sys.argv)
