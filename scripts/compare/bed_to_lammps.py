#!/usr/bin/env python3
"""Turns the fibre bed that `fibrenet bench --write-bed BED.csv` wrote into a LAMMPS data
file: spheres (atom_style hybrid sphere bond) with their velocities and spins, one molecule
per fibre, a harmonic bond between consecutive particles of a fibre.

Usage: bed_to_lammps.py BED.csv OUT.data
Prints the -var arguments of fibre_bed.lammps for this bed on stdout: the time step of the
bed, the harmonic bond of the fibre's axial stiffness E pi R^2 / (2R), and a Hookean contact
of the stiffness of fibrenet's van Wyk contact at first touch (C g / (2R), 28 N/m for the
bench's defaults C = 0.26 mN, g = 3.45; bed_csv.py) with the damping of the bed's
restitution.
"""
import math
import sys

from bed_csv import contact_stiffness, read_bed


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
    k_contact = contact_stiffness(header, radius)
    # Linear spring-dashpot with restitution e: damping ratio -ln e / sqrt(pi^2 + ln^2 e);
    # LAMMPS takes the damping per unit effective mass, 2 zeta sqrt(k / m_eff).
    log_e = math.log(header["restitution"])
    zeta = -log_e / math.sqrt(math.pi ** 2 + log_e ** 2)
    gamma_n = 2.0 * zeta * math.sqrt(k_contact / (0.5 * mass))
    print(f"-var data {sys.argv[2]} -var dt {header['dt']!r} -var kn {k_contact!r} -var gn {gamma_n!r} "
          f"-var kbond {0.5 * k_axial!r} -var r0 {spacing!r} -var g {header['gravity']!r} "
          f"-var mu {header['mu']!r}")


if __name__ == "__main__":
    main()
