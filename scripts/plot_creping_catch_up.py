"""Peel-ahead episodes on a long strip (docs/creping.md, "Peeled at the reel's speed"):
for each run, the blade's MD load, the reel's pull along the face and the distance of the peel
front ahead of the tip against the length of strip the blade has scraped, and a table of the
episodes in which the front ran more than THRESHOLD_UM ahead of the tip (where each began and
ended along the strip, how far ahead the front got) and of the catch-ups that ended them.
A web held to the blade keeps its front within about 100 um of the tip (docs/creping.md); an
episode that ends before the strip does is a catch-up, and a second episode after it is the
cycle of debond, buckle and catch-up that a crepe would repeat.
Usage: /usr/bin/python3 scripts/plot_creping_catch_up.py OUT.png FOLDER RUN... [--threshold UM]
           [--speed M_PER_S] [--run-in UM] [--fit-from MM] [--window FROM_MM TO_MM]...
where FOLDER holds RUN.json and RUN/curves of `fibrenet run --json --out FOLDER/RUN`; the Yankee
speed and the run-in (default 30 m/s and 500 um) must be the runs' own. Each --window adds a row
per run to a second table: the means of the blade's load and the reel's pull over that length
scraped, the front's median, the stored-energy ratio N^2 / (2 S toughness) of the mean load and
the middle's bond loss at the window's end."""
import argparse
import math
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

from creping_runs import (curve, gathered_split, mean_over, median_over, stage,
                          stored_energy_ratio)


def scraped_mm(times_us, speed, run_in_um):
    """Length of strip the blade has passed at each time [mm]: a constant acceleration over the
    run-in (creping.h, run_in_length), then the Yankee speed."""
    run_in = run_in_um * 1e-6
    t_run_in = 2.0 * run_in / speed if run_in > 0.0 else 0.0
    out = []
    for t_us in times_us:
        t = t_us * 1e-6
        if t < t_run_in:
            s = 0.5 * speed / t_run_in * t * t
        else:
            s = run_in + speed * (t - t_run_in)
        out.append(s * 1e3)
    return out


def slope(xs, ys):
    """Least-squares slope of ys on xs (nan for fewer than 3 points)."""
    n = len(xs)
    if n < 3:
        return float("nan")
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx if sxx > 0 else float("nan")


def episodes(position_mm, front_um, threshold_um, fit_from_mm=0.0):
    """[(start_mm, end_mm or None, largest front um, closing)]: end None where the episode lasted
    until the front, stopped at the strip's far end, came within the threshold of the tip as the
    blade neared that end (no catch-up); closing, the rate at which the gap to the tip shrank
    per length scraped, fitted from the largest front (or fit_from_mm scraped, if later) to the
    episode's end or to the front's reaching the far end. Past the last nonzero front the blade
    has passed the far end and the front, with no web left ahead, reads 0; those samples are
    left out."""
    last = max((k for k, f in enumerate(front_um) if f > 0.0), default=-1)
    if last < 0:
        return []
    far_end_mm = position_mm[last] + front_um[last] * 1e-3
    found, start = [], None

    def close(k_end, caught):
        peak = max(range(start, k_end), key=lambda k: front_um[k])
        fit = [k for k in range(peak, k_end)
               if position_mm[k] >= fit_from_mm
               and position_mm[k] + front_um[k] * 1e-3 < far_end_mm - 0.05]
        closing = -slope([position_mm[k] for k in fit], [front_um[k] * 1e-3 for k in fit])
        found.append((position_mm[start], position_mm[k_end] if caught else None,
                      front_um[peak], closing))

    for k in range(last + 1):
        if front_um[k] > threshold_um:
            if start is None:
                start = k
        elif start is not None:
            close(k, position_mm[k] + threshold_um * 1e-3 < far_end_mm)
            start = None
    if start is not None:
        close(last + 1, False)
    return found


