#!/usr/bin/env python3
"""Turns the fibre bed that `fibrenet bench --write-bed BED.csv` wrote into a LAMMPS data
file: spheres (atom_style hybrid sphere bond) with their velocities and spins, one molecule
per fibre, a harmonic bond between consecutive particles of a fibre.

Usage: bed_to_lammps.py BED.csv OUT.data
Prints the -var arguments of fibre_bed.lammps for this bed on stdout: the time step of the
bed, the harmonic bond of the fibre's axial stiffness E pi R^2 / (2R), and a Hookean contact
of the stiffness of fibrenet's van Wyk contact at first touch (C g / (2R), 28 N/m for the
bench's defaults C = 0.26 mN, g = 3.45) with the damping of the bed's restitution.
"""
import csv
import math
import sys

VAN_WYK_C = 0.26e-3  # [N], fibrenet's default contact law (van_wyk_normal.h)
VAN_WYK_G = 3.45


def read_bed(path):
    header = {}
    rows = []
    with open(path) as f:
        lines = [line for line in f]
    for line in lines:
        if not line.startswith("#"):
            continue
        words = line[1:].split()
        if words and words[0] == "cell":
            header["cell"] = [float(w) for w in words[1:7]]
        elif words and words[0] == "E":
            header.update({words[k]: float(words[k + 1]) for k in range(0, len(words), 2)})
    reader = csv.DictReader(line for line in lines if not line.startswith("#"))
    for r in reader:
        rows.append({k: (int(v) if k == "fibre" else float(v)) for k, v in r.items()})
    return header, rows


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    header, rows = read_bed(sys.argv[1])
    xlo, xhi, ylo, yhi, zlo, zhi = header["cell"]
    top = max(r["z"] + r["radius"] for r in rows)
    bonds = [(k, k + 1) for k in range(len(rows) - 1) if rows[k]["fibre"] == rows[k + 1]["fibre"]]
    with open(sys.argv[2], "w") as out:
        out.write("fibre bed from fibrenet bench --write-bed\n\n")
        out.write(f"{len(rows)} atoms\n1 atom types\n{len(bonds)} bonds\n1 bond types\n\n")
        out.write(f"{xlo!r} {xhi!r} xlo xhi\n{ylo!r} {yhi!r} ylo yhi\n")
        out.write(f"{min(zlo, 0.0)!r} {max(zhi, 2.0 * top)!r} zlo zhi\n\n")
        out.write("Atoms # hybrid sphere bond\n\n")
        for k, r in enumerate(rows, start=1):
            d = 2.0 * r["radius"]
            density = r["mass"] / (math.pi / 6.0 * d ** 3)
            out.write(f"{k} 1 {r['x']!r} {r['y']!r} {r['z']!r} {d!r} {density!r} {r['fibre'] + 1}\n")
        out.write("\nVelocities\n\n")
        for k, r in enumerate(rows, start=1):
            out.write(f"{k} {r['vx']!r} {r['vy']!r} {r['vz']!r} {r['wx']!r} {r['wy']!r} {r['wz']!r}\n")
        out.write("\nBonds\n\n")
        for n, (a, b) in enumerate(bonds, start=1):
            out.write(f"{n} 1 {a + 1} {b + 1}\n")
    radius, mass = rows[0]["radius"], rows[0]["mass"]
    spacing = 2.0 * radius
    k_axial = header["E"] * math.pi * radius ** 2 / spacing
    k_contact = VAN_WYK_C * VAN_WYK_G / spacing
    # Linear spring-dashpot with restitution e: damping ratio -ln e / sqrt(pi^2 + ln^2 e);
    # LAMMPS takes the damping per unit effective mass, 2 zeta sqrt(k / m_eff).
    log_e = math.log(header["restitution"])
    zeta = -log_e / math.sqrt(math.pi ** 2 + log_e ** 2)
    gamma_n = 2.0 * zeta * math.sqrt(k_contact / (0.5 * mass))
    with open(sys.argv[1]) as f:
        dt = float(f.readline().split("dt")[1].split()[0])
    print(f"-var data {sys.argv[2]} -var dt {dt!r} -var kn {k_contact!r} -var gn {gamma_n!r} "
          f"-var kbond {0.5 * k_axial!r} -var r0 {spacing!r} -var g {header['gravity']!r} "
          f"-var mu {header['mu']!r}")


if __name__ == "__main__":
    main()
