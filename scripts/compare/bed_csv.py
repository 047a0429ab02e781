"""Reads the fibre bed that `fibrenet bench --write-bed BED.csv` wrote, for the scripts that
run it in other codes (bed_to_lammps.py, esys_fibre_bed.py).

read_bed(path) returns (header, rows): header holds dt [s], cell (xlo, xhi, ylo, yhi, zlo,
zhi) [m] and the bed's E, G [Pa], mu, restitution, gravity [m/s^2], contact_C [N],
contact_g and particles_per_fibre; rows are the particles in fibre order, dicts of floats
(fibre an int). contact_stiffness(header, radius) is the slope of fibrenet's van Wyk contact
C [(2R/d)^g - 1] at first touch, C g / 2R [N/m], the linear contact the other codes use.
"""
import csv
import re


def read_bed(path):
    with open(path) as f:
        lines = f.read().splitlines()
    comments = [line[1:].split() for line in lines if line.startswith("#")]
    header = {"dt": float(re.search(r"dt (\S+) s", " ".join(" ".join(c) for c in comments)).group(1))}
    for words in comments:
        if words and words[0] == "cell":
            header["cell"] = tuple(float(w) for w in words[1:7])
        elif words and words[0] == "E":
            header.update({words[k]: float(words[k + 1]) for k in range(0, len(words), 2)})
    rows = [{k: (int(v) if k == "fibre" else float(v)) for k, v in r.items()}
            for r in csv.DictReader(line for line in lines if not line.startswith("#"))]
    return header, rows


def contact_stiffness(header, radius):
    return header["contact_C"] * header["contact_g"] / (2.0 * radius)
