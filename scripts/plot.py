#!/usr/bin/python3
"""Plot the tables of a PBMS run.

Usage: /usr/bin/python3 scripts/plot.py RUN_DIR      (or: ./pbms plot RUN_DIR)

Reads RUN_DIR/results.h5 and writes PNG files next to it, one per stage that
has curves (one per table for stage kinds this script does not know). Prints
the path of every PNG it writes. Exit status: 0 on success, also when there
is nothing to plot; 1 when results.h5 is missing or unreadable.

Layout of results.h5 (written by the coupler):
  /<stage>                 group, attrs kind, status, wall_s (+ driver attrs)
  /<stage>/<scalar>        scalar float dataset, attr unit (+ std_error)
  /<stage>/<table>/<col>   1-D float dataset, attr unit
Pressures are stored in bar (metal units); plots show GPa (1 GPa = 1e4 bar).
"""

import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

try:
    import h5py  # noqa: E402
except ImportError:  # pragma: no cover - the launcher installs python3-h5py
    sys.exit("plot.py: error: h5py is missing; install python3-h5py "
             "(and run this script with /usr/bin/python3)")

from concurrent_xdmf import write_concurrent_xdmf  # noqa: E402

DPI = 120
BAR_PER_GPA = 1.0e4


# ---------------------------------------------------------------- helpers

def text(value):
    """An HDF5 string attribute as str (h5py returns bytes for fixed-length strings)."""
    if isinstance(value, bytes):
        return value.decode("utf-8", "replace")
    if isinstance(value, np.ndarray) and value.shape == ():
        return text(value[()])
    return str(value)


def attr(obj, name, default=None):
    return text(obj.attrs[name]) if name in obj.attrs else default


def pretty_unit(unit):
    """'Å^3' -> 'Å³'; '1' (dimensionless) -> ''."""
    if unit is None or unit in ("", "1"):
        return ""
    sup = str.maketrans("0123456789-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")
    return re.sub(r"\^(-?\d+)", lambda m: m.group(1).translate(sup), unit)


def label(name, unit):
    u = pretty_unit(unit)
    return f"{name} ({u})" if u else name


def safe(name):
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", name)


class Table:
    """A table subgroup: columns as float arrays, with units."""

    def __init__(self, group):
        self.name = group.name.rsplit("/", 1)[-1]
        self.columns = {}
        self.units = {}
        for key, ds in group.items():
            if isinstance(ds, h5py.Dataset) and ds.ndim == 1:
                self.columns[key] = np.asarray(ds[()], dtype=float)
                self.units[key] = attr(ds, "unit", "")
        # h5py lists links in creation order when the file tracks it, else by name.
        self.order = list(self.columns)
        self.attrs = {k: text(v) for k, v in group.attrs.items()}

    def has(self, *names):
        return all(n in self.columns for n in names)

    def __getitem__(self, name):
        return self.columns[name]

    def get(self, name):
        return self.columns.get(name)


class Stage:
    def __init__(self, name, group):
        self.name = name
        self.kind = attr(group, "kind", "")
        self.status = attr(group, "status", "")
        self.attrs = {k: text(v) for k, v in group.attrs.items()}
        self.scalars = {}
        self.scalar_units = {}
        self.scalar_errors = {}
        self.tables = {}
        for key, obj in group.items():
            if isinstance(obj, h5py.Group):
                t = Table(obj)
                if t.columns:
                    self.tables[key] = t
            elif isinstance(obj, h5py.Dataset) and obj.shape == ():
                try:
                    self.scalars[key] = float(obj[()])
                except (TypeError, ValueError):
                    continue
                self.scalar_units[key] = attr(obj, "unit", "")
                if "std_error" in obj.attrs:
                    self.scalar_errors[key] = float(obj.attrs["std_error"])

    def scalar(self, key):
        return self.scalars.get(key)

    def float_attr(self, key):
        try:
            return float(self.attrs[key])
        except (KeyError, ValueError):
            return None


def finish(fig, path):
    fig.tight_layout()
    fig.savefig(path, dpi=DPI)
    plt.close(fig)
    print(path)
    return [path]


def errs(table, name, scale=1.0):
    e = table.get(name + "_std_error")
    if e is None or not np.all(np.isfinite(e)):
        return None
    return e * scale


def fmt_err(value, error):
    """3.63165 ± 0.00008: the value to the precision of its standard error."""
    if error is None or not np.isfinite(error) or error <= 0:
        return f"{value:.4g}"
    decimals = max(0, 1 - int(np.floor(np.log10(error))))
    if decimals > 8:
        return f"{value:.6g} ± {error:.1g}"
    return f"{value:.{decimals}f} ± {error:.{decimals}f}"


# ---------------------------------------------------------------- md_isotherm

