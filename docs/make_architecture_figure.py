#!/usr/bin/python3
"""Draw docs/architecture.png (the processes of one PBMS job and their messages) and
docs/figures/layers.png (the layers of the source tree and what may include what).

Run with: /usr/bin/python3 docs/make_architecture_figure.py
"""

import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import FancyArrowPatch, FancyBboxPatch  # noqa: E402

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "architecture.png")
LAYERS_OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "figures", "layers.png")

BLUE, GREEN, GREY, RED, ORANGE = "#dbe8f6", "#dff0d8", "#f2f2f2", "#c0392b", "#fbe9d0"


def box(ax, x0, y0, x1, y1, face, text="", dashed=False, fs=10, weight="normal",
        va="center", ty=None, edge="0.25", lw=1.3, round_=0.12, z=1):
    ax.add_patch(FancyBboxPatch((x0, y0), x1 - x0, y1 - y0,
                                boxstyle=f"round,pad=0,rounding_size={round_}",
                                fc=face, ec=edge, lw=lw, ls=(0, (5, 3)) if dashed else "-",
                                zorder=z))
    if text:
        ax.text((x0 + x1) / 2, ty if ty is not None else (y0 + y1) / 2, text, ha="center",
                va=va, fontsize=fs, weight=weight, zorder=z + 1, linespacing=1.35)


def arrow(ax, p, q, color="0.15", dashed=False, both=False, lw=1.6, rad=0.0):
    ax.add_patch(FancyArrowPatch(p, q, arrowstyle="<|-|>" if both else "-|>",
                                 mutation_scale=14, color=color, lw=lw,
                                 ls=(0, (5, 3)) if dashed else "-",
                                 connectionstyle=f"arc3,rad={rad}", zorder=5,
                                 shrinkA=0, shrinkB=0))


def label(ax, x, y, s, color="0.1", fs=9, ha="center", style="normal", weight="normal"):
    ax.text(x, y, s, ha=ha, va="center", fontsize=fs, color=color, style=style,
            weight=weight, zorder=6, linespacing=1.3,
            bbox=dict(fc="white", ec="none", pad=1.5, alpha=0.9))


def main():
    fig, ax = plt.subplots(figsize=(13.0, 8.2))
    ax.set_xlim(0, 15)
    ax.set_ylim(0, 9.6)
    ax.axis("off")

    # The launcher.
    box(ax, 2.2, 8.15, 10.6, 9.45, ORANGE,
        "./pbms run CONFIG   (bash launcher)\n"
        "install packages → build → coupler plan (validate) → mpirun → "
        "coupler postmortem → plot.py", fs=10)

    # The MPMD job.
    box(ax, 0.3, 0.3, 11.3, 7.45, "white", edge="0.35", lw=1.2, round_=0.2, z=0)
    ax.text(0.5, 7.2, "mpirun: ONE MPMD job.  MPI_COMM_WORLD is split by MPI_APPNUM; "
            "an allgather tells each app the others' roles;",
            fontsize=9.5, va="center", color="0.25", style="italic")
    ax.text(0.5, 6.92, "coupler ↔ each driver and driver ↔ driver: one intercommunicator "
            "per pair; Hello says who is who",
            fontsize=9.5, va="center", color="0.25", style="italic")
    arrow(ax, (6.4, 8.15), (6.4, 7.45))
    label(ax, 8.45, 7.8, "mpirun -np 1 coupler daemon : -np N md_driver [: …]", fs=8.5,
          style="italic")

    # Coupler.
    box(ax, 3.0, 5.4, 7.7, 6.6, BLUE,
        "coupler daemon\napp 0 · 1 rank\nruns the workflow, records the run",
        fs=10)

    # md_driver with its ranks.
    box(ax, 0.6, 0.65, 4.0, 3.75, GREEN, "md_driver  (LAMMPS library)\napp 1 · N ranks",
        fs=10, va="top", ty=3.6)
    for i, name in enumerate(("rank 0", "rank 1", "…", "rank N−1")):
        y = 2.55 - i * 0.45
        if name == "…":
            ax.text(2.3, y + 0.14, "⋮", ha="center", va="center", fontsize=12, zorder=3)
            continue
        box(ax, 1.2, y, 3.4, y + 0.34, "white", name, fs=8.5, lw=1.0, round_=0.06, z=2)
    ax.text(2.3, 0.85, "own communicator; LAMMPS\nwrites <stage>/*.in, *.log",
            ha="center", va="center", fontsize=8, color="0.3", zorder=3)

    # Future drivers.
    box(ax, 5.0, 0.65, 7.55, 3.75, GREY, "dpd_driver\napp 2 · M ranks\n(future)", dashed=True,
        fs=10, edge="0.45")
    box(ax, 8.3, 0.65, 10.85, 3.75, GREY, "mpm_driver\napp 3 · K ranks\n(future)", dashed=True,
        fs=10, edge="0.45")

    # coupler <-> md_driver: one intercommunicator, rank 0 speaks for the driver.
    arrow(ax, (1.6, 3.75), (3.25, 5.4))            # driver rank 0 -> coupler
    label(ax, 1.35, 4.6, "Hello\nProgress\nStageDone\n(rank 0)", fs=9, weight="bold")
    arrow(ax, (3.85, 5.4), (2.2, 3.75))            # coupler -> driver rank 0
    label(ax, 3.3, 4.3, "Welcome\nRunStage\nShutdown", fs=9, ha="left", weight="bold")
    arrow(ax, (3.4, 2.2), (4.95, 5.4), color=RED, rad=0.32)
    label(ax, 5.15, 4.55, "Fatal\n(any rank)", color=RED, fs=9, weight="bold")

    # coupler <-> future drivers: the same protocol.
    arrow(ax, (6.4, 5.4), (6.3, 3.75), color="0.5", dashed=True, both=True, lw=1.3)
    arrow(ax, (7.4, 5.4), (9.3, 3.75), color="0.5", dashed=True, both=True, lw=1.3)
    label(ax, 8.7, 4.75, "same messages", color="0.4", fs=8.5, style="italic")

    # driver <-> driver intercommunicators.
    arrow(ax, (7.55, 2.2), (8.3, 2.2), color="0.5", dashed=True, both=True, lw=1.3)
    label(ax, 7.92, 1.3, "rank-to-rank\ninterface\nexchange", color="0.35", fs=8, style="italic")
    arrow(ax, (4.0, 1.45), (5.0, 1.45), color="0.5", dashed=True, both=True, lw=1.3)

    # Run directory.
    box(ax, 11.75, 1.2, 14.75, 6.9, "#fffbe6",
        "run directory\n<output>/<name>/", fs=10, weight="bold", va="top", ty=6.75)
    files = ("config.yaml", "manifest.yaml", "log.txt", "summary.yaml", "results.h5",
             "mpirun.log", "<stage>/*.in, *.log", "*.png")
    notes = ("resolved input", "layout, current stage/step", "progress, results",
             "scalar results", "scalars + tables", "copied by launcher",
             "from md_driver (LAMMPS)", "from plot.py")
    for i, (f, n) in enumerate(zip(files, notes)):
        y = 5.95 - i * 0.6
        ax.text(11.95, y, f, fontsize=9, family="monospace", va="center", zorder=3)
        ax.text(11.95, y - 0.24, n, fontsize=7.5, color="0.35", va="center", zorder=3)
    arrow(ax, (7.7, 6.2), (11.75, 6.2))
    label(ax, 9.7, 6.2, "writes as it goes", fs=8.5, style="italic")
    arrow(ax, (10.6, 8.8), (13.25, 6.9), rad=-0.25)
    label(ax, 13.0, 8.3, "postmortem: who died, where\n(manifest.yaml + mpirun output)", fs=8.5,
          style="italic")

    # Legend.
    ax.text(0.35, 0.05, "solid: exists today   dashed: planned (DPD, MPM)   "
            "red: failure report → coupler records it in manifest.yaml and calls MPI_Abort",
            fontsize=8.5, color="0.3", va="bottom")

    fig.tight_layout(pad=0.3)
    fig.savefig(OUT, dpi=120)
    print(OUT)


