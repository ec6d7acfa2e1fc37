"""Pictures of a concurrent stage's body for the report page (report.py):
the DPD particles and MPM points of its H5MD files at a few times, drawn
with matplotlib (Agg: no display, no ParaView needed).

One PNG, a row per time: the body coloured by solver (DPD or MPM), by
speed |v|, and by displacement along the body's long axis since the first
frame. Colour scales are shared by all rows, so the rows compare.
"""

import os

os.environ.setdefault("HDF5_USE_FILE_LOCKING", "FALSE")  # see report_run.py

import numpy as np  # noqa: E402

PARTS = (("dpd", "DPD", "tab:green"), ("mpm", "MPM", "tab:blue"))
FRAMES = 4
AXES = "xyz"


class Part:
    """One H5MD file of the stage: its frame steps and times, the first
    frame's positions, and the frames `load` read."""

    def __init__(self, path, label, colour):
        import h5py
        self.path, self.label, self.colour = path, label, colour
        self.frames = {}
        self.first = None
        self.keep = None  # the members of the drawn slice, from the first frame
        with h5py.File(path, "r") as f:
            pos = f["particles/all/position"]
            self.steps = np.asarray(pos["step"][()], dtype=np.int64)
            self.times = np.asarray(pos["time"][()], dtype=float) if "time" in pos else None
            self.n = pos["value"].shape[1] if pos["value"].ndim == 3 else 0
            self.unit = unit_of(f.get("particles/all/velocity/value"))
            self.periodic, self.edges = box_of(f)
            if self.n and len(self.steps):
                self.first = np.asarray(pos["value"][0], dtype=float)

    def load(self, indices):
        """Reads the frames at `indices` (positions, and velocities if written)."""
        import h5py
        with h5py.File(self.path, "r") as f:
            pos = f["particles/all/position/value"]
            vel = f.get("particles/all/velocity/value")
            for i in indices:
                v = np.asarray(vel[i], dtype=float) if vel is not None and i < vel.shape[0] else None
                self.frames[i] = (np.asarray(pos[i], dtype=float), v)


def unit_of(ds):
    if ds is None or "unit" not in ds.attrs:
        return ""
    u = ds.attrs["unit"]
    return u.decode() if isinstance(u, bytes) else str(u)


def box_of(f):
    """Which axes are periodic, and the box edge lengths of the first frame."""
    import h5py
    box = f.get("particles/all/box")
    periodic = [False, False, False]
    edges = None
    if isinstance(box, h5py.Group):
        b = box.attrs.get("boundary")
        if b is not None:
            periodic = [(x.decode() if isinstance(x, bytes) else str(x)) == "periodic" for x in b]
        e = box.get("edges/value")
        if e is not None and e.shape[0]:
            edges = np.diag(np.asarray(e[0], dtype=float).reshape(3, 3))
    return periodic, edges


def pick_frames(count, wanted=FRAMES):
    """Indices of `wanted` frames spread from the first to the last."""
    if count <= wanted:
        return list(range(count))
    return sorted({round(i * (count - 1) / (wanted - 1)) for i in range(wanted)})


def nearest_index(steps, step):
    return int(np.argmin(np.abs(steps - step))) if len(steps) else None


def view_axes(parts, config):
    """(horizontal, vertical, depth) axis indices: the wave's axis (or the
    body's longest) across, the longer of the other two up."""
    pts = np.concatenate([p.first for p in parts if p.first is not None])
    pts = pts[np.all(np.isfinite(pts), axis=1)]
    extent = np.ptp(pts, axis=0) if len(pts) else np.ones(3)
    wave = config.get("wave") if isinstance(config.get("wave"), dict) else {}
    axis = wave.get("axis")
    h = AXES.index(axis) if axis in ("x", "y", "z") else int(np.argmax(extent))
    rest = [a for a in range(3) if a != h]
    v = max(rest, key=lambda a: extent[a])
    d = [a for a in rest if a != v][0]
    return h, v, d, extent


SLICE_HALF_WIDTH = 4.0  # Å: two (100) planes of the copper mesoparticle lattice (a/2 = 3.6 Å)