def birch_murnaghan_pressure(ratio, b0, b0p):
    """Third-order Birch-Murnaghan P(V/V0), in the units of b0."""
    x = ratio ** (-2.0 / 3.0)  # (V0/V)^(2/3)
    return 1.5 * b0 * (x ** 3.5 - x ** 2.5) * (1.0 + 0.75 * (b0p - 4.0) * (x - 1.0))


def plot_isotherm(stage, outdir):
    t = stage.tables.get("isotherm")
    if t is None or not (t.has("pressure") and (t.has("volume_ratio") or t.has("volume_per_atom"))):
        return None  # not the expected layout: let the generic plot handle it
    b0 = stage.scalar("bulk_modulus")
    b0p = stage.scalar("bulk_modulus_derivative")
    v0 = stage.scalar("equilibrium_volume")
    p = t["pressure"] / BAR_PER_GPA
    p_err = errs(t, "pressure", 1.0 / BAR_PER_GPA)
    if t.has("volume_ratio"):
        ratio, ratio_err = t["volume_ratio"], errs(t, "volume_ratio")
    else:
        ratio = t["volume_per_atom"] / v0
        e = errs(t, "volume_per_atom")
        ratio_err = None if e is None else e / v0
    temp = t.get("temperature")
    md_label = "MD (NPT average)"
    if temp is not None and len(temp):
        md_label = f"MD, {np.mean(temp):.0f} K (NPT average)"

    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    ax.errorbar(p, ratio, xerr=p_err, yerr=ratio_err, fmt="o", ms=6, capsize=3,
                color="C0", label=md_label, zorder=3)
    if b0 is not None and b0p is not None and np.isfinite(b0) and np.isfinite(b0p):
        lo, hi = min(p.min(), 0.0), p.max()
        pad = 0.04 * (hi - lo if hi > lo else 1.0)
        r = np.linspace(0.5, 1.2, 4001)
        pr = birch_murnaghan_pressure(r, b0, b0p)
        keep = (pr >= lo - pad) & (pr <= hi + pad)
        if keep.any():
            ax.plot(pr[keep], r[keep], "-", color="C3", lw=1.6, zorder=2,
                    label=("3rd-order Birch–Murnaghan fit\n"
                           f"$B_0$ = {b0:.1f} GPa, $B_0'$ = {b0p:.2f}"))
    ax.set_xlabel("pressure P (GPa)")
    v0_text = f", $V_0$ = {v0:.4g} {pretty_unit(stage.scalar_units.get('equilibrium_volume', ''))}/atom" \
        if v0 is not None else ""
    ax.set_ylabel("V / V$_0$")
    ax.set_title(f"{stage.name}: pressure–volume isotherm{v0_text}")
    a0 = stage.scalar("lattice_parameter")
    if a0 is not None:
        unit = pretty_unit(stage.scalar_units.get("lattice_parameter", "Å"))
        where = ""
        if t.has("pressure_target") and len(t["pressure_target"]):
            where = f" at {np.min(t['pressure_target']) / BAR_PER_GPA:g} GPa"
        ax.text(0.97, 0.97, f"lattice parameter{where}:\na = {fmt_err(a0, stage.scalar_errors.get('lattice_parameter'))} {unit}",
                transform=ax.transAxes, ha="right", va="top", fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(loc="lower left", fontsize=9)
    return finish(fig, os.path.join(outdir, f"{safe(stage.name)}_isotherm.png"))


# ---------------------------------------------------------------- md_tension

def plot_tension(stage, outdir):
    t = stage.tables.get("stress_strain")
    if t is None or not t.has("strain", "stress"):
        return None
    strain, stress = t["strain"], t["stress"]
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    ax.plot(strain, stress, "o", ms=3, color="C0", label="MD", zorder=2)
    if t.has("stress_yy", "stress_zz"):  # a laterally periodic pull
        ax.plot(strain, 0.5 * (t["stress_yy"] + t["stress_zz"]), ".", ms=2, color="C2",
                label="lateral stress (yy + zz)/2", zorder=2)
    e = stage.scalar("youngs_modulus")
    fit_max = stage.float_attr("fit_max_strain")
    intercept = stage.float_attr("fit_intercept_gpa") or 0.0
    if e is not None and np.isfinite(e):
        x_max = fit_max if fit_max is not None else float(np.max(strain))
        # A periodic pull may start compressed: the fit starts at its first sample.
        x_min = min(stage.float_attr("fit_min_strain") or 0.0, 0.0)
        x = np.linspace(x_min, x_max, 50)
        ax.plot(x, e * x + intercept, "-", color="C3", lw=2, zorder=3,
                label=(f"linear fit, strain ≤ {x_max:g}\n"
                       f"E = {fmt_err(e, stage.scalar_errors.get('youngs_modulus'))} GPa"))
    ax.set_xlabel(label("strain", t.units.get("strain")))
    ax.set_ylabel(label("stress", t.units.get("stress", "GPa")))
    title = f"{stage.name}: stress–strain"
    temp = t.get("temperature")
    if temp is not None and len(temp):
        title += f" ({np.mean(temp):.0f} K)"
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend(loc="best", fontsize=9)
    return finish(fig, os.path.join(outdir, f"{safe(stage.name)}_stress_strain.png"))


# ---------------------------------------------------------------- md_elastic

def plot_elastic(stage, outdir):
    t = stage.tables.get("strains")
    if t is None or not t.has("mode", "strain", "stress_xx", "stress_yy", "stress_xy"):
        return None
    temps = t["temperature"] if t.has("temperature") else np.zeros_like(t["strain"])
    unit = t.units.get("stress_xx", "GPa")
    fig, (ax_n, ax_s) = plt.subplots(1, 2, figsize=(10.0, 4.4))
    markers = ["o", "s", "^", "D"]
    for i, temp in enumerate(np.unique(temps)):
        hot = temp > 0
        suffix = "_at_t" if hot else ""
        tag = f"{temp:.0f} K"
        fill = "none" if hot else None
        m = markers[i % len(markers)]
        sel = temps == temp
        normal = sel & (t["mode"] == 0)
        shear = sel & (t["mode"] == 1)
        e_n, e_s = t["strain"][normal], t["strain"][shear]
        span_n = max(np.max(np.abs(e_n)) if e_n.size else 0.0, 1e-12) * 1.25
        span_s = max(np.max(np.abs(e_s)) if e_s.size else 0.0, 1e-12) * 1.25
        x_n = np.array([-span_n, span_n])
        x_s = np.array([-span_s, span_s])
        ls = "--" if hot else "-"
        for col, const, color in (("stress_xx", "c11", "C0"), ("stress_yy", "c12", "C1")):
            ax_n.plot(e_n, t[col][normal], m, color=color, mfc=fill, ms=7,
                      label=f"$\\sigma_{{{col[-2:]}}}$, {tag}")
            c = stage.scalar(const + suffix)
            if c is not None:
                ax_n.plot(x_n, c * x_n, ls, color=color, lw=1.2,
                          label=f"slope $C_{{{const[1:]}}}$ = {c:.1f} GPa ({tag})")
        ax_s.plot(e_s, t["stress_xy"][shear], m, color="C2", mfc=fill, ms=7,
                  label=f"$\\sigma_{{xy}}$, {tag}")
        c = stage.scalar("c44" + suffix)
        if c is not None:
            ax_s.plot(x_s, c * x_s, ls, color="C2", lw=1.2,
                      label=f"slope $C_{{44}}$ = {c:.1f} GPa ({tag})")
    ax_n.set_xlabel(r"normal strain $\varepsilon_{xx}$")
    ax_n.set_ylabel(label("stress", unit))
    ax_n.set_title(f"{stage.name}: normal strain")
    ax_s.set_xlabel(r"engineering shear strain $\gamma_{xy}$")
    ax_s.set_ylabel(label("stress", unit))
    ax_s.set_title(f"{stage.name}: shear strain")
    for ax in (ax_n, ax_s):
        ax.axhline(0, color="0.6", lw=0.6)
        ax.axvline(0, color="0.6", lw=0.6)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="upper left")
    return finish(fig, os.path.join(outdir, f"{safe(stage.name)}_elastic.png"))


