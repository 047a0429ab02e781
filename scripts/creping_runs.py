"""The creping runs of a study folder, as the creping study scripts write them: NAME.json, one
`fibrenet run --json` document per run, and NAME/curves/*.csv. Shared by the creping studies'
plotting scripts."""
import csv
import json
import os
import sys


def stage(folder, name):
    """The creping stage of run NAME (details, steps, wall_s, warnings); exits with the path on
    a bad file."""
    path = os.path.join(folder, name + ".json")
    try:
        with open(path) as f:
            run = json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        sys.exit(f"error: {path}: {e}")
    return next(s for s in run["stages"] if s["name"] == "creping")


def details(folder, name):
    """The creping stage's details of run NAME."""
    return stage(folder, name)["details"]


def curve(folder, name, curve_name):
    """{column: values} of run NAME's curve NAME/curves/CURVE_NAME.csv."""
    with open(os.path.join(folder, name, "curves", curve_name + ".csv")) as f:
        rows = list(csv.DictReader(f))
    return {key: [float(r[key]) for r in rows] for key in rows[0]}


# The 25 and 100 mN generic webs' MD tensile stiffness S = E h [N/m], measured on their 2.5 mm
# strips' pressings (docs/creping.md, "The generic tissue: a lift-off criterion").
WEB_TENSILE_STIFFNESS_N_PER_M = 160410.0


def stored_energy_ratio(load, toughness, stiffness=WEB_TENSILE_STIFFNESS_N_PER_M):
    """N^2 / (2 S G): the strain energy an MD load N [N/m] stores per area of the glued web ahead
    of the tip, over the coating's toughness G [J/m^2] (the lift-off criterion, docs/creping.md)."""
    return load ** 2 / (2.0 * stiffness * toughness)


def gathered_split(d):
    """'gathered = curl x folds x in plane' of a creping run's details, as the tables print it."""
    return (f"{d['crepe_gathered_ratio']:.3f} = {d['crepe_curl_ratio']:.3f} x "
            f"{d['crepe_fold_ratio']:.3f} x {d['crepe_in_plane_ratio']:.3f}")


def mean_over(xs, values, lo, hi):
    """Mean of the values whose abscissa lies in [lo, hi] (nan if none)."""
    inside = [v for x, v in zip(xs, values) if lo <= x <= hi]
    return sum(inside) / len(inside) if inside else float("nan")


def median_over(xs, values, lo, hi):
    """Median (the upper one of an even count) of the values whose abscissa lies in [lo, hi]."""
    inside = sorted(v for x, v in zip(xs, values) if lo <= x <= hi)
    return inside[len(inside) // 2] if inside else float("nan")
