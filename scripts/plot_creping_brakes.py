"""The brakes on the creped sheet over time (scripts/creping_study_friction.sh): one column per
web, rows for the blade's MD load, the reel's pull along the face (negative: it holds back)
and the distance of the peel front ahead of the tip, one line per setting of the blade's
friction mu and the reel's draw time tau. The grey band is the steady window WINDOW_US
(default 100-165 us: the tip over the second half of the 5 mm strip's middle), over which
the legend gives each run's mean blade load.
Usage: /usr/bin/python3 scripts/plot_creping_brakes.py OUT.png FOLDER [T0_US T1_US]
where FOLDER holds the runs wWEB_muMU_tauTAU.json with their curves."""
import glob
import os
import re
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

from creping_runs import curve

RUN_NAME = re.compile(r"w(\d+)_mu([\d.]+)_tau([\d.]+)\.json$")


def runs_in(folder):
    """{web_mN: [(mu, tau, name)]} of the study's finished runs, sorted by setting."""
    webs = {}
    for path in glob.glob(os.path.join(folder, "w*_mu*_tau*.json")):
        match = RUN_NAME.search(os.path.basename(path))
        if match:
            web, mu, tau = int(match[1]), float(match[2]), float(match[3])
            webs.setdefault(web, []).append((mu, tau, match[0][:-5]))
    if not webs:
        sys.exit(f"error: {folder}: no run wWEB_muMU_tauTAU.json")
    return {web: sorted(runs) for web, runs in sorted(webs.items())}


def mean_over(times, values, t0, t1):
    inside = [v for t, v in zip(times, values) if t0 <= t <= t1]
    return sum(inside) / len(inside) if inside else float("nan")


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
        for mu, tau, name in runs:
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


if __name__ == "__main__":
    main(sys.argv)