# ---------------------------------------------------------------- generic

# Columns that, when present, make the natural abscissa of a table.
PREFERRED_X = ("time", "step", "strain", "x", "position", "distance", "pressure_target",
               "pressure", "generation", "iteration")


def x_column(table):
    for key in ("x", "x_column", "abscissa"):
        if table.attrs.get(key) in table.columns:
            return table.attrs[key]
    for name in PREFERRED_X:
        if name in table.columns:
            return name
    return table.order[0]


def plot_generic(stage, outdir, skip=()):
    written = []
    for tname, t in stage.tables.items():
        if tname in skip:
            continue
        x_name = x_column(t)
        x = t[x_name]
        ys = [c for c in t.order
              if c != x_name and not (c.endswith("_std_error") and c[:-10] in t.columns)]
        ys = [c for c in ys if t[c].shape == x.shape]
        if not ys or x.size == 0:
            continue
        n = len(ys)
        ncols = 1 if n == 1 else 2
        nrows = (n + ncols - 1) // ncols
        fig, axes = plt.subplots(nrows, ncols, figsize=(5.2 * ncols, 3.2 * nrows + 0.5),
                                 sharex=True, squeeze=False)
        style = "o-" if x.size <= 50 else "-"
        for ax, col in zip(axes.flat, ys):
            err = errs(t, col)
            if err is not None and x.size <= 50:
                ax.errorbar(x, t[col], yerr=err, fmt=style, ms=4, capsize=2)
            else:
                ax.plot(x, t[col], style, ms=4)
                if err is not None:  # many points: the standard error as a band
                    ax.fill_between(x, t[col] - err, t[col] + err, alpha=0.25, lw=0)
            ax.set_ylabel(label(col, t.units.get(col)))
            ax.grid(alpha=0.3)
        for ax in axes.flat[n:]:
            ax.set_visible(False)
        for ax in axes[-1, :]:
            ax.set_xlabel(label(x_name, t.units.get(x_name)))
        if n % ncols and nrows > 1:  # the last row is short: label the axis above the gap
            axes[-2, -1].set_xlabel(label(x_name, t.units.get(x_name)))
            axes[-2, -1].xaxis.set_tick_params(labelbottom=True)
        fig.suptitle(f"{stage.name} ({stage.kind or 'unknown kind'}): {tname}")
        written += finish(fig, os.path.join(outdir, f"{safe(stage.name)}_{safe(tname)}.png"))
    return written


