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
