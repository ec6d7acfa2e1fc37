"""Renders a run's grid fields and particles with ParaView.

    pvpython --force-offscreen-rendering scripts/render_paraview.py RUN_DIR

(`./pbms plot RUN_DIR` runs it, under xvfb-run when there is no display.)
For each XDMF grid file under RUN_DIR (`<stage>/grid.xdmf`, written by
mpm_run with grid_every) it writes `RUN_DIR/<stage>_grid_<field>.png`: the
first scalar field at the last time, on the grid's nodes, seen along z. For
each H5MD file (`<stage>/<name>.h5md`) it writes
`RUN_DIR/<stage>_particles.png` (`<stage>_<name>_particles.png` for other
names than `particles`): the particles of the last frame, coloured by speed.

ParaView has no H5MD reader; the particles are read with h5py and handed to
ParaView as points. Exit status 0 when everything found was rendered (or
nothing was found), 1 otherwise.
"""

import os
import sys

import h5py
import numpy as np
from paraview import simple as pv
from vtkmodules.util import numpy_support
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData

SIZE = [800, 600]


def stage_of(run_dir, path):
    rel = os.path.relpath(os.path.dirname(path), run_dir)
    return "run" if rel == "." else rel.replace(os.sep, "_")


def save(source, representation, field, out, title, bar_title, t=None, direction=(0, 0, 1),
         up=(0, 1, 0)):
    """Renders `source` coloured by the point field `field`, seen from
    `direction`, into the PNG `out`: white background, black `title` on top,
    a colour bar titled `bar_title`."""
    view = pv.CreateRenderView()
    view.ViewSize = SIZE
    view.OrientationAxesVisibility = 1
    view.Background = [1, 1, 1]
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    if t is not None:
        view.ViewTime = t
    shown = pv.Show(source, view)
    shown.Representation = representation
    if representation == "Points":
        shown.PointSize = 6
        try:
            shown.RenderPointsAsSpheres = 1
        except AttributeError:
            pass
    pv.ColorBy(shown, ("POINTS", field))
    shown.RescaleTransferFunctionToDataRange(True, False)
    shown.SetScalarBarVisibility(view, True)
    bar = pv.GetScalarBar(pv.GetColorTransferFunction(field), view)
    bar.Title = bar_title
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = [0, 0, 0]
    text = pv.Text(Text=title)
    label = pv.Show(text, view)
    label.Color = [0, 0, 0]
    label.WindowLocation = "Upper Center"
    view.CameraPosition = list(direction)
    view.CameraFocalPoint = [0, 0, 0]
    view.CameraViewUp = list(up)
    view.ResetCamera()
    pv.SaveScreenshot(out, view, ImageResolution=SIZE)
    pv.Delete(view)
    pv.Delete(text)
    pv.Delete(source)


def render_grid(run_dir, xdmf):
    reader = pv.Xdmf3ReaderT(FileName=[os.path.abspath(xdmf)])
    reader.UpdatePipelineInformation()
    times = list(reader.TimestepValues) if reader.TimestepValues else [0.0]
    t = times[-1]
    reader.UpdatePipeline(t)
    info = reader.GetPointDataInformation()
    scalars = [info.GetArray(i).GetName() for i in range(info.GetNumberOfArrays())
               if info.GetArray(i).GetNumberOfComponents() == 1]
    if not scalars:
        raise RuntimeError(f"{xdmf}: no scalar field on the nodes")
    field = scalars[0]
    stage = stage_of(run_dir, xdmf)
    unit = grid_unit(xdmf, field)
    out = os.path.join(run_dir, f"{stage}_grid_{field}.png")
    save(reader, "Surface", field, out, f"{stage}: nodal {field}, t = {t:g}",
         f"{field} [{unit}]" if unit not in ("", "1") else field, t=t, direction=[0, 0, 1],
         up=[0, 1, 0])
    return out, f"{field} at t = {t:g} ({len(times)} times)"


def grid_unit(xdmf, field):
    """The unit grid.h5 records for `field` at its last step, or ''."""
    try:
        with h5py.File(os.path.splitext(xdmf)[0] + ".h5", "r") as f:
            last = max(f.keys(), key=lambda s: int(s.split("_")[1]))
            u = f[last][field].attrs.get("unit", "")
            return u.decode() if isinstance(u, bytes) else str(u)
    except (OSError, KeyError, ValueError):
        return ""


def last_frame(path):
    with h5py.File(path, "r") as f:
        g = f["particles/all"]
        n = min(g["position/value"].shape[0], g["position/step"].shape[0])
        if n == 0:
            raise RuntimeError(f"{path}: no frame")
        x = g["position/value"][n - 1]
        v = g["velocity/value"][n - 1] if "velocity" in g else np.zeros_like(x)
        unit = g["velocity/value"].attrs.get("unit", "") if "velocity" in g else ""
        unit = unit.decode() if isinstance(unit, bytes) else str(unit)
        return x, v, int(g["position/step"][n - 1]), unit.replace(" ps-1", "/ps")


def render_particles(run_dir, h5md):
    x, v, step, unit = last_frame(h5md)
    poly = vtkPolyData()
    points = vtkPoints()
    points.SetData(numpy_support.numpy_to_vtk(np.ascontiguousarray(x, dtype=float), deep=True))
    poly.SetPoints(points)
    cells = vtkCellArray()
    for i in range(x.shape[0]):
        cells.InsertNextCell(1)
        cells.InsertCellPoint(i)
    poly.SetVerts(cells)
    speed = numpy_support.numpy_to_vtk(np.linalg.norm(v, axis=1), deep=True)
    speed.SetName("speed")
    poly.GetPointData().AddArray(speed)
    source = pv.TrivialProducer()
    source.GetClientSideObject().SetOutput(poly)
    source.UpdatePipeline()
    stem = os.path.splitext(os.path.basename(h5md))[0]
    name = "particles" if stem == "particles" else f"{stem}_particles"
    out = os.path.join(run_dir, f"{stage_of(run_dir, h5md)}_{name}.png")
    save(source, "Points", "speed", out, f"{stage_of(run_dir, h5md)}: {stem}, step {step}",
         f"speed [{unit}]" if unit else "speed", direction=[1, -1.5, 1], up=[0, 0, 1])
    return out, f"{x.shape[0]} particles at step {step}"


def main(argv):
    if len(argv) != 2:
        print(__doc__.strip(), file=sys.stderr)
        return 1
    run_dir = argv[1]
    found = []
    for top, dirs, names in os.walk(run_dir):
        dirs[:] = sorted(d for d in dirs if not d.startswith("."))
        for n in sorted(names):
            if n.endswith(".xdmf"):
                found.append((render_grid, os.path.join(top, n)))
            elif n.endswith(".h5md"):
                found.append((render_particles, os.path.join(top, n)))
    status = 0
    for render, path in found:
        try:
            out, what = render(run_dir, path)
            print(f"{out}: {what}")
        except Exception as e:  # one bad file must not stop the others
            print(f"pbms plot: cannot render {path}: {e}", file=sys.stderr)
            status = 1
    return status


if __name__ == "__main__":
    sys.exit(main(sys.argv))