# ---------------------------------------------------------------- mpm_run

def plot_mpm_run(stage, outdir):
    """Energies of the probes table, the wave-front profile when present,
    and every other probe through the generic plot."""
    written = []
    p = stage.tables.get("probes")
    if p is not None and p.has("time", "energy.kinetic", "energy.internal", "energy.total"):
        t = p["time"]
        fig, ax = plt.subplots(figsize=(6.4, 4.0))
        for col, name in (("energy.kinetic", "kinetic"), ("energy.internal", "internal (stress work)"),
                          ("energy.stored", "strain (from stress)"), ("energy.total", "total")):
            if p.has(col):
                ax.plot(t, p[col], "-", label=name, lw=2 if col.endswith("total") else 1.2)
        ax.set_xlabel(label("time", p.units.get("time")))
        ax.set_ylabel(label("energy", p.units.get("energy.total")))
        drift = stage.scalar("energy_max_deviation")
        extra = f" (largest |ΔE|/E0 = {drift:.2%})" if drift is not None else ""
        ax.set_title(f"{stage.name}: energies{extra}")
        ax.grid(alpha=0.3)
        ax.legend()
        written += finish(fig, os.path.join(outdir, f"{safe(stage.name)}_energy.png"))
    prof = stage.tables.get("profile")
    if prof is not None and prof.has("x", "stress_xx", "exact_stress_xx"):
        order = np.argsort(prof["x"])
        fig, ax = plt.subplots(figsize=(7.0, 4.0))
        ax.plot(prof["x"][order], prof["stress_xx"][order], ".-", ms=3, lw=0.6,
                label=f"{stage.name} ({stage.attrs.get('gradient', '?')} gradients)")
        ax.plot(prof["x"][order], prof["exact_stress_xx"][order], "k-", lw=1.2, label="exact")
        ax.set_xlabel(label("x", prof.units.get("x")))
        ax.set_ylabel(label("stress_xx", prof.units.get("stress_xx")))
        ax.set_title(f"{stage.name}: stress profile at t = {stage.attrs.get('profile_time', '?')}")
        ax.grid(alpha=0.3)
        ax.legend()
        written += finish(fig, os.path.join(outdir, f"{safe(stage.name)}_profile.png"))
    written += plot_generic(stage, outdir, skip=("profile",))
    return written


def plot_profiles_together(stages, outdir):
    """All wave-front profiles of a run on one axis (plain MPM against DDMP)."""
    with_profile = [s for s in stages if s.kind == "mpm_run" and s.tables.get("profile") is not None]
    if len(with_profile) < 2:
        return []
    fig, ax = plt.subplots(figsize=(7.5, 4.2))
    exact = None
    for st in with_profile:
        prof = st.tables["profile"]
        order = np.argsort(prof["x"])
        rms = st.scalar("rms_from_exact")
        ax.plot(prof["x"][order], prof["stress_xx"][order], ".-", ms=2.5, lw=0.6,
                label=f"{st.name} ({st.attrs.get('gradient', '?')}), rms {rms:.4g}")
        exact = (prof["x"][order], prof["exact_stress_xx"][order])
    ax.plot(*exact, "k-", lw=1.2, label="exact")
    ax.set_xlabel(label("x", with_profile[0].tables["profile"].units.get("x")))
    ax.set_ylabel(label("stress_xx", with_profile[0].tables["profile"].units.get("stress_xx")))
    ax.set_title(f"stress profiles at t = {with_profile[0].attrs.get('profile_time', '?')}")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return finish(fig, os.path.join(outdir, "profiles.png"))


