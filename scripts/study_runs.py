"""The runs of a study folder, as the study scripts write them: NAME_sSEED.json, one
`fibrenet run --json` document per run. Shared by the plotting scripts of the fidelity studies."""
import glob
import json
import os
import sys


def load(folder, name):
    """{seed: document} of the runs NAME_s*.json in folder; exits with the path on a bad file."""
    runs = {}
    for path in sorted(glob.glob(os.path.join(folder, name + "_s*.json"))):
        seed = path.rsplit("_s", 1)[1].removesuffix(".json")
        try:
            with open(path) as f:
                runs[seed] = json.load(f)
        except (OSError, json.JSONDecodeError) as e:
            sys.exit(f"error: {path}: {e}")
    return runs
