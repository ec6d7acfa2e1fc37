#!/usr/bin/python3
"""`./pbms export` writes extended XYZ that ASE reads back as the H5MD values.

    readers_export.py ROOT RUN_DIR

OVITO does not read H5MD; `./pbms export RUN_DIR` writes `<name>.xyz` beside
every `<name>.h5md`. ASE (python3-ase) reads each with ase.io.read, and
every frame must give back the H5MD file's values exactly (17 significant
digits are written): ids, species (the `type` column, OVITO's Particle
Type), positions, velocities (`velo`, OVITO's Velocity), forces in eV/Å
(as in the H5MD file), internal energies, the
box, periodicity, time and step, and the solver on the comment line.
"""

import glob
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np
from checklist import Checklist
from ase.io import read


check = Checklist()


def check_file(h5md, solver):
    xyz = os.path.splitext(h5md)[0] + ".xyz"
    name = os.path.relpath(xyz)
    if not os.path.isfile(xyz):
        check(False, f"{name} written")
        return
    frames = read(xyz, index=":", format="extxyz")
    with h5py.File(h5md, "r") as f:
        g = f["particles/all"]
        x = g["position/value"][()]
        v = g["velocity/value"][()]
        force = g["force/value"][()] if "force" in g else None
        energy = g["internal_energy/value"][()] if "internal_energy" in g else None
        edges = g["box/edges/value"][()]
        periodic = [b.decode() == "periodic" for b in g["box"].attrs["boundary"]]
        time = g["position/time"][()]
        step = g["position/step"][()]
        ids = g["id"][()]
        species = g["species"][()]
        metal = "unit" in g["position/value"].attrs
    check(len(frames) == x.shape[0], f"{name}: {len(frames)} frames of {x.shape[0]}")
    bad = []
    for k, atoms in enumerate(frames):
        box = edges[k] if edges[k].ndim == 2 else np.diag(edges[k])
        if not np.array_equal(atoms.positions, x[k]):
            bad.append(f"positions of frame {k}")
        if not np.array_equal(atoms.arrays["velo"], v[k]):
            bad.append(f"velocities of frame {k}")
        if not np.array_equal(atoms.arrays["id"], ids):
            bad.append(f"ids of frame {k}")
        if not np.array_equal(atoms.arrays["type"], species):
            bad.append(f"types of frame {k}")
        if force is not None:
            want = force[k]
            if not np.array_equal(atoms.get_forces(), want):
                bad.append(f"forces of frame {k}")
        if energy is not None and not np.array_equal(atoms.arrays["internal_energy"], energy[k]):
            bad.append(f"internal energies of frame {k}")
        if not np.array_equal(atoms.cell.array, box):
            bad.append(f"cell of frame {k}")
        if list(atoms.pbc) != periodic:
            bad.append(f"pbc of frame {k}: {atoms.pbc}")
        info = atoms.info
        if info.get("Time") != time[k] or info.get("step") != step[k]:
            bad.append(f"time/step of frame {k}: {info.get('Time')}/{info.get('step')}")
        if info.get("solver") != solver or info.get("units") != ("metal" if metal else "consistent"):
            bad.append(f"solver/units of frame {k}: {info.get('solver')}/{info.get('units')}")
    cols = "ids, types, positions, velocities" + (", forces" if force is not None else "") + \
        (", internal energies" if energy is not None else "") + ", cell, pbc, time, step, solver"
    check(not bad, f"{name}: {len(frames)} frames x {x.shape[1]} particles: {cols} equal to the "
          "H5MD file's" + ("" if not bad else ": " + "; ".join(bad[:5])))


def main():
    root, run = sys.argv[1], sys.argv[2]
    for stale in glob.glob(os.path.join(run, "**", "*.xyz"), recursive=True):
        os.remove(stale)
    out = subprocess.run([os.path.join(root, "pbms"), "export", run], capture_output=True,
                         text=True)
    print(out.stdout + out.stderr, end="")
    check(out.returncode == 0, f"./pbms export exited {out.returncode}")
    files = sorted(glob.glob(os.path.join(run, "**", "*.h5md"), recursive=True))
    solvers = {"md": "md", "md_tension": "md", "dpd": "dpd", "mpm_consistent": "mpm",
               "mpm_metal": "mpm"}
    check(len(files) >= 4, f"{len(files)} H5MD files to export")
    for path in files:
        # A concurrent stage has one file per part: dpd_particles, mpm_particles.
        part = os.path.basename(path).split("_")[0]
        solver = part if part in ("dpd", "mpm") else solvers.get(
            os.path.basename(os.path.dirname(path)), "?")
        check_file(path, solver)
    with tempfile.TemporaryDirectory() as nothing:
        out = subprocess.run([os.path.join(root, "pbms"), "export", nothing], capture_output=True,
                             text=True)
    check(out.returncode == 1 and "no H5MD file" in out.stderr,
          f"a directory without H5MD files is refused: {out.stderr.strip()}")
    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
