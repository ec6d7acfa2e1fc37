#!/usr/bin/python3
"""The gas between two sintering bodies: how many gas points stand in their neck.

Usage: /usr/bin/python3 scripts/gas_film.py OUT.png RUN_DIR[:STAGE] ...

For each run (a concurrent stage with gas and a neck, `pair` unless STAGE
is given) reads the DPD particles' and the gas points' H5MD frames
(particles_every > 0; a run without gas has none) and the neck history in results.h5. The two bodies
are the particles on either side of the pair's middle along its longest
axis in the first frame. Prints, per frame, the neck width and the film:
the gas points within 3 Å of the plane midway between the bodies' centres
of mass and inside the neck's circle (half its width from the line of
centres). Draws each run's last frame in a slab 3.8 Å thick through the
line of centres: particles orange, gas points blue.
"""

import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

FILM_HALF_THICKNESS = 3.0  # Å, about one gas spacing of a_cg/2 across the plane
SLAB_HALF_THICKNESS = 1.9  # Å, the drawing's slab


def frames(path):
    g = h5py.File(path, "r")["particles/all/position"]
    return g["time"][:], g["value"]


def bodies(x0):
    centred = x0 - x0.mean(axis=0)
    axis = np.linalg.svd(centred, full_matrices=False)[2][0]
    return centred @ axis < 0.0


def film_history(run, stage):
    times, dpd = frames(f"{run}/{stage}/dpd_particles.h5md")
    gas_file = f"{run}/{stage}/mpm_particles.h5md"
    gas = frames(gas_file)[1] if os.path.isfile(gas_file) else None  # a run without gas
    with h5py.File(f"{run}/results.h5", "r") as f:
        neck = next(v for k, v in f[stage].items() if k.startswith("neck_") and isinstance(v, h5py.Group))
        neck_t, neck_w = neck["time"][:], neck["width"][:]
    first = bodies(dpd[0])
    rows = []
    for k, t in enumerate(times):
        x = dpd[k]
        gx = gas[k] if gas is not None else np.zeros((0, 3))
        a, b = x[first].mean(axis=0), x[~first].mean(axis=0)
        axis = (b - a) / np.linalg.norm(b - a)
        rel = gx - 0.5 * (a + b)
        s = rel @ axis
        r = np.linalg.norm(rel - np.outer(s, axis), axis=1)
        near = np.abs(neck_t - t) <= 1.0
        width = float(np.mean(neck_w[near])) if near.any() else 0.0
        film = int(np.sum((np.abs(s) < FILM_HALF_THICKNESS) & (r < 0.5 * width)))
        rows.append((float(t), width, film, 0.5 * (a + b), axis, x, gx))
    return rows


def main(argv):
    if len(argv) < 3:
        print(__doc__)
        return 1
    runs = [(a.split(":") + ["pair"])[:2] for a in argv[2:]]
    fig, axes = plt.subplots(1, len(runs), figsize=(4.0 * len(runs), 4.2), squeeze=False)
    for ax, (run, stage) in zip(axes[0], runs):
        rows = film_history(run, stage)
        print(run + ": " + "; ".join(f"{t:.1f} ps neck {w:.1f} Å film {n}" for t, w, n, *_ in rows))
        t, width, film, mid, axis, x, gx = rows[-1]
        # The slab through the line of centres, drawn in the plane of that
        # line and the axis across it that is least along it.
        across = np.eye(3)[int(np.argmin(np.abs(axis)))]
        across = across - (across @ axis) * axis
        across /= np.linalg.norm(across)
        normal = np.cross(axis, across)
        for pts, colour, size in ((x, "tab:orange", 24), (gx, "tab:blue", 5)):
            rel = pts - mid
            m = np.abs(rel @ normal) < SLAB_HALF_THICKNESS
            ax.scatter(rel[m] @ axis, rel[m] @ across, s=size, c=colour)
        ax.set_xlim(-30, 30)
        ax.set_ylim(-30, 30)
        ax.set_aspect("equal")
        ax.set_xlabel("along the line of centres (Å)")
        ax.set_title(f"{run.rstrip('/').split('/')[-1]}, {t:.0f} ps: neck {width:.1f} Å, film {film}",
                     fontsize=9)
    fig.tight_layout()
    fig.savefig(argv[1], dpi=90)
    print(argv[1])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