def choose_slice(parts, d):
    """Keeps, in each part, the members whose first position lies within
    SLICE_HALF_WIDTH of the bodies' middle along the depth axis `d`: a side
    view of everything would show only the outside, and hide a core inside
    a shell. Returns the middle."""
    firsts = [p.first[np.isfinite(p.first[:, d]), d] for p in parts if p.first is not None]
    depth = np.concatenate(firsts) if firsts else np.zeros(1)
    mid = 0.5 * (float(depth.min()) + float(depth.max())) if depth.size else 0.0
    for p in parts:
        if p.first is not None:
            p.keep = np.abs(p.first[:, d] - mid) <= SLICE_HALF_WIDTH
    return mid


def displacement(part, pos, axis):
    """Displacement along `axis` since the first frame, across a periodic box."""
    u = pos[:, axis] - part.first[:, axis]
    if part.periodic[axis] and part.edges is not None and part.edges[axis] > 0:
        length = part.edges[axis]
        u -= length * np.round(u / length)
    return u


def speed_scale(unit):
    """(factor, label): H5MD velocities in Å/ps are 100 m/s."""
    if unit.replace(" ", "") in ("Angstromps-1", "Å/ps", "Angstrom/ps"):
        return 100.0, "m/s"
    return 1.0, unit or "model units"


def rows_of(parts):
    """Per picked time: (time, step, [(part, pos, vel, u)...])."""
    main = max(parts, key=lambda p: (len(p.steps), p.n))
    rows = []
    for i in pick_frames(len(main.steps)):
        step = int(main.steps[i])
        time = float(main.times[i]) if main.times is not None else None
        rows.append((time, step, [(p, nearest_index(p.steps, step)) for p in parts]))
    return rows


def load_parts(stage_dir):
    """The parts with particles, each with its picked frames read."""
    parts = []
    for key, label, colour in PARTS:
        path = os.path.join(stage_dir, f"{key}_particles.h5md")
        if not os.path.isfile(path):
            continue
        p = Part(path, label, colour)
        if p.n and len(p.steps):
            parts.append(p)
    return parts


def draw_row(axs, row, axes3, scales, norms):
    import matplotlib.pyplot as plt
    h, v, d = axes3
    time, step, members = row
    mappables = [None, None]
    lost = 0
    for part, idx in members:
        pos, vel = part.frames[idx]
        ok = np.all(np.isfinite(pos), axis=1)
        lost += int(np.count_nonzero(~ok))
        if part.keep is not None and len(part.keep) == len(ok):
            ok &= part.keep
        order = np.argsort(-pos[ok, d])  # the front (smallest depth) drawn last
        x, y = pos[ok, h][order], pos[ok, v][order]
        kw = dict(s=float(np.clip(12000.0 / max(1, len(x)), 4, 20)), linewidths=0, rasterized=True)
        axs[0].scatter(x, y, color=part.colour, **kw)
        if vel is not None:
            sp = np.linalg.norm(vel[ok], axis=1)[order] * scales[0]
            mappables[0] = axs[1].scatter(x, y, c=sp, cmap="viridis", norm=norms[0], **kw)
        u = displacement(part, pos, h)[ok][order]
        mappables[1] = axs[2].scatter(x, y, c=u, cmap="coolwarm", norm=norms[1], **kw)
    label = f"t = {time:.3g} ps" if time is not None else f"step {step}"
    if lost:  # a blown-up step: say how many are not drawn
        label += f", {lost} non-finite"
    axs[0].set_ylabel(f"{label}\n{AXES[v]} (Å)", fontsize=8)
    for ax in axs:
        ax.set_aspect("equal")
        ax.tick_params(labelsize=7)
    plt.setp(axs[1].get_yticklabels(), visible=False)
    plt.setp(axs[2].get_yticklabels(), visible=False)
    return mappables


def colour_norms(rows, h, scale):
    """Shared colour limits: speed 0 to its 99.5th percentile, displacement
    symmetric about 0 at its 99.5th percentile of |u|, over the frames after
    the first."""
    from matplotlib.colors import Normalize
    speeds, disps = [], []
    # A flyer launched at the first frame would set the speed scale for all
    # rows; the later frames set it (the flyer saturates).
    for _, _, members in rows[1:] or rows:
        for part, idx in members:
            pos, vel = part.frames[idx]
            ok = np.all(np.isfinite(pos), axis=1)
            if vel is not None:
                speeds.append(np.linalg.norm(vel[ok], axis=1) * scale)
            disps.append(np.abs(displacement(part, pos, h)[ok]))
    top_s = np.percentile(np.concatenate(speeds), 99.5) if speeds else 1.0
    top_u = np.percentile(np.concatenate(disps), 99.5) if disps else 1.0
    top_s = top_s if np.isfinite(top_s) and top_s > 0 else 1.0
    top_u = top_u if np.isfinite(top_u) and top_u > 0 else 1.0
    return Normalize(0.0, top_s), Normalize(-top_u, top_u)