def plot_runs_together(stages, outdir):
    """Stages of one kind of analysis side by side (the DPD/MPM-grid model
    against DPD-only, an MPM rod against the DPD rod it was calibrated
    from): every tension curve on one axis, every impact's slab
    displacements on one axis."""
    written = []
    curves = [s for s in stages if s.tables.get("tension_curve") is not None]
    if len(curves) >= 2:
        fig, ax = plt.subplots(figsize=(6.5, 4.2))
        for st in curves:
            t = st.tables["tension_curve"]
            grid = st.attrs.get("grid_cell_size")
            if st.kind == "mpm_run":
                name = f"{st.name} (MPM)"
            elif st.kind == "concurrent":
                counts = (("DPD", "dpd_particles"), ("MPM", "mpm_points"))
                parts = "/".join(p for p, key in counts if (st.scalar(key) or 0) > 0)
                name = f"{st.name} ({parts}, interface {st.attrs.get('interface', '?')})"
            else:
                name = f"{st.name} (grid h = {grid} Å)" if grid else f"{st.name} (DPD-only)"
            line, = ax.plot(t["strain"], t["stress"], lw=1.0,
                            label=f"{name}, E = {st.scalar('youngs_modulus'):.2f} GPa")
            g = st.tables.get("gauge_curve")
            if g is not None:
                # The gauge's Cauchy stress against its own strain, dashed.
                ax.plot(g["strain"], g["stress"], lw=1.0, ls="--", color=line.get_color(),
                        label=f"{name} gauge, E = {st.scalar('gauge_youngs_modulus'):.2f} GPa")
        ax.set_xlabel(label("strain", curves[0].tables["tension_curve"].units.get("strain")))
        ax.set_ylabel(label("stress", curves[0].tables["tension_curve"].units.get("stress")))
        ax.set_title("tension curves (dashed: gauge)" if any(
            s.tables.get("gauge_curve") is not None for s in curves) else "tension curves")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        written += finish(fig, os.path.join(outdir, "tension_curves.png"))
    # Stages that timed a wave; a baseline (a body not struck) has no speed.
    impacts = [s for s in stages
               if s.tables.get("slabs") is not None and s.scalar("wave_speed") is not None]
    if len(impacts) >= 2:
        fig, ax = plt.subplots(figsize=(6.5, 4.2))
        for k, st in enumerate(impacts):
            t = st.tables["slabs"]
            grid = st.attrs.get("grid_cell_size")
            if st.kind == "mpm_run":
                name = f"{st.name} (MPM)"
            else:
                name = f"{st.name} (grid h = {grid} Å)" if grid else f"{st.name} (DPD-only)"
            c = f"C{k}"
            ax.plot(t["time"], t["near_displacement"], "-", color=c, lw=1.0,
                    label=f"{name}: near slab, c = {st.scalar('wave_speed'):.0f} m/s")
            ax.plot(t["time"], t["far_displacement"], "--", color=c, lw=1.0, label=f"{name}: far slab")
        ax.set_xlabel(label("time", t.units.get("time")))
        ax.set_ylabel(label("displacement", t.units.get("near_displacement")))
        ax.set_title("impact: slab displacements")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
        written += finish(fig, os.path.join(outdir, "impact_slabs_compared.png"))
    return written


