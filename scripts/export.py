#!/usr/bin/python3
"""Extended XYZ copies of a run's particle trajectories, for OVITO.

    ./pbms export RUN_DIR      (or: /usr/bin/python3 scripts/export.py RUN_DIR)

OVITO, the viewer most materials scientists use, does not read H5MD. For
every H5MD file under RUN_DIR (`<stage>/*.h5md`, written by md_driver,
dpd_driver and mpm_driver) this writes `<stage>/<name>.xyz` beside it: one
extended XYZ frame per H5MD frame, with the columns

    id:I:1    particle id (H5MD particles/all/id)
    type:I:1  species (particles/all/species); OVITO's Particle Type
    pos:R:3   position
    velo:R:3  velocity; OVITO's Velocity
    forces:R:3, internal_energy:R:1   where the H5MD file has them

and on each frame's comment line the box (`Lattice`, `pbc`), `Time`, `step`,
the `solver` that wrote the file (md, dpd or mpm) and `units`. A `type`
column rather than `species`: ASE takes `species` for chemical symbols.

Units: a run in metal units gives angstrom, ps, angstrom/ps, and forces in
eV/angstrom (the H5MD file's own unit; it names it in `pbms_unit`);
`units=metal` on the comment line. An MPM run in consistent units has no unit attributes in its H5MD
file; its numbers are copied as they are, with `units=consistent`.

Values are written with 17 significant digits, so a reader gets the H5MD
file's doubles back exactly. Only frames complete in every series are
written, so a file still being written by a running job exports cleanly.
Each XYZ file is written to a temporary name and renamed into place.

Exit status: 0 when at least one file was exported; 1 when RUN_DIR holds
no H5MD file or one cannot be read.
"""

import os
import sys

import h5py
import numpy as np

# Units an H5MD file of PBMS may carry, as factors to metal units.
TO_METAL = {
    "Angstrom": 1.0,
    "Angstrom ps-1": 1.0,
    "ps": 1.0,
    "eV": 1.0,
    "eV Angstrom-1": 1.0,
}


def unit_of(dataset):
    """The dataset's unit attribute as str, or None (forces: `pbms_unit`)."""
    u = dataset.attrs.get("unit", dataset.attrs.get("pbms_unit"))
    if u is None:
        return None
    return u.decode() if isinstance(u, bytes) else str(u)


def solver_of(f):
    """md, dpd or mpm, from the creator the driver wrote; '' if unknown."""
    text = ""
    for key in ("name", "version"):
        v = f["h5md/creator"].attrs.get(key, b"") if "h5md/creator" in f else b""
        text += " " + (v.decode() if isinstance(v, bytes) else str(v))
    for solver in ("md", "dpd", "mpm"):
        if f"{solver}_driver" in text:
            return solver
    return ""


class Series:
    """One H5MD time series (value, step, time), converted to metal units."""

    def __init__(self, group, path):
        self.name = group.name
        self.value = group["value"]
        self.step = group["step"]
        self.time = group["time"] if "time" in group else None
        unit = unit_of(self.value)
        if unit is not None and unit not in TO_METAL:
            raise ValueError(f"{path}: {self.name}/value has unit '{unit}', not one PBMS writes")
        self.factor = 1.0 if unit is None else TO_METAL[unit]
        self.has_unit = unit is not None

    def frames(self):
        n = min(self.value.shape[0], self.step.shape[0])
        return n if self.time is None else min(n, self.time.shape[0])

    def __getitem__(self, k):
        v = self.value[k]
        return v * self.factor if self.factor != 1.0 else v


def boolean(b):
    return "T" if b else "F"


def export(path):
    """Writes the .xyz beside `path`; returns (xyz path, frames)."""
    out = os.path.splitext(path)[0] + ".xyz"
    with h5py.File(path, "r") as f:
        g = f["particles/all"]
        solver = solver_of(f)
        series = {"pos": Series(g["position"], path)}
        if "velocity" in g:
            series["velo"] = Series(g["velocity"], path)
        if "force" in g:
            series["forces"] = Series(g["force"], path)
        if "internal_energy" in g:
            series["internal_energy"] = Series(g["internal_energy"], path)
        edges = Series(g["box/edges"], path)
        metal = series["pos"].has_unit
        n = series["pos"].value.shape[1]
        ids = g["id"][()] if "id" in g else np.arange(n)
        species = g["species"][()] if "species" in g else np.zeros(n, dtype=int)
        boundary = [b.decode() if isinstance(b, bytes) else str(b)
                    for b in g["box"].attrs["boundary"]]
        pbc = " ".join(boolean(b == "periodic") for b in boundary)
        frames = min([s.frames() for s in series.values()] + [edges.frames()])
        steps = series["pos"].step[:frames]
        times = series["pos"].time[:frames] if series["pos"].time is not None else steps * np.nan

        props = "id:I:1:type:I:1:pos:R:3"
        for name in ("velo", "forces"):
            if name in series:
                props += f":{name}:R:3"
        if "internal_energy" in series:
            props += ":internal_energy:R:1"
        tmp = out + ".tmp"
        with open(tmp, "w") as xyz:
            for k in range(frames):
                e = edges[k]
                box = np.diag(e) if e.ndim == 1 else e
                cols = [ids.reshape(n, 1).astype(np.int64), species.reshape(n, 1).astype(np.int64),
                        series["pos"][k]]
                for name in ("velo", "forces", "internal_energy"):
                    if name in series:
                        cols.append(series[name][k].reshape(n, -1))
                table = np.hstack([c.astype(float) for c in cols])
                lattice = " ".join(repr(float(x)) for x in box.reshape(9))
                xyz.write(f"{n}\n")
                xyz.write(f'Lattice="{lattice}" Properties={props} Time={float(times[k])!r} '
                          f'step={int(steps[k])} pbc="{pbc}" solver={solver or "unknown"} '
                          f'units={"metal" if metal else "consistent"}\n')
                fmt = ["%d", "%d"] + ["%.17g"] * (table.shape[1] - 2)
                np.savetxt(xyz, table, fmt=fmt)
        os.replace(tmp, out)
    return out, frames


def main(argv):
    if len(argv) != 2 or argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if len(argv) == 2 else 1
    run_dir = argv[1]
    if not os.path.isdir(run_dir):
        print(f"pbms export: '{run_dir}' is not a directory", file=sys.stderr)
        return 1
    files = []
    for top, dirs, names in os.walk(run_dir):
        dirs[:] = sorted(d for d in dirs if not d.startswith("."))
        files += [os.path.join(top, n) for n in sorted(names) if n.endswith(".h5md")]
    if not files:
        print(f"pbms export: no H5MD file under '{run_dir}'", file=sys.stderr)
        return 1
    status = 0
    for path in files:
        try:
            out, frames = export(path)
            print(f"{out}: {frames} frame(s)")
        except (OSError, KeyError, ValueError) as e:
            print(f"pbms export: {path}: {e}", file=sys.stderr)
            status = 1
    return status


if __name__ == "__main__":
    sys.exit(main(sys.argv))
