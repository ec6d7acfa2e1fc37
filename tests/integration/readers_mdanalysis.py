#!/usr/bin/python3
"""MDAnalysis opens every H5MD file of a run and reads what PBMS wrote.

    readers_mdanalysis.py ROOT RUN_DIR

RUN_DIR is the run of tests/integration/configs/readers.yaml (md_driver,
dpd_driver and mpm_driver trajectories, in metal and in consistent units).
For every frame of every `*.h5md` file, MDAnalysis' positions, velocities,
forces, box, time and step must equal h5py's reads of the same file after
rounding to float32 (MDAnalysis keeps coordinates in float32): exactly for
the arrays, to float32 rounding for the box and time.

The topology comes from the file's own particle count (Universe.empty):
MDAnalysis' topology-less path looks for a `particles/trajectory` group,
while H5MD writers, PBMS and LAMMPS among them, name theirs `all`.
Files in metal units open with MDAnalysis' default convert_units=True and
must report Angstrom, ps, Angstrom/ps and kJ/(mol*Angstrom); files in
consistent units carry no unit attributes, so MDAnalysis refuses them with
its defaults (checked) and opens them with convert_units=False.
"""

import glob
import os
import sys
import warnings

import h5py
import numpy as np
from checklist import Checklist

warnings.filterwarnings("ignore", category=DeprecationWarning)
import MDAnalysis as mda  # noqa: E402

check = Checklist()
g_force_unit = {}  # path -> the force pbms_unit attribute


def same32(a, b):
    """a (MDAnalysis, float32) equals b (the file's float64) rounded to float32."""
    return np.array_equal(np.asarray(a, dtype=np.float32), np.asarray(b).astype(np.float32))


def check_file(path):
    with h5py.File(path, "r") as f:
        g = f["particles/all"]
        x = g["position/value"][()]
        v = g["velocity/value"][()] if "velocity" in g else None
        force = g["force/value"][()] if "force" in g else None
        if force is not None:
            g_force_unit[path] = g["force/value"].attrs.get("pbms_unit")
        edges = g["box/edges/value"][()]
        time = g["position/time"][()]
        step = g["position/step"][()]
        metal = "unit" in g["position/value"].attrs
    frames, n = x.shape[0], x.shape[1]
    name = os.path.relpath(path)

    if not metal:
        try:
            mda.Universe.empty(n, trajectory=False).load_new(path, format="H5MD")
            check(False, f"{name}: MDAnalysis refuses a file without units under convert_units=True")
        except ValueError:
            check(True, f"{name}: no units: MDAnalysis wants convert_units=False, as documented")

    # Forces are in eV/Å, a unit MDAnalysis has no name for (pbms_unit):
    # such files open with convert_units=False, which leaves Å and ps (its
    # base units) as they are.
    convert = metal and force is None
    u = mda.Universe.empty(n, trajectory=False)
    u.load_new(path, format="H5MD", convert_units=convert)
    units = u.trajectory.units
    if metal:
        want = {"time": "ps", "length": "Angstrom", "velocity": "Angstrom/ps", "force": None}
        check(units == want, f"{name}: units {units}")
    if force is not None:
        unit = g_force_unit[path]
        check(unit == "eV Angstrom-1", f"{name}: forces in {unit} (pbms_unit)")
    check(len(u.trajectory) == frames, f"{name}: {len(u.trajectory)} frames of {frames}")
    bad = []
    for k, ts in enumerate(u.trajectory):
        box = np.diagonal(edges[k]) if edges[k].ndim == 2 else edges[k]
        if not same32(ts.positions, x[k]):
            bad.append(f"positions of frame {k}")
        if v is not None and not same32(ts.velocities, v[k]):
            bad.append(f"velocities of frame {k}")
        if force is not None and not same32(ts.forces, force[k]):
            bad.append(f"forces of frame {k}")
        if not (same32(ts.dimensions[:3], box) and np.allclose(ts.dimensions[3:], 90.0, atol=1e-5)):
            bad.append(f"box of frame {k}: {ts.dimensions} vs {box}")
        if np.float32(ts.time) != np.float32(time[k]):
            bad.append(f"time of frame {k}: {ts.time} vs {time[k]}")
        if ts.data.get("step") != step[k]:
            bad.append(f"step of frame {k}: {ts.data.get('step')} vs {step[k]}")
    what = "positions, velocities" + (", forces" if force is not None else "") + ", box, time, step"
    check(not bad, f"{name}: {frames} frames x {n} particles: {what} equal to h5py's (float32)"
          + ("" if not bad else ": " + "; ".join(bad[:5])))
    return frames


def main():
    run = sys.argv[2]
    files = sorted(glob.glob(os.path.join(run, "**", "*.h5md"), recursive=True))
    stages = sorted({os.path.basename(os.path.dirname(p)) for p in files})
    check({"md", "dpd", "mpm_consistent", "mpm_metal"} <= set(stages),
          f"H5MD files of the md, dpd and mpm stages: {stages}")
    for path in files:
        try:
            check(check_file(path) > 1, f"{os.path.relpath(path)}: more than one frame")
        except Exception as e:  # MDAnalysis refusing a file is the failure looked for
            check(False, f"{os.path.relpath(path)}: {type(e).__name__}: {e}")
    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