def plot_inclusion(stages, outdir):
    """The seed's fig. 6.4: the volume ratio of a body held in a gas (each
    concurrent stage with a gas and a volume probe) against the gas pressure
    it reached, beside the bulk isotherms of the run (dpd_isotherm,
    md_isotherm) as V/V0 against P."""
    held = [s for s in stages if s.kind == "concurrent" and s.scalar("volume_ratio") is not None
            and s.scalar("gas_pressure") is not None]
    if not held:
        return []
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    for k, st in enumerate(s for s in stages if s.kind in ("dpd_isotherm", "md_isotherm")):
        t = st.tables.get("isotherm")
        if t is None or not (t.has("pressure") and t.has("volume_ratio")):
            continue
        scale = 1.0 if st.kind == "dpd_isotherm" else 1.0 / BAR_PER_GPA
        order = np.argsort(t["pressure"])
        what = "bulk DPD" if st.kind == "dpd_isotherm" else "bulk MD"
        ax.plot(t["pressure"][order] * scale, t["volume_ratio"][order], "s-" if k else "^-",
                ms=5, lw=1.0, label=f"{what} ({st.name})")
    p = [st.scalar("gas_pressure") for st in held]
    v = [st.scalar("volume_ratio") for st in held]
    ax.plot(p, v, "o", ms=7, color="C3", label="body in the gas (concurrent DPD/MPM)")
    for st, x, y in zip(held, p, v):
        ax.annotate(st.name, (x, y), fontsize=7, xytext=(4, 4), textcoords="offset points")
    ax.set_xlabel("pressure P (GPa)")
    ax.set_ylabel("V / V$_0$")
    ax.set_title("a body in a gas against the bulk isotherms (seed fig. 6.4)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return finish(fig, os.path.join(outdir, "volume_in_gas.png"))


def plot_necks(stages, outdir):
    """The seed's fig. 6.7: the neck `pair` of every stage that has one
    against time on one axis (DPD on the grid with and without gas, DPD
    alone, and MD)."""
    curves = [st for st in stages if "neck_pair" in st.tables]
    if not curves:
        return []
    fig, ax = plt.subplots(figsize=(6.8, 4.4))
    for st in curves:
        t = st.tables["neck_pair"]
        gas = st.scalar("gas_pressure_target")
        what = ("MD" if st.kind == "md_bodies" else "DPD alone" if st.kind != "concurrent"
                else "no gas" if gas is None else f"gas {gas:g} GPa")
        stable = st.scalar("neck_width_pair")
        ax.plot(t["time"], t["width"], lw=1.0, color="black" if st.kind == "md_bodies" else None,
                label=f"{st.name} ({what}): stable {stable:.1f} Å" if stable is not None
                else f"{st.name} ({what})")
    ax.set_xlabel("time (ps)")
    ax.set_ylabel("neck width (Å)")
    ax.set_title("neck between sintering bodies (seed fig. 6.7)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return finish(fig, os.path.join(outdir, "necks.png"))


def plot_assemblies(stages, outdir):
    """A sintering assembly (seed figs 6.8-6.16): each neck of the stage
    against time, and the rod's bend on a second axis."""
    written = []
    for st in stages:
        necks = sorted(n for n in st.tables if n.startswith("neck_") and n != "neck_pair")
        rods = sorted(n for n in st.tables if n.startswith("rod_"))
        if st.kind != "concurrent" or not (necks or rods):
            continue
        fig, ax = plt.subplots(figsize=(6.8, 4.4))
        for n in necks:
            t = st.tables[n]
            touch = st.scalar(f"contact_time_{n[len('neck_'):]}")
            ax.plot(t["time"], t["width"], lw=1.0,
                    label=f"{n[len('neck_'):]}" + (f" (touch {touch:g} ps)" if touch is not None else " (never touch)"))
        ax.set_xlabel("time (ps)")
        ax.set_ylabel("neck width (Å)")
        if rods:
            bend = ax.twinx()
            for r in rods:
                t = st.tables[r]
                bend.plot(t["time"], t["bend"], "k--", lw=1.0, label=f"{r[len('rod_'):]} bend")
            bend.set_ylabel("rod bend (Å)")
            bend.legend(fontsize=8, loc="lower right")
        gas = st.scalar("gas_pressure_target")
        ax.set_title(f"{st.name}" + (f", gas {gas:g} GPa" if gas is not None else ""))
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="upper left")
        written += finish(fig, os.path.join(outdir, f"{safe(st.name)}_necks.png"))
    return written


def plot_fit(stage, outdir):
    """fit_dpd_potential: the objective per evaluation, the fitted isotherm
    against its targets with residuals, and the elastic constants side by side."""
    written = []
    log = stage.tables.get("evaluation_log")
    if log is not None and log.has("evaluation", "objective", "status"):
        fig, ax = plt.subplots(figsize=(6.4, 4.0))
        n, obj, ok = log["evaluation"], log["objective"], log["status"] > 0.5
        local = log.get("phase")
        for phase, colour, name in ((0, "tab:blue", "global search"), (1, "tab:green", "local polish")):
            sel = ok & ((local == phase) if local is not None else True)
            ax.semilogy(n[sel], obj[sel], ".", ms=3, color=colour, label=name)
        if (~ok).any():
            ax.semilogy(n[~ok], obj[~ok], "x", color="tab:red", ms=4, label="failed (penalty)")
        best = np.minimum.accumulate(np.where(ok, obj, np.inf))
        ax.semilogy(n, best, "-", color="black", lw=1, label="best so far")
        ax.set_xlabel("evaluation")
        ax.set_ylabel("objective")
        ax.set_title(f"{stage.name}: objective per candidate")
        ax.legend(fontsize=8)
        written += finish(fig, os.path.join(outdir, f"{safe(stage.name)}_objective.png"))
    iso = stage.tables.get("isotherm")
    if iso is not None and iso.has("pressure", "volume_per_atom", "volume_per_atom_target", "residual"):
        p = iso["pressure"] / BAR_PER_GPA
        held = iso["held_out"] > 0.5 if iso.has("held_out") else np.zeros(len(p), bool)
        fig, (top, bottom) = plt.subplots(2, 1, figsize=(6.4, 6.0), sharex=True,
                                          gridspec_kw={"height_ratios": [2, 1]})
        top.plot(p, iso["volume_per_atom_target"], "o", mfc="none", color="black", label="target")
        top.plot(p, iso["volume_per_atom"], "s-", ms=4, color="tab:orange", label="fitted DPD")
        top.set_ylabel(label("volume per atom", "Å^3"))
        top.legend(fontsize=8)
        top.set_title(f"{stage.name}: isotherm")
        r = 100 * iso["residual"]
        bottom.axhline(0, color="grey", lw=0.8)
        bottom.plot(p[~held], r[~held], "o", color="tab:orange", label="trained")
        bottom.plot(p[held], r[held], "D", mfc="none", color="tab:purple", label="held out")
        bottom.set_xlabel("pressure (GPa)")
        bottom.set_ylabel("residual (%)")
        bottom.legend(fontsize=8)
        written += finish(fig, os.path.join(outdir, f"{safe(stage.name)}_isotherm.png"))
    el = stage.tables.get("elastic")
    if el is not None and el.has("target", "fitted"):
        fig, ax = plt.subplots(figsize=(5.0, 3.8))
        x = np.arange(len(el["target"]))
        names = [f"C{int(i)}" for i in el["index"]] if el.has("index") else [str(i) for i in x]
        ax.bar(x - 0.2, el["target"], 0.4, label="target", color="grey")
        err = el.get("fitted_std_error")
        ax.bar(x + 0.2, el["fitted"], 0.4, yerr=err, label="fitted DPD", color="tab:orange")
        ax.set_xticks(x, names)
        ax.set_ylabel("GPa")
        ax.set_title(f"{stage.name}: elastic constants")
        ax.legend(fontsize=8)
        written += finish(fig, os.path.join(outdir, f"{safe(stage.name)}_elastic.png"))
    return written


def plot_concurrent(stage, outdir):
    """concurrent: each part's displacement profile along the wave at
    several times (seed fig 5.9), DPD solid and MPM dashed in one colour per
    time; the slabs of both parts; the interface opening."""
    written = []
    dpd, mpm = stage.tables.get("dpd_profiles"), stage.tables.get("mpm_profiles")
    if dpd is not None or mpm is not None:
        fig, ax = plt.subplots(figsize=(7.5, 4.2))
        times = [c for c in (dpd or mpm).order if c.startswith("t=")]
        for k, t in enumerate(times):
            for table, style, part in ((dpd, "-", "DPD"), (mpm, "--", "MPM")):
                if table is None or t not in table.columns:
                    continue
                colour = plt.cm.viridis(k / max(1, len(times) - 1))
                ax.plot(table["position"], table[t], style, color=colour, lw=1.0,
                        label=f"{t} ps" if part == "DPD" or dpd is None else None)
        ax.set_xlabel(label("initial position", "Å"))
        ax.set_ylabel(label("displacement", "Å"))
        ax.set_title(f"{stage.name}: displacement profiles (DPD solid, MPM dashed)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, ncol=2)
        written += finish(fig, os.path.join(outdir, f"{safe(stage.name)}_profiles.png"))
    slabs = [(stage.tables.get(n), n) for n in ("dpd_slabs", "mpm_slabs")]
    opening = stage.tables.get("interface")
    if any(t is not None for t, _ in slabs) or opening is not None:
        fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 3.8))
        for t, name in slabs:
            if t is None:
                continue
            for col in t.order:
                if col != "time":
                    a1.plot(t["time"], t[col], lw=1.0, label=f"{col} ({name.split('_')[0]})")
        a1.set_xlabel(label("time", "ps"))
        a1.set_ylabel(label("slab displacement", "Å"))
        a1.grid(alpha=0.3)
        a1.legend(fontsize=7)
        if opening is not None:
            a2.plot(opening["time"], opening["opening"] - opening["opening"][0], "k-", lw=1.0)
        a2.set_xlabel(label("time", "ps"))
        a2.set_ylabel(label("interface opening", "Å"))
        a2.set_title(f"interface: {stage.attrs.get('interface', '')}")
        a2.grid(alpha=0.3)
        written += finish(fig, os.path.join(outdir, f"{safe(stage.name)}_slabs.png"))
    dl, ml = stage.tables.get("dpd_ledger"), stage.tables.get("mpm_ledger")
    if dl is not None and ml is not None and dl.has("time", "kinetic_energy"):
        fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 3.8))
        t = dl["time"]
        total = np.zeros_like(t)
        parts = [(dl, "kinetic_energy", "DPD kinetic"), (dl, "potential_energy", "DPD potential"),
                 (dl, "interface_pair_energy", "DPD-MPM interface pairs"),
                 (dl, "internal_energy", "DPD internal"),
                 (ml, "kinetic_energy", "MPM kinetic"), (ml, "stored_energy", "MPM stored"),
                 (ml, "dissipated_energy", "MPM dissipated")]
        for table, col, name in parts:
            if col in table.columns and len(table[col]) == len(t):
                e = table[col] - table[col][0]
                total = total + e
                a1.plot(t, e, lw=1.0, label=name)
        a1.plot(t, total, "k-", lw=1.2, label="sum")
        a1.set_xlabel(label("time", "ps"))
        a1.set_ylabel(label("energy change", "eV"))
        a1.grid(alpha=0.3)
        a1.legend(fontsize=7)
        for axis in "xyz":
            col = f"momentum_{axis}"
            if col in dl.columns and col in ml.columns and len(ml[col]) == len(t):
                a2.plot(t, dl[col] + ml[col], lw=1.0, label=f"total {axis}")
        a2.set_xlabel(label("time", "ps"))
        a2.set_ylabel(label("momentum", "g/mol Å/ps"))
        if "mass" in dl.columns and "mass" in ml.columns and len(ml["mass"]) == len(t):
            m = dl["mass"] + ml["mass"]
            a2.set_title(f"total mass {m[0]:.6g} g/mol, largest change {np.max(np.abs(m - m[0])):.3g}",
                         fontsize=9)
        a2.grid(alpha=0.3)
        a2.legend(fontsize=7)
        written += finish(fig, os.path.join(outdir, f"{safe(stage.name)}_ledger.png"))
    return written