def figure_size(extent, h, v, nrows):
    """Inches: three panels across 14 in, each as tall as the body's aspect asks."""
    aspect = extent[v] / extent[h] if extent[h] > 0 else 0.3
    panel = min(max(4.4 * aspect, 0.7), 3.0)
    return 14.0, nrows * (panel + 0.35) + 1.3


def render_body(stage_dir, out_png, title, config):
    """Writes out_png; returns None, or why there is no picture."""
    parts = load_parts(stage_dir)
    if not parts:
        every = config.get("particles_every")
        hint = "; set particles_every to draw it" if not every else ""
        return f"the stage wrote no particle frames (particles_every: {every}){hint}"
    rows = rows_of(parts)
    for p in parts:
        p.load(sorted({idx for _, _, m in rows for q, idx in m if q is p}))
    h, v, d, extent = view_axes(parts, config)
    mid = choose_slice(parts, d)
    title = (f"{title}\nslice {2 * SLICE_HALF_WIDTH:g} Å thick through the middle, "
             f"{AXES[d]} = {mid:.4g} Å")
    scale, unit = speed_scale(parts[0].unit)
    norms = colour_norms(rows, h, scale)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(len(rows), 3, figsize=figure_size(extent, h, v, len(rows)),
                             squeeze=False, sharex=True, sharey=True, constrained_layout=True)
    mappables = [None, None]
    for axs, row in zip(axes, rows):
        got = draw_row(axs, row, (h, v, d), (scale,), norms)
        mappables = [g or m for g, m in zip(got, mappables)]
    finish_figure(fig, axes, mappables, parts, (h, unit, title))
    save_small_png(fig, out_png)
    plt.close(fig)
    return None


def save_small_png(fig, path):
    """Saves with a palette of 192 colours where Pillow is there (Debian's
    matplotlib depends on it): a quarter of the bytes of a full-colour PNG
    of thousands of dots, and the page carries it inline."""
    try:
        from PIL import Image
    except ImportError:
        fig.savefig(path, dpi=100)
        return
    fig.set_dpi(100)
    fig.canvas.draw()
    rgb = np.asarray(fig.canvas.buffer_rgba())[..., :3]
    Image.fromarray(rgb).quantize(colors=192).save(path, format="png", optimize=True)


def solver_colourbar(fig, axes, parts):
    """A two-colour bar under the solver column, so that all three columns
    have a bar and keep the same width."""
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import BoundaryNorm, ListedColormap
    cmap = ListedColormap([p.colour for p in parts])
    norm = BoundaryNorm(np.arange(len(parts) + 1) - 0.5, len(parts))
    bar = fig.colorbar(ScalarMappable(norm=norm, cmap=cmap), ax=axes[:, 0],
                       orientation="horizontal", fraction=0.04, pad=0.02,
                       ticks=range(len(parts)))
    bar.ax.set_xticklabels([f"{p.label} ({p.n} {'particles' if p.label == 'DPD' else 'points'})"
                            for p in parts], fontsize=8)


def finish_figure(fig, axes, mappables, parts, labels):
    h, unit, title = labels
    axes[0, 0].set_title("solver", fontsize=9)
    axes[0, 1].set_title(f"speed |v| ({unit})", fontsize=9)
    axes[0, 2].set_title(f"displacement along {AXES[h]} since the first frame (Å)", fontsize=9)
    for ax in axes[-1]:
        ax.set_xlabel(f"{AXES[h]} (Å)", fontsize=8)
    solver_colourbar(fig, axes, parts)
    for col, m in ((1, mappables[0]), (2, mappables[1])):
        if m is not None:
            bar = fig.colorbar(m, ax=axes[:, col], orientation="horizontal", fraction=0.04,
                               pad=0.02, extend="both" if col == 2 else "max")
            bar.ax.tick_params(labelsize=8)
    fig.suptitle(title, fontsize=10)
