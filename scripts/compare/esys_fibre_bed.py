"""Times ESyS-Particle 2.3 on the fibre bed of `fibrenet bench --write-bed BED.csv`
(docs/performance.md): the same particles (position, radius, mass, velocity, spin), time
step, gravity and floor, with
  bonds     RotBondPrms (Wang et al. 2006 rotational bond, 6 degrees of freedom) between
            consecutive particles of a fibre, the spring constants of fibrenet's beam bond
            (BeamBondParams::FromBeam: k_n = EA/L, k_s = 12EI/L^3, k_t = GJ/L, k_b = EI/L,
            L = 2R; Poisson's ratio E/(2G) - 1 enters through G), unbreakable;
  contacts  RotFrictionPrms: linear normal spring k_n = C g / 2R (28 N/m, the tangent of
            fibrenet's van Wyk law C [(2R/d)^g - 1] at first touch), shear spring k_n,
            Coulomb friction mu; no contact damping; excluded between bonded pairs;
  floor     a wall at z = 0 with a linear elastic contact of the same k_n (ESyS has no
            frictional planar wall);
  gravity   GravityPrms along -z.
ESyS-Particle implements circular boundaries by exchanging particles between workers, so
they need 2 workers along each circular axis. With one worker (`-np 2`: the master and one
computing process) the bed is therefore not periodic: the lateral boundaries are open and
the bonds and contacts across the cell edges are left out (in the 10 000-particle bed,
177 of 9 500 bonds and 4 of 730 touching pairs; unwrapping the fibres instead would keep
the bonds but lose 126 of the touching pairs). With `-np 5` (4 workers, 2 x 2) the cell is
periodic in x and y and nothing is left out.
Runs 20 untimed steps, then times STEPS steps of the step loop; writes no files.

Usage: mpirun --allow-run-as-root -np 2 esysparticle scripts/compare/esys_fibre_bed.py BED.csv STEPS
"""
import math
import os
import sys
import time

from esys.lsm import (GravityPrms, LsmMpi, NRotElasticWallPrms, RotBondPrms, RotFrictionPrms,
                      RotSphere)
from esys.lsm.geometry import TaggedIdConnection
from esys.lsm.util import BoundingBox, Vec3

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bed_csv import contact_stiffness, read_bed  # noqa: E402 (after the path is set)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    prm, rows = read_bed(sys.argv[1])
    xlo, xhi, ylo, yhi, zlo, zhi = prm["cell"]
    steps = int(sys.argv[2])
    n = len(rows)
    R = rows[0]["radius"]
    E, G, L = prm["E"], prm["G"], 2.0 * R
    bonded = [k for k in range(n - 1) if rows[k]["fibre"] == rows[k + 1]["fibre"]]

    workers = int(os.environ.get("OMPI_COMM_WORLD_SIZE", "2")) - 1
    periodic = workers >= 4
    if periodic:  # 2 x (workers / 2) sub-domains, circular in x and y
        dims, lo, hi = [2, workers // 2, 1], [xlo, ylo], [xhi, yhi]
    else:  # one worker: open lateral boundaries a few diameters outside the cell
        dims, lo, hi = [1, 1, 1], [xlo - 4 * L, ylo - 4 * L], [xhi + 4 * L, yhi + 4 * L]
        bonded = [k for k in bonded if abs(rows[k]["x"] - rows[k + 1]["x"]) < 2 * L
                  and abs(rows[k]["y"] - rows[k + 1]["y"]) < 2 * L]
    top = max(max(r["z"] for r in rows) + R, zhi)

    sim = LsmMpi(numWorkerProcesses=workers, mpiDimList=dims)
    # Grid cells of about 2.5 diameters that tile the x extent exactly (needed when circular).
    grid = (hi[0] - lo[0]) / math.floor((hi[0] - lo[0]) / (2.5 * L))
    sim.initNeighbourSearch(particleType="RotSphere", gridSpacing=grid, verletDist=0.1 * L)
    sim.setSpatialDomain(BoundingBox(Vec3(lo[0], lo[1], -2 * L), Vec3(hi[0], hi[1], top + 4 * L)),
                         circDimList=[periodic, periodic, False])
    sim.setTimeStepSize(prm["dt"])
    sim.setNumTimeSteps(20 + steps)

    # RotSphere takes the mass directly (inertia 0.4 m R^2, as in fibrenet); the velocities
    # set on it are kept by createParticles.
    spheres = []
    for i, r in enumerate(rows):
        s = RotSphere(id=i, posn=Vec3(r["x"], r["y"], r["z"]), radius=r["radius"], mass=r["mass"])
        s.setLinearVelocity(Vec3(r["vx"], r["vy"], r["vz"]))
        s.setAngularVelocity(Vec3(r["wx"], r["wy"], r["wz"]))
        spheres.append(s)
    sim.createParticles(spheres)
    sim.createConnections([TaggedIdConnection(k, k + 1, 0) for k in bonded])

    A, I = math.pi * R ** 2, math.pi * R ** 4 / 4.0
    never = 1e30  # breaking forces and moments: the bonds never break
    sim.createInteractionGroup(RotBondPrms(
        name="bonds", normalK=E * A / L, shearK=12.0 * E * I / L ** 3, torsionK=G * 2.0 * I / L,
        bendingK=E * I / L, normalBrkForce=never, shearBrkForce=never, torsionBrkForce=never,
        bendingBrkForce=never, tag=0, scaling=False))
    kn = contact_stiffness(prm, R)
    # scaling=False: normalK and shearK are spring constants [N/m]. rigid=False: the
    # rigid-rotation variant has an absolute slip threshold (1e-8) meant for unit-size models.
    sim.createInteractionGroup(RotFrictionPrms(
        name="friction", normalK=kn, dynamicMu=prm["mu"], staticMu=prm["mu"], shearK=kn,
        scaling=False, rigid=False))
    sim.createExclusion(interactionName1="bonds", interactionName2="friction")
    sim.createInteractionGroup(GravityPrms(name="gravity", acceleration=Vec3(0, 0, -prm["gravity"])))
    sim.createWall(name="floor", posn=Vec3(0, 0, 0), normal=Vec3(0, 0, 1))
    # The elastic wall scales normalK by pi R in 3D.
    sim.createInteractionGroup(NRotElasticWallPrms(name="floor_contact", wallName="floor",
                                                   normalK=kn / (math.pi * R)))

    for _ in range(20):
        sim.runTimeStep()
    t0 = time.perf_counter()
    for _ in range(steps):
        sim.runTimeStep()
    wall = time.perf_counter() - t0

    # Sanity check outside the timing: nobody left the domain, nothing blew up.
    final = sim.getParticleList()
    vmax = max(p.getVelocity().norm() for p in final)
    vmax0 = max(math.sqrt(r["vx"] ** 2 + r["vy"] ** 2 + r["vz"] ** 2) for r in rows)
    print(f"esys-particle: {n} particles, {steps} steps, {wall:.3f} s, "
          f"{n * steps / wall:.4g} particle-steps/s (ESyS-Particle {sim.getLsmVersion()}; "
          f"{workers} worker(s), {len(bonded)} bonds, "
          f"{'periodic' if periodic else 'open lateral boundaries'}; {len(final)} particles "
          f"left, max speed {vmax:.3g} m/s, {vmax0:.3g} at the start)", flush=True)
    sim.exit()


if __name__ == "__main__":
    main()