def last_positions(path):
    """The last frame of an H5MD file's positions (N x 3) and its step, or None."""
    if not os.path.isfile(path):
        return None
    with h5py.File(path, "r") as f:
        pos = f.get("particles/all/position")
        if pos is None or pos["value"].shape[0] == 0:
            return None
        return pos["value"][-1], int(pos["step"][-1])


def plot_concurrent_snapshots(stages, outdir):
    """The last particle frame of every concurrent stage that wrote one, side
    view along the pulled axis, DPD particles and MPM points in two colours,
    one panel per stage (seed fig 5.11: the rod all DPD, with and without
    the interface treatment)."""
    rows = []
    for st in stages:
        if st.kind != "concurrent":
            continue
        parts = [(last_positions(os.path.join(outdir, st.name, f"{p}_particles.h5md")), p)
                 for p in ("dpd", "mpm")]
        parts = [(frame, p) for frame, p in parts if frame is not None and len(frame[0])]
        if parts:
            rows.append((st, parts))
    if not rows:
        return []
    fig, axes = plt.subplots(len(rows), 1, figsize=(9.0, 1.6 + 1.3 * len(rows)), squeeze=False,
                             sharex=True)
    colours = {"dpd": "tab:green", "mpm": "tab:blue"}
    for ax, (st, parts) in zip(axes[:, 0], rows):
        step = None
        for (x, s), part in parts:
            # A side view: every particle projected on the x-z plane.
            ax.plot(x[:, 0], x[:, 2], ".", ms=0.8, color=colours[part], label=part.upper())
            step = s
        ax.set_aspect("equal")
        ax.set_ylabel(label("z", "Å"))
        ax.set_title(f"{st.name} ({st.attrs.get('interface', '')}), step {step}", fontsize=9)
        ax.legend(fontsize=7, markerscale=8, loc="upper right")
    axes[-1, 0].set_xlabel(label("x", "Å"))
    return finish(fig, os.path.join(outdir, "concurrent_snapshots.png"))


