#!/usr/bin/python3
"""scripts/gas_film.py counts the gas points planted in a pair's contact.

    gas_film_count.py ROOT

A run directory is written by hand: two blocks of particles 9 Å apart
along a line of centres turned off the axes (the pair longest along it), gas points on a square
lattice of 3.615 Å in the plane midway between them, and the neck history
in results.h5. Frame 0 has no film; frame 1 has a layer in the neck's
circle, the same layer's continuation outside it, a second layer 5 Å off
the plane and gas beyond the blocks. The film of frame 1 must be exactly
the planted points within 3 Å of the mid-plane and half the neck width of
the line of centres, counted here from how they were planted; the PNG
must be written.
"""

import os
import re
import subprocess
import sys

import h5py
import numpy as np

ROOT = sys.argv[1]
NECK = 30.0  # Å, the neck width the run reports at both frames' times
SPACING = 3.615


def frame_file(path, frames):
    with h5py.File(path, "w") as f:
        g = f.create_group("particles/all/position")
        g["time"] = np.array([0.0, 5.0])
        g["step"] = np.array([0, 500])
        g["value"] = np.stack(frames)


def rotation():
    # The line of centres along (2, 1, 0.5)/|.|; the other two axes complete it.
    axis = np.array([2.0, 1.0, 0.5])
    axis /= np.linalg.norm(axis)
    other = np.cross(axis, [0.0, 0.0, 1.0])
    other /= np.linalg.norm(other)
    return np.stack([axis, other, np.cross(axis, other)])  # rows: new x, y, z


def main():
    rot = rotation()
    centre = np.array([100.0, 90.0, 80.0])
    grid = np.arange(-8, 9) * 3.615
    # Two blocks of 7.23 Å simple cubic sites, faces 9 Å apart across the
    # plane x' = 0 (coordinates along the line of centres, then across),
    # the pair longest along that line, as the script takes it.
    block = np.array([(x, y, z) for x in np.arange(7) * 7.23 for y in grid[::2] for z in grid[::2]])
    left = block.copy()
    left[:, 0] = -4.5 - left[:, 0]
    right = block.copy()
    right[:, 0] += 4.5
    particles = np.vstack([left, right])
    # Gas, in the same turned frame: the mid-plane layer, a layer 5 Å off
    # it, and points beyond the blocks.
    layer = np.array([(0.0, y, z) for y in grid for z in grid])
    off_plane = layer + [5.0, 0.0, 0.0]
    beyond = np.array([(x, 0.0, 0.0) for x in (-40.0, 40.0)])
    gas1 = np.vstack([layer, off_plane, beyond])
    planted = int(np.sum(np.hypot(layer[:, 1], layer[:, 2]) < 0.5 * NECK))
    gas0 = np.vstack([off_plane, off_plane + [-10.0, 0.0, 0.0], beyond])

    def place(local):
        return local @ rot + centre

    run = "run"
    os.makedirs(f"{run}/pair", exist_ok=True)
    frame_file(f"{run}/pair/dpd_particles.h5md", [place(particles)] * 2)
    frame_file(f"{run}/pair/mpm_particles.h5md", [place(gas0), place(gas1)])
    with h5py.File(f"{run}/results.h5", "w") as f:
        neck = f.create_group("pair/neck_pair")
        neck["time"] = np.arange(0.0, 5.01, 0.2)
        neck["width"] = np.full(26, NECK)
        f["pair/neck_final_pair"] = NECK
    out = subprocess.run(
        ["/usr/bin/python3", f"{ROOT}/scripts/gas_film.py", "film.png", run],
        capture_output=True, text=True, check=False)
    print(out.stdout + out.stderr)
    films = [int(n) for n in re.findall(r"film (\d+)", out.stdout)]
    bad = []
    if out.returncode != 0:
        bad.append(f"gas_film.py exited {out.returncode}")
    if films != [0, planted]:
        bad.append(f"films {films}, planted [0, {planted}]")
    if not os.path.isfile("film.png"):
        bad.append("film.png not written")
    print(f"planted {planted} gas points in the neck's circle; counted {films}")
    for b in bad:
        print("FAIL:", b)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