def layers():
    """The source tree's layers: each may include those below it, never beside."""
    fig, ax = plt.subplots(figsize=(11, 6.2))
    ax.set_xlim(0, 11)
    ax.set_ylim(0, 6.2)
    ax.axis("off")
    box(ax, 0.3, 0.3, 10.7, 1.4, GREY,
        "core/   units · config schema and validation · protocol · MPMD · driver runtime ·\n"
        "geometry · HDF5/H5MD I/O · analysis (block averages, fits, cubic moduli, C_ij)", fs=9.5)
    box(ax, 0.3, 1.8, 10.7, 2.8, GREEN,
        "grid/   regular grid · partition · halo sums · shape functions · DDMP ·\n"
        "the phased MPM step (solver, points, boundary conditions, lanes) · material interface",
        fs=9.5)
    box(ax, 0.3, 3.2, 10.7, 4.1, BLUE,
        "coupling/   concurrent spec and typed parameters · body hand-over ·\n"
        "CouplingScheme · links across programs (nodal sums, ghosts, held nodes)", fs=9.5)
    drivers = (("md_driver/", "LAMMPS stages\nEAM material kinds"),
               ("dpd_driver/", "kernels · engine ·\nstages · properties"),
               ("mpm_driver/", "material models ·\nengine · stages"),
               ("coupler/", "daemon · scheduler ·\nrun record · fit/"))
    for i, (name, what) in enumerate(drivers):
        x0 = 0.3 + i * 2.65
        box(ax, x0, 4.5, x0 + 2.4, 5.9, ORANGE if name != "coupler/" else "#ede3f6",
            f"{name}\n{what}", fs=9.5)
    for x in (1.5, 4.15, 6.8, 9.45):
        arrow(ax, (x, 4.5), (x, 4.15))
    arrow(ax, (5.5, 3.2), (5.5, 2.85))
    arrow(ax, (5.5, 1.8), (5.5, 1.45))
    label(ax, 5.5, 6.08, "each box may include the ones below it; no driver includes another, "
          "the coupler includes no driver (ctest layers)", fs=9, style="italic")
    fig.tight_layout(pad=0.3)
    os.makedirs(os.path.dirname(LAYERS_OUT), exist_ok=True)
    fig.savefig(LAYERS_OUT, dpi=110)
    print(LAYERS_OUT)


if __name__ == "__main__":
    main()
    layers()