PLOTTERS = {
    "concurrent": plot_concurrent,
    "mpm_run": plot_mpm_run,
    "md_isotherm": plot_isotherm,
    "md_tension": plot_tension,
    "md_elastic": plot_elastic,
    "fit_dpd_potential": plot_fit,
}


# ---------------------------------------------------------------- main

def main(argv):
    if len(argv) != 2 or argv[1] in ("-h", "--help"):
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 0 if len(argv) == 2 else 1
    run_dir = argv[1]
    path = os.path.join(run_dir, "results.h5")
    if not os.path.isfile(path):
        print(f"plot.py: error: {path} not found (is '{run_dir}' a run directory "
              f"of a finished ./pbms run?)", file=sys.stderr)
        return 1
    try:
        f = h5py.File(path, "r")
    except OSError as e:
        print(f"plot.py: error: cannot read {path}: {e}", file=sys.stderr)
        return 1

    written = []
    finished = []
    with f:
        for name, group in f.items():
            if not isinstance(group, h5py.Group):
                continue
            stage = Stage(name, group)
            if stage.status and stage.status != "ok":
                print(f"plot.py: skipping stage '{name}' (status: {stage.status})",
                      file=sys.stderr)
                continue
            if not stage.tables:
                continue
            finished.append(stage)
            plotter = PLOTTERS.get(stage.kind)
            result = plotter(stage, run_dir) if plotter else None
            if result is None:
                result = plot_generic(stage, run_dir)
            written += result
        written += plot_profiles_together(finished, run_dir)
        written += plot_runs_together(finished, run_dir)
        written += plot_concurrent_snapshots(finished, run_dir)
        written += plot_inclusion(finished, run_dir)
        written += plot_necks(finished, run_dir)
        written += plot_assemblies(finished, run_dir)
        for stage in finished:
            if stage.kind == "concurrent":
                # Not a plot, but derived from the run's files as the plots are.
                xdmf = write_concurrent_xdmf(os.path.join(run_dir, stage.name))
                if xdmf:
                    print(f"plot.py: {xdmf} opens both parts and the grid "
                          "(ParaView's XDMF Reader)")
    if not written:
        print(f"plot.py: nothing to plot in {path} (no finished stage with tables)",
              file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
