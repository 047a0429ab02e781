"""The lift-off criterion of docs/creping.md on both delamination studies: the blade's peak
load N compresses the web ahead of it, which then stores N^2 / (2 S) per m^2 (S = E h, the
web's MD tensile stiffness); where that exceeds the coating's toughness, buckling the web off
the Yankee releases more than the delamination costs (the steady state of buckle-driven
delamination of a thin film). Plots the delaminated length and the bonds broken against
N^2 / (2 S toughness) and prints the generic tissue's table.
Usage: /usr/bin/python3 scripts/plot_delamination_criterion.py STUDY_OUT GENERIC_OUT FIGURE_DIR
  (STUDY_OUT from scripts/delamination_study.sh, GENERIC_OUT from scripts/delamination_generic.sh)"""
import glob
import json
import os
import sys
import tomllib

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

study_out, generic_out, figures = sys.argv[1:4]


def load(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        sys.exit(f"error: {path}: {e}")


def stage(run, name):
    return next(s for s in run["stages"] if s["name"] == name)


def strip_length_um(scene):
    with open(scene, "rb") as f:
        return tomllib.load(f)["cell"]["size_x_mm"] * 1e3


def stiffness(folder, name):
    """The web's MD tensile stiffness S = E h [N/m] from its tensile run NAME.json."""
    return load(os.path.join(folder, name + ".json"))["metrics"]["tensile_modulus_N_per_m"]


def runs(folder, pattern, web_of):
    """(name, creping details) of the creping runs NAME.json matching pattern, the details with
    the web's S and the ratio N_peak^2 / (2 S toughness) ("drive") added."""
    out = []
    for path in sorted(glob.glob(os.path.join(folder, pattern + ".json"))):
        name = os.path.basename(path).removesuffix(".json")
        d = stage(load(path), "creping")["details"]
        d["S"] = stiffness(folder, web_of(name))
        d["drive"] = d["peak_blade_force_N_per_m"] ** 2 / (
            2.0 * d["S"] * d["coating_toughness_J_per_m2"])
        out.append((name, d))
    return out


study_strip = strip_length_um("campaigns/scenes/study-creping.toml")
generic_strip = strip_length_um("campaigns/scenes/generic-tissue-creped.toml")
study = runs(study_out, "v*_e*_f*", lambda name: "t_base")
generic = runs(generic_out, "p89*_e*", lambda name: "t_" + name.split("_e")[0])


def coating(name):
    """The coating modulus [MPa] of a generic run WEB_eMODULUS[_rRUN_IN]."""
    return float(name.split("_e")[1].split("_r")[0])


def run_in(name):
    return name.split("_r")[1] if "_r" in name else "0"


def strong(name):
    return name.startswith("p89s")


print("| web (ff bonds' F_s0) | run-in [um] | coating [MPa] | toughness [J/m^2] | "
      "peak blade force [N/m] | N^2 / (2 S toughness) | delaminated [um] | (largest) | "
      "ff broken (middle) | dust mass | bulk gain | crepe freq [1/mm] | energy error | "
      "past the blade | closest contact |")
print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
for name, d in sorted(generic, key=lambda r: (int(run_in(r[0])), strong(r[0]), -coating(r[0]))):
    print(f"| {'25 mN' if strong(name) else '5 mN'} | {run_in(name)} | {coating(name):g} | "
          f"{d['coating_toughness_J_per_m2']:.1f} | {d['peak_blade_force_N_per_m']:.0f} | "
          f"{d['drive']:.2f} | {d['delaminated_length_um']:.0f} | "
          f"{d['delaminated_length_max_um']:.0f} | {d['bonds_broken_fraction']:.3f} | "
          f"{d['dust_mass_fraction']:.3f} | {d['bulk_gain']:.2f} | "
          f"{d['crepe_frequency_per_mm']:.2f} | {d['energy_balance_error']:.4f} | "
          f"{d['particles_past_blade']:.0f} | {d['min_contact_ratio']:.4f} |")
for label, rs in (("study sheet", study), ("generic tissue", generic)):
    print(f"{label}: S = {sorted({round(d['S']) for _, d in rs})} N/m")


def generic_series(strong_web, with_run_in):
    return [d for n, d in generic if strong(n) == strong_web and (run_in(n) != "0") == with_run_in]


series = [("study sheet, 15 m/s", [d for n, d in study if n.startswith("v15")], study_strip, "v",
           "tab:green", True),
          ("study sheet, 30 m/s", [d for n, d in study if n.startswith("v30")], study_strip, "o",
           "tab:blue", True),
          ("study sheet, 60 m/s", [d for n, d in study if n.startswith("v60")], study_strip, "^",
           "tab:purple", True),
          ("generic 89 um, F_s0 5 mN, rammed", generic_series(False, False), generic_strip, "s",
           "tab:red", True),
          ("generic 89 um, F_s0 25 mN, rammed", generic_series(True, False), generic_strip, "D",
           "tab:orange", True),
          ("generic 89 um, F_s0 5 mN, run-in 500 um", generic_series(False, True), generic_strip,
           "s", "tab:red", False),
          ("generic 89 um, F_s0 25 mN, run-in 500 um", generic_series(True, True), generic_strip,
           "D", "tab:orange", False)]
fig, axes = plt.subplots(1, 2, figsize=(12, 4.6))
for label, ds, strip, marker, colour, filled in series:
    if not ds:
        continue
    x = [d["drive"] for d in ds]
    style = dict(marker=marker, edgecolors=colour, facecolors=colour if filled else "none")
    axes[0].scatter(x, [d["delaminated_length_um"] / strip for d in ds], label=label, **style)
    axes[1].scatter(x, [d["bonds_broken_fraction"] for d in ds], **style)
for ax in axes:
    ax.set_xscale("log")
    ax.axvline(1.0, color="grey", lw=0.8, ls="--")
    ax.set_xlabel("N_peak^2 / (2 S toughness)\n(web's stored energy at the peak blade load / "
                  "coating's toughness)")
axes[0].set_yscale("log")
axes[0].set_ylabel("delaminated length / strip length\n(0.5: the whole web off)")
axes[1].set_ylabel("fibre-fibre bonds broken (middle)")
axes[0].legend(fontsize=7)
fig.tight_layout()
fig.savefig(os.path.join(figures, "delamination_criterion.png"), dpi=110)
