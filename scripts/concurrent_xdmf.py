"""One XDMF 3 file that opens a concurrent stage's three outputs together.

A concurrent stage writes its DPD particles (`dpd_particles.h5md`), its MPM
points (`mpm_particles.h5md`) and its grid (`mpm_grid.xdmf` over
`mpm_grid.h5`) as three files, one per writer, because particle readers
take the first particle group of a file only. `concurrent.xdmf` describes
them as one temporal collection: at each particle frame, a spatial
collection of the DPD particles and the MPM points (polyvertex meshes with
velocity and id, read by hyperslab from the H5MD files) and, where the grid
has a frame at the same time, that grid frame. It holds no data of its own;
ParaView opens it with the XDMF 3 reader.

    write_concurrent_xdmf(stage_dir) -> path or None
"""

import os
import xml.etree.ElementTree as ET

import h5py

PARTS = (("dpd_particles", "dpd_particles.h5md"), ("mpm_points", "mpm_particles.h5md"))


def number_type(dataset):
    kind = dataset.dtype.kind
    return ("Float" if kind == "f" else "Int" if kind == "i" else "UInt"), dataset.dtype.itemsize


def hdf_item(path, name, dataset):
    t, p = number_type(dataset)
    dims = " ".join(str(d) for d in dataset.shape)
    return (f'<DataItem Dimensions="{dims}" NumberType="{t}" Precision="{p}" Format="HDF">'
            f"{path}:{name}</DataItem>")


def frame_slab(path, name, dataset, frame):
    """Frame `frame` of a (frames, N, 3) H5MD value dataset."""
    _, n, c = dataset.shape
    t, p = number_type(dataset)
    # The reader takes the slab's number type from the outer item.
    return (f'<DataItem ItemType="HyperSlab" Dimensions="{n} {c}" '
            f'NumberType="{t}" Precision="{p}">'
            f'<DataItem Dimensions="3 3" NumberType="UInt" Format="XML">'
            f'{frame} 0 0 1 1 1 1 {n} {c}</DataItem>'
            f"{hdf_item(path, name, dataset)}</DataItem>")


def particle_grid(label, path, group, frame):
    pos = group["position/value"]
    n = pos.shape[1]
    base = f"/particles/{group.name.split('/')[-1]}"
    xml = [f'<Grid Name="{label}" GridType="Uniform">',
           f'<Topology TopologyType="Polyvertex" NumberOfElements="{n}" NodesPerElement="1"/>',
           f'<Geometry GeometryType="XYZ">{frame_slab(path, base + "/position/value", pos, frame)}'
           "</Geometry>"]
    if "velocity" in group:
        vel = group["velocity/value"]
        xml.append('<Attribute Name="velocity" AttributeType="Vector" Center="Node">'
                   f'{frame_slab(path, base + "/velocity/value", vel, frame)}</Attribute>')
    if "id" in group:
        xml.append('<Attribute Name="id" AttributeType="Scalar" Center="Node">'
                   f'{hdf_item(path, base + "/id", group["id"])}</Attribute>')
    xml.append("</Grid>")
    return "".join(xml)


def grid_frames(stage_dir):
    """The grid's frames as (time, XML text without its Time element)."""
    path = os.path.join(stage_dir, "mpm_grid.xdmf")
    if not os.path.isfile(path):
        return []
    frames = []
    for g in ET.parse(path).getroot().iter("Grid"):
        if g.get("GridType") != "Uniform":
            continue
        time = g.find("Time")
        if time is None:
            continue
        g.remove(time)
        g.set("Name", "grid")
        frames.append((float(time.get("Value")), ET.tostring(g, encoding="unicode")))
    return frames


def write_concurrent_xdmf(stage_dir):
    files = [(label, os.path.join(stage_dir, name)) for label, name in PARTS]
    if not all(os.path.isfile(p) for _, p in files):
        return None
    grids = grid_frames(stage_dir)
    handles = [(label, os.path.basename(p), h5py.File(p, "r")) for label, p in files]
    try:
        groups = [(label, name, next(iter(h["particles"].values()))) for label, name, h in handles]
        times = [g["position/time"][:] for _, _, g in groups]
        steps = [g["position/step"][:] for _, _, g in groups]
        count = min(len(t) for t in times)
        frames = []
        for k in range(count):
            t = float(times[0][k])
            parts = [particle_grid(label, name, g, k) for label, name, g in groups]
            parts += [xml for tg, xml in grids if abs(tg - t) <= 1e-9 * max(1.0, abs(t))]
            frames.append(f'<Grid Name="step_{int(steps[0][k])}" GridType="Collection" '
                          f'CollectionType="Spatial"><Time Value="{t!r}"/>{"".join(parts)}</Grid>')
    finally:
        for _, _, h in handles:
            h.close()
    out = os.path.join(stage_dir, "concurrent.xdmf")
    tmp = out + ".tmp"
    with open(tmp, "w") as f:
        f.write('<?xml version="1.0" encoding="UTF-8"?>\n<Xdmf Version="3.0"><Domain>'
                '<Grid Name="concurrent" GridType="Collection" CollectionType="Temporal">')
        f.write("\n".join(frames))
        f.write("</Grid></Domain></Xdmf>\n")
    os.replace(tmp, out)
    return out
