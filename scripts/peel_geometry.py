"""Peel geometry of a creping run, from its impact frames (`creping.impact_frames = N`): per
frame, the peel front (the 99.5th percentile along MD of the glue sites that still hold, the
blade coming from +x), the delaminated length of the bond-loss curve at that time (front to
blade tip), and the angle at which the web rises from the Yankee: a line x = a + b z fitted
to the sheet particles between heights Z_LO and Z_HI that lie between 200 um ahead of the
front and 100 um short of the tip; angle = atan2(1, b) from the Yankee on the tip's side (90:
straight up; more: leaning back over the glued web). Then the front's speed and the reel's
mean pull between the fitted frames in the steady window FROM:TO (microseconds), for the
peel balance of docs/creping.md ("The peel angle at the running front").
Usage: /usr/bin/python3 scripts/peel_geometry.py RUN_DIR [Z_LO_UM Z_HI_UM [FROM:TO]]"""
import csv
import glob
import sys

import h5py
import numpy as np

run = sys.argv[1]
z_lo, z_hi = (float(sys.argv[2]), float(sys.argv[3])) if len(sys.argv) > 3 else (200.0, 1000.0)
steady = [float(v) for v in sys.argv[4].split(":")] if len(sys.argv) > 4 else [0.0, 1e300]
rows = list(csv.DictReader(open(f"{run}/curves/creping_bond_loss.csv")))
curve_t = np.array([float(r["time_us"]) for r in rows])
curve_delam = np.array([float(r["delaminated_length_um"]) for r in rows])
curve_reel = np.array([float(r["reel_force_N_per_m"]) for r in rows])
frames = sorted(glob.glob(f"{run}/snapshots/creping_frame_*.h5"))
t0 = h5py.File(frames[0]).attrs["time"] * 1e6  # the first frame is the stage's first step
fronts = []
for path in frames:
    f = h5py.File(path)
    x = f["particles/x"][:] * 1e6
    fibre = f["particles/fibre"][:]
    kind, broken, ij = f["bonds/kind"][:], f["bonds/broken"][:], f["bonds/ij"][:]
    t = f.attrs["time"] * 1e6 - t0
    site = np.where(fibre[ij[:, 0]] >= 0, ij[:, 0], ij[:, 1])  # the sheet's end of a glue bond
    held = site[(kind == 2) & (broken == 0)]
    if len(held) == 0:
        print(f"{t:6.1f} us: no glue holds")
        continue
    front = np.percentile(x[held, 0], 99.5)
    delam = np.interp(t, curve_t, curve_delam)
    web = ((fibre >= 0) & (x[:, 0] > front - 200) & (x[:, 0] < front + delam - 100)
           & (x[:, 2] > z_lo) & (x[:, 2] < z_hi))
    if delam < 300 or web.sum() < 30:
        print(f"{t:6.1f} us: front x = {front:5.0f} um, delaminated {delam:5.0f} um")
        continue
    b, _ = np.polyfit(x[web, 2], x[web, 0], 1)
    angle = np.degrees(np.arctan2(1.0, b))
    print(f"{t:6.1f} us: front x = {front:5.0f} um, delaminated {delam:5.0f} um, web at "
          f"{angle:5.1f} deg ({web.sum()} particles at z {z_lo:.0f}-{z_hi:.0f} um, median "
          f"{np.median(x[web, 0]) - front:+.0f} um from the front)")
    if steady[0] <= t <= steady[1]:
        fronts.append((t, front))
if len(fronts) >= 2:
    (ta, xa), (tb, xb) = fronts[0], fronts[-1]
    window = (curve_t >= ta) & (curve_t <= tb)
    print(f"{ta:.1f}-{tb:.1f} us: front speed {(xa - xb) / (tb - ta):.1f} m/s, reel pull "
          f"{curve_reel[window].mean():.1f} N/m (sd {curve_reel[window].std():.1f}, "
          f"{window.sum()} samples)")
