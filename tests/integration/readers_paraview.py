#!/usr/bin/python3
"""ParaView opens every XDMF grid file of a run; `./pbms plot` renders with it.

    readers_paraview.py ROOT RUN_DIR

1. For every `<stage>/grid.xdmf` under RUN_DIR (mpm_run with grid_every),
   pvpython (Debian paraview + python3-paraview) opens it by its absolute
   path from another working directory with the XDMF 3 reader, and at every
   time it lists reads every field; each must equal the dataset in grid.h5
   that h5py reads, and the times, origin, spacing and node counts must
   equal the ones grid.h5 records. (This part runs inside pvpython: this
   script calls pvpython on itself.) Reading needs no display.
2. `./pbms plot RUN_DIR` renders, with ParaView under xvfb-run, a grid field
   of each XDMF file and the particles of each H5MD file; each PNG must
   exist, be 800 x 600, and not be blank: at least 1 % of its pixels differ
   from the background colour and the image holds more than 20 colours.
"""

import glob
import json
import os
import subprocess
import sys
import tempfile

from checklist import Checklist


def in_pvpython(xdmf):
    """Runs inside pvpython: compares one XDMF file's fields with its .h5 (same stem)."""
    import h5py
    import numpy as np
    from paraview import servermanager
    from paraview import simple as pv
    from vtkmodules.util.numpy_support import vtk_to_numpy

    bad = []
    reader = pv.Xdmf3ReaderT(FileName=[xdmf])
    reader.UpdatePipelineInformation()
    times = list(reader.TimestepValues)
    h5path = os.path.splitext(xdmf)[0] + ".h5"
    with h5py.File(h5path, "r") as h5:
        steps = sorted(h5.keys(), key=lambda s: int(s.split("_")[1]))
        want_times = [float(h5[s].attrs["time"]) for s in steps]
        origin = h5.attrs["origin"]
        spacing = float(h5.attrs["cell_size"])
        nodes = list(h5.attrs["nodes_per_axis"])
        if not np.allclose(times, want_times, rtol=1e-12, atol=0):
            bad.append(f"times {times} vs {want_times}")
        fields = 0
        for t, s in zip(times, steps):
            reader.UpdatePipeline(t)
            data = servermanager.Fetch(reader)
            if data.IsA("vtkMultiBlockDataSet"):
                data = data.GetBlock(0)
            if list(data.GetDimensions()) != nodes:
                bad.append(f"{s}: dimensions {data.GetDimensions()} vs {nodes}")
            if not np.allclose(data.GetOrigin(), origin, rtol=0, atol=1e-12):
                bad.append(f"{s}: origin {data.GetOrigin()} vs {list(origin)}")
            if not np.allclose(data.GetSpacing(), spacing, rtol=1e-12, atol=0):
                bad.append(f"{s}: spacing {data.GetSpacing()} vs {spacing}")
            for name, ds in h5[s].items():
                array = data.GetPointData().GetArray(name)
                if array is None:
                    bad.append(f"{s}: ParaView has no field '{name}'")
                    continue
                got = vtk_to_numpy(array)
                want = ds[()].reshape(got.shape)
                if not np.array_equal(got, want):
                    bad.append(f"{s}/{name}: max |ParaView - h5py| {np.abs(got - want).max():.3g}")
                fields += 1
    print(json.dumps({"times": len(times), "fields": fields, "bad": bad}))


def png_is_drawn(path):
    import matplotlib.image as mpimg
    import numpy as np

    img = mpimg.imread(path)[..., :3]
    background = img[0, 0]
    differ = np.any(np.abs(img - background) > 0.02, axis=2).mean()
    colours = len(np.unique((img * 255).astype(np.uint8).reshape(-1, 3), axis=0))
    return img.shape[:2] == (600, 800) and differ > 0.01 and colours > 20, differ, colours


def main():
    root, run = sys.argv[1], os.path.abspath(sys.argv[2])
    check = Checklist()

    # concurrent.xdmf joins a concurrent stage's particle files and grid; test
    # concurrent_paraview opens it with the reader it needs.
    xdmfs = sorted(x for x in glob.glob(os.path.join(run, "**", "*.xdmf"), recursive=True)
                   if os.path.basename(x) != "concurrent.xdmf")
    h5mds = sorted(glob.glob(os.path.join(run, "**", "*.h5md"), recursive=True))
    check(len(xdmfs) >= 2, f"{len(xdmfs)} XDMF grid files in the run")
    with tempfile.TemporaryDirectory() as elsewhere:
        for xdmf in xdmfs:
            out = subprocess.run(["pvpython", os.path.abspath(__file__), "--in-pvpython", xdmf],
                                 capture_output=True, text=True, cwd=elsewhere, timeout=300)
            lines = [ln for ln in out.stdout.splitlines() if ln.startswith("{")]
            if out.returncode != 0 or not lines:
                check(False, f"pvpython on {xdmf}: exit {out.returncode}: {out.stderr[-2000:]}")
                continue
            r = json.loads(lines[-1])
            check(not r["bad"] and r["times"] > 1 and r["fields"] >= 2 * r["times"],
                  f"ParaView reads {os.path.relpath(xdmf, run)} by its absolute path: "
                  f"{r['times']} times, {r['fields']} fields equal to its .h5"
                  + ("" if not r["bad"] else ": " + "; ".join(r["bad"][:5])))

    for old in glob.glob(os.path.join(run, "*_grid_*.png")) + \
            glob.glob(os.path.join(run, "*particles.png")):
        os.remove(old)
    out = subprocess.run([os.path.join(root, "pbms"), "plot", run], capture_output=True, text=True,
                         timeout=600)
    print(out.stdout + out.stderr, end="")
    check(out.returncode == 0, f"./pbms plot exited {out.returncode}")
    expected = []
    for xdmf in xdmfs:
        stage = os.path.basename(os.path.dirname(xdmf))
        expected.append(os.path.join(run, f"{stage}_grid_mass.png"))
    for h5md in h5mds:
        stage = os.path.basename(os.path.dirname(h5md))
        stem = os.path.splitext(os.path.basename(h5md))[0]
        name = "particles" if stem == "particles" else f"{stem}_particles"
        expected.append(os.path.join(run, f"{stage}_{name}.png"))
    for png in expected:
        if not os.path.isfile(png):
            check(False, f"{os.path.basename(png)} written by ./pbms plot")
            continue
        ok, differ, colours = png_is_drawn(png)
        check(ok, f"{os.path.basename(png)}: 800 x 600, {differ:.1%} of pixels drawn, "
              f"{colours} colours")
    return check.finish()


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "--in-pvpython":
        in_pvpython(sys.argv[2])
    else:
        sys.exit(main())