def print_windows(folder, names, a):
    print()
    print("| run | scraped [mm] | blade MD load [N/m] | reel [N/m] | front ahead, median [um] | "
          "N^2 / (2 S toughness) | ff broken (middle), at the window's end |")
    print("|" + "---|" * 7)
    for name in names:
        d = stage(folder, name)["details"]
        c = curve(folder, name, "creping_bond_loss")
        x = scraped_mm(c["time_us"], a.speed, a.run_in)
        for lo, hi in a.window:
            inside = [k for k, xk in enumerate(x) if lo <= xk <= hi]
            if not inside:
                sys.exit(f"error: {name}: no sample scraped within {lo}-{hi} mm")
            load = mean_over(x, c["blade_force_N_per_m"], lo, hi)
            reel = mean_over(x, c["reel_force_N_per_m"], lo, hi)
            front = median_over(x, c["delaminated_length_um"], lo, hi)
            ratio = stored_energy_ratio(load, d["coating_toughness_J_per_m2"])
            print(f"| {name} | {lo:g}-{hi:g} | {load:.0f} | {reel:.0f} | {front:.0f} | "
                  f"{ratio:.3g} | {c['fibre_fibre_broken_fraction'][inside[-1]]:.3f} |")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out")
    parser.add_argument("folder")
    parser.add_argument("runs", nargs="+")
    parser.add_argument("--threshold", type=float, default=300.0, help="um (default 300)")
    parser.add_argument("--speed", type=float, default=30.0, help="Yankee speed, m/s (30)")
    parser.add_argument("--run-in", type=float, default=500.0, help="run-in length, um (500)")
    parser.add_argument("--window", type=float, nargs=2, action="append", default=[],
                        metavar=("FROM_MM", "TO_MM"), help="a length scraped to average over")
    parser.add_argument("--fit-from", type=float, default=0.0,
                        help="fit the gap's closing from this length scraped on, mm (0: from the "
                             "largest front)")
    a = parser.parse_args()
    out, folder, names, threshold = a.out, a.folder, a.runs, a.threshold
    rows = [("blade_force_N_per_m", "blade MD load [N/m]"),
            ("reel_force_N_per_m", "reel pull [N/m]"),
            ("delaminated_length_um", "front ahead of tip [um]")]
    fig, axes = plt.subplots(len(rows), 1, figsize=(10, 9), sharex=True)
    print("| run | coating [J/m^2] | episodes ahead of the tip by more than "
          f"{threshold:.0f} um: scraped from-to [mm] (largest front [um], gap closing per length "
          "scraped) | catch-ups | "
          "ff broken (middle) | dust mass | crepe [1/mm] | folds (profile [mm]) | "
          "gathered = curl x folds x in plane | energy error | wall [s] |")
    print("|" + "---|" * 10)
    for name in names:
        s = stage(folder, name)
        d = s["details"]
        c = curve(folder, name, "creping_bond_loss")
        x = scraped_mm(c["time_us"], a.speed, a.run_in)
        label = f"{name} ({d['coating_toughness_J_per_m2']:.1f} J/m^2)"
        for ax, (key, _) in zip(axes, rows):
            ax.plot(x, c[key], lw=1, label=label)
        found = episodes(x, c["delaminated_length_um"], threshold, a.fit_from)
        text = "; ".join(
            f"{begin:.2f}-{'end' if end is None else f'{end:.2f}'} ({largest:.0f}, "
            f"{'-' if math.isnan(closing) else f'{closing:.3f}'})"
            for begin, end, largest, closing in found) or "none"
        caught = sum(1 for _, end, _, _ in found if end is not None)
        print(f"| {name} | {d['coating_toughness_J_per_m2']:.1f} | {text} | {caught} | "
              f"{d['bonds_broken_fraction']:.3f} | {d['dust_mass_fraction']:.3f} | "
              f"{d['crepe_frequency_per_mm']:.2f} | {d['crepe_fold_count']:.0f} "
              f"({d['crepe_profile_length_um'] * 1e-3:.2f}) | {gathered_split(d)} | "
              f"{d['energy_balance_error']:.3f} | "
              f"{s['wall_s']:.0f} |")
    if a.window:
        print_windows(folder, names, a)
    for ax, (_, ylabel) in zip(axes, rows):
        ax.set_ylabel(ylabel)
    axes[2].axhline(threshold, color="grey", ls="--", lw=0.8)
    axes[0].legend(fontsize=8)
    axes[-1].set_xlabel("strip scraped by the blade [mm]")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main()
