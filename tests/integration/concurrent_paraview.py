#!/usr/bin/python3
"""ParaView opens a concurrent stage's three outputs together.

    concurrent_paraview.py ROOT RUN_DIR

RUN_DIR is the run of tests/integration/concurrent_impact.sh. For the
treated concurrent stages, `concurrent.xdmf` (written next to the stage's
files by the run's plot step, scripts/concurrent_xdmf.py) is opened by
pvpython with ParaView's XDMF Reader, by its absolute path from another
working directory. At every time it lists, the DPD particles' and the MPM
points' positions must equal the frame h5py reads from the two H5MD files,
and the grid must be there at every time the grid file has a frame, with
its node count and, node by node, the mass and velocity that frame holds
(so a reader stuck on one frame, or axes taken in the wrong order, fails).
(ParaView's Xdmf3 readers take the grid but not the particles' hyperslabs;
the XDMF Reader takes all three.)
"""

import json
import os
import subprocess
import sys
import tempfile

from checklist import Checklist


def in_pvpython(xdmf):
    import h5py
    import numpy as np
    from paraview import servermanager
    from paraview import simple as pv
    from vtkmodules.util.numpy_support import vtk_to_numpy

    reader = pv.XDMFReader(FileNames=[xdmf])
    reader.UpdatePipelineInformation()
    times = list(reader.TimestepValues)
    stage = os.path.dirname(xdmf)
    report = {"times": len(times), "bad": [], "grid_frames": 0}
    with h5py.File(os.path.join(stage, "dpd_particles.h5md"), "r") as d, \
            h5py.File(os.path.join(stage, "mpm_particles.h5md"), "r") as m, \
            h5py.File(os.path.join(stage, "mpm_grid.h5"), "r") as g:
        want = {"dpd_particles": d["particles/all/position"], "mpm_points": m["particles/all/position"]}
        grid_steps = {int(k.split("_")[1]) for k in g.keys() if k.startswith("step_")}
        h5_times = list(want["dpd_particles"]["time"][:])
        if not np.allclose(times, h5_times, rtol=1e-12, atol=0):
            report["bad"].append(f"times {times} vs the H5MD file's {h5_times}")
        for k, t in enumerate(times):
            reader.UpdatePipeline(t)
            data = servermanager.Fetch(reader)
            it = data.NewIterator()
            it.InitTraversal()
            seen = {}
            while not it.IsDoneWithTraversal():
                name = it.GetCurrentMetaData().Get(data.NAME()).split("[")[0]
                seen[name] = it.GetCurrentDataObject()
                it.GoToNextItem()
            for part, group in want.items():
                block = seen.get(part)
                if block is None:
                    report["bad"].append(f"t = {t}: no {part} block")
                    continue
                pts = vtk_to_numpy(block.GetPoints().GetData())
                if not np.array_equal(pts, group["value"][k]):
                    report["bad"].append(f"t = {t}: {part} positions differ from frame {k}")
            step = int(want["dpd_particles"]["step"][k])
            if step in grid_steps:
                report["grid_frames"] += 1
                block = seen.get("grid")
                frame = g[f"step_{step}"]
                nodes = int(np.prod(frame["mass"].shape))
                if block is None or block.GetNumberOfPoints() != nodes:
                    report["bad"].append(f"t = {t}: grid missing or not {nodes} nodes")
                    continue
                # VTK numbers the nodes x fastest, as the file's (z, y, x) order flattened.
                for field, width in (("mass", 1), ("velocity", 3)):
                    array = block.GetPointData().GetArray(field)
                    got = None if array is None else vtk_to_numpy(array).reshape(nodes, width)
                    if got is None or not np.array_equal(got, frame[field][()].reshape(nodes, width)):
                        report["bad"].append(f"t = {t}: grid {field} differs from step {step} of the file")
    print("REPORT " + json.dumps(report))


def main():
    root, run = sys.argv[1], os.path.abspath(sys.argv[2])
    check = Checklist()
    for stage in ("concurrent", "concurrent_seed"):
        xdmf = os.path.join(run, stage, "concurrent.xdmf")
        if not check(os.path.isfile(xdmf), f"{stage}: the run wrote {xdmf}"):
            continue
        with tempfile.TemporaryDirectory() as elsewhere:
            out = subprocess.run(["pvpython", os.path.abspath(__file__), "--in-pvpython", xdmf],
                                 cwd=elsewhere, capture_output=True, text=True, timeout=600)
        lines = [l for l in out.stdout.splitlines() if l.startswith("REPORT ")]
        if not check(out.returncode == 0 and lines, f"{stage}: pvpython ran (exit {out.returncode})"):
            print(out.stderr[-2000:])
            continue
        r = json.loads(lines[-1][7:])
        check(not r["bad"] and r["times"] > 1 and r["grid_frames"] > 0,
              f"{stage}: ParaView read both parts at {r['times']} times and the grid (mass and "
              f"velocity node by node) at {r['grid_frames']}, equal to the files" + ("; " + "; ".join(r["bad"][:5]) if r["bad"] else ""))
    return check.finish()


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "--in-pvpython":
        in_pvpython(sys.argv[2])
    else:
        sys.exit(main())
