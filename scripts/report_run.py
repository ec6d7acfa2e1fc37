"""Reads one run directory for the report page (report.py): the manifest,
summary, resolved config and results.h5, as far as they exist.

A run that is still going, or that failed, has partial files; a file that
cannot be read is noted in Run.problems and the rest is still read. Nothing
here raises on a bad run directory.

Also defines what the report calls a stage's headline results: at most three
numbers per stage kind, the ones the end of `./pbms run` prints; a headline
that is NaN, infinite or missing from a finished stage is a warning.
"""

import math
import os
from dataclasses import dataclass, field

# HDF5 1.10 locks the files it opens: a report reading an H5MD file that a
# driver is about to open for writing would make the driver fail. The
# report only reads, and never needs the lock.
os.environ.setdefault("HDF5_USE_FILE_LOCKING", "FALSE")

import yaml  # noqa: E402

# What each stage kind does, in one sentence for the page.
KIND_DESCRIPTIONS = {
    "md_isotherm": "NPT pressure–volume isotherm of the MD crystal (LAMMPS), with a third-order "
                   "Birch–Murnaghan fit: lattice parameter, bulk modulus B0 and its pressure "
                   "derivative B0'.",
    "md_elastic": "Cubic elastic constants C11, C12, C44 of the MD crystal (LAMMPS) from ± finite "
                  "strains, relaxed at 0 K and optionally averaged by NVT MD at a temperature.",
    "md_tension": "Uniaxial tension of an MD nanowire or periodic crystal (LAMMPS) at a constant "
                  "strain rate: Young's modulus from the stress–strain curve and the ultimate "
                  "stress.",
    "dpd_isotherm": "Pressure against volume of the periodic DPD crystal at a temperature: the "
                    "coarse-grained model's lattice constant and bulk modulus.",
    "dpd_elastic": "C11, C12, C44 of the periodic DPD crystal, static or at a temperature, and the "
                   "wave speeds they give.",
    "dpd_uniaxial_strain": "Stress of the DPD crystal compressed along [100] with its sides held, "
                           "and the weak-shock speeds of its Rayleigh lines.",
    "dpd_equilibrate": "DPD run with a Berendsen thermostat that brings the body to its "
                       "temperature, for a later stage to start from.",
    "dpd_run": "DPD or DPDE run of mesoparticles: free, an impact (wave speed) or a tension "
               "test (Young's modulus).",
    "mpm_run": "Explicit material point method run of continuum bodies on a background grid.",
    "fit_dpd_potential": "Fits the DPD pair potential's parameters so that the DPD crystal "
                         "reproduces the targets (isotherm, elastic constants, surface "
                         "energy); dpd_driver "
                         "judges every candidate.",
    "concurrent": "One body shared by two programs: some regions DPD particles (dpd_driver), "
                  "the rest continuum MPM points (mpm_driver), exchanging interface data every "
                  "step.",
}

# Programs a stage kind uses besides the one the manifest names.
PARTNER_PROGRAMS = {"concurrent": ["mpm_driver"], "fit_dpd_potential": ["dpd_driver"]}


@dataclass
class Result:
    value: object  # a float, or whatever summary.yaml held
    unit: str = ""
    error: float | None = None


@dataclass
class Stage:
    name: str
    kind: str = ""
    program: str = ""
    status: str = "pending"
    wall_s: float | None = None
    files: list = field(default_factory=list)
    results: dict = field(default_factory=dict)  # key -> Result, summary order
    config: dict = field(default_factory=dict)   # the stage's entry in config.yaml
    attrs: dict = field(default_factory=dict)    # results.h5 group attributes, as str
    tables: dict = field(default_factory=dict)   # name -> {column: (list, unit)}
    warnings: list = field(default_factory=list)  # the driver's own, from manifest.yaml
    baseline_of: str = ""  # a later stage that takes this one's noise (`noise_of`) as its baseline


@dataclass
class Run:
    dir: str
    name: str
    manifest: dict
    summary: dict
    config: dict
    stages: list
    problems: list  # files that exist but could not be read


# ---------------------------------------------------------------- reading

def load_yaml(path, problems):
    """The mapping in a YAML file, {} when it is missing or unreadable."""
    if not os.path.isfile(path):
        return {}
    try:
        with open(path, encoding="utf-8") as f:
            data = yaml.safe_load(f)
    except (OSError, yaml.YAMLError, ValueError) as e:
        problems.append(f"{os.path.basename(path)} could not be read: {e}")
        return {}
    return data if isinstance(data, dict) else {}


def as_float(value):
    try:
        return float(value)
    except (TypeError, ValueError):
        return None


def text(value):
    """An HDF5 attribute as str (h5py gives bytes for fixed-length strings)."""
    if isinstance(value, bytes):
        return value.decode("utf-8", "replace")
    if hasattr(value, "tolist"):
        value = value.tolist()
    if isinstance(value, bytes):
        return value.decode("utf-8", "replace")
    return str(value)


def parse_results(node):
    """summary.yaml's {key: {value, unit[, std_error]}} as Results; the
    `x_error` entries become the error of `x`."""
    results = {}
    if not isinstance(node, dict):
        return results
    for key, entry in node.items():
        if isinstance(entry, dict):
            results[str(key)] = Result(entry.get("value"), str(entry.get("unit", "") or ""),
                                       as_float(entry.get("std_error")))
        else:
            results[str(key)] = Result(entry)
    for key in list(results):
        base = key[:-len("_error")]
        if key.endswith("_error") and base in results and results[base].error is None:
            results[base].error = as_float(results[key].value)
    return results


def stage_entries(manifest, summary, config):
    """Every stage the run knows of, in order: the manifest's list (it holds
    pending stages too), then any only the config or summary names."""
    order, seen = [], set()

    def add(name):
        if name and name not in seen:
            seen.add(name)
            order.append(name)

    for s in manifest.get("stages") or []:
        if isinstance(s, dict):
            add(str(s.get("name", "")))
    for s in config.get("stages") or []:
        if isinstance(s, dict):
            add(str(s.get("name", "")))
    for name in (summary.get("stages") or {}) if isinstance(summary.get("stages"), dict) else {}:
        add(str(name))
    return order


def build_stage(name, manifest, summary, config):
    stage = Stage(name)
    for s in config.get("stages") or []:
        if isinstance(s, dict) and str(s.get("name")) == name:
            stage.config = s
            stage.kind = str(s.get("kind", ""))
    sums = summary.get("stages") if isinstance(summary.get("stages"), dict) else {}
    entry = sums.get(name) if isinstance(sums.get(name), dict) else {}
    if entry:
        stage.kind = str(entry.get("kind", stage.kind) or stage.kind)
        stage.status = str(entry.get("status", stage.status))
        stage.wall_s = as_float(entry.get("wall_s"))
        stage.results = parse_results(entry.get("results"))
    for s in manifest.get("stages") or []:
        if isinstance(s, dict) and str(s.get("name")) == name:
            stage.kind = str(s.get("kind", stage.kind) or stage.kind)
            stage.program = str(s.get("program", "") or "")
            stage.status = str(s.get("status", stage.status))
            stage.wall_s = as_float(s.get("wall_s")) if s.get("wall_s") is not None else stage.wall_s
            stage.files = [str(f) for f in s.get("files") or []]
            stage.warnings = [str(w) for w in s.get("warnings") or []]
    return stage


def read_h5_stage(group, stage, h5py):
    """Attributes of a stage's results.h5 group, and the fit tables the
    report shows (the other tables are plot.py's)."""
    stage.attrs = {k: text(v) for k, v in group.attrs.items()}
    if stage.kind != "fit_dpd_potential":
        return
    for tname in ("elastic", "isotherm"):
        t = group.get(tname)
        if not isinstance(t, h5py.Group):
            continue
        cols = {}
        for cname, ds in t.items():
            if isinstance(ds, h5py.Dataset) and ds.ndim == 1:
                cols[cname] = ([float(x) for x in ds[()]], text(ds.attrs.get("unit", "")))
        stage.tables[tname] = cols


def read_results_h5(run_dir, stages, problems):
    path = os.path.join(run_dir, "results.h5")
    if not os.path.isfile(path):
        return
    try:
        import h5py
        with h5py.File(path, "r") as f:
            for stage in stages:
                g = f.get(stage.name)
                if isinstance(g, h5py.Group):
                    read_h5_stage(g, stage, h5py)
    except Exception as e:  # noqa: BLE001 - a damaged file must not stop the page
        problems.append(f"results.h5 could not be read: {e}")


def read_run(run_dir):
    problems = []
    manifest = load_yaml(os.path.join(run_dir, "manifest.yaml"), problems)
    summary = load_yaml(os.path.join(run_dir, "summary.yaml"), problems)
    config = load_yaml(os.path.join(run_dir, "config.yaml"), problems)
    names = stage_entries(manifest, summary, config)
    stages = [build_stage(n, manifest, summary, config) for n in names]
    for st in stages:
        if isinstance(st.config, dict) and st.config.get("noise_of"):
            for base in stages:
                if base.name == st.config["noise_of"]:
                    base.baseline_of = st.name
    read_results_h5(run_dir, stages, problems)
    run_cfg = config.get("run") if isinstance(config.get("run"), dict) else {}
    name = str(summary.get("run") or run_cfg.get("name") or os.path.basename(os.path.abspath(run_dir)))
    return Run(run_dir, name, manifest, summary, config, stages, problems)


def run_status(run):
    """ok, failed or running (a manifest without a status is taken as running)."""
    return str(run.manifest.get("status") or ("running" if run.manifest else "unknown"))


def ranks_of(run, program):
    for item in run.manifest.get("layout") or []:
        if isinstance(item, dict) and item.get("program") == program:
            return item.get("ranks")
    return None


def stage_programs(run, stage):
    """'dpd_driver (1 rank) + mpm_driver (2 ranks)': the programs a stage runs on."""
    programs = [stage.program] if stage.program else []
    programs += [p for p in PARTNER_PROGRAMS.get(stage.kind, []) if p not in programs]
    parts = []
    for p in programs:
        n = ranks_of(run, p)
        parts.append(f"{p} ({n} rank{'s' if n != 1 else ''})" if n is not None else p)
    return " + ".join(parts)


# ---------------------------------------------------------------- headlines

def truthy_map(config, key):
    return isinstance(config.get(key), dict) and bool(config.get(key))


def wave_speed_keys(config):
    """wave_speed_<name> of the stage's wave.speeds (their names are the user's)."""
    wave = config.get("wave") if isinstance(config.get("wave"), dict) else {}
    speeds = wave.get("speeds") if isinstance(wave.get("speeds"), list) else []
    return [f"wave_speed_{s['name']}" for s in speeds if isinstance(s, dict) and s.get("name")]


# Headline keys per stage kind, for the kinds whose headlines do not depend
# on what the stage was configured to measure.
HEADLINES = {
    "md_isotherm": ["lattice_parameter", "bulk_modulus", "bulk_modulus_derivative"],
    "md_elastic": ["c11", "c12", "c44"],
    "md_tension": ["youngs_modulus", "ultimate_stress", "strain_at_ultimate"],
    "dpd_isotherm": ["lattice_constant", "bulk_modulus"],
    "dpd_elastic": ["c11", "c12", "c44"],
    "dpd_uniaxial_strain": ["lattice_constant", "density"],
    "dpd_equilibrate": ["temperature", "pressure", "energy_drift"],
    "fit_dpd_potential": ["objective", "max_residual_trained", "max_residual_held_out"],
}


def headline_keys(stage):
    """[(key, required)]: at most three results that matter most. A required
    key missing from a finished stage is a warning; an optional one is shown
    when present. dpd_run, mpm_run and concurrent measure what their config
    asks for (a tension, an impact, a wave front), so theirs follow it."""
    kind, cfg = stage.kind, stage.config
    if kind == "fit_dpd_potential":  # held-out rows only where an isotherm is a target
        return [("objective", True), ("max_residual_trained", True),
                ("max_residual_held_out", truthy_map(cfg, "isotherm"))]
    if kind in HEADLINES:
        return [(k, True) for k in HEADLINES[kind]]
    if kind in ("dpd_run", "mpm_run", "concurrent") and truthy_map(cfg, "tension"):
        last = "momentum_change" if kind == "concurrent" else "yield_stress"
        return [("youngs_modulus", True), ("max_stress", True), (last, kind == "concurrent")]
    if kind == "dpd_run" and stage.baseline_of:  # nothing strikes a baseline: no speeds
        return [("temperature", True), ("pressure", True), ("energy_drift", True)]
    if kind == "dpd_run" and truthy_map(cfg, "impact") and "baseline" in cfg["impact"]:
        return [("wave_speed", True), ("pulse_speed", True), ("baseline_residual", True)]
    if kind == "dpd_run" and truthy_map(cfg, "impact"):
        return [("wave_speed", True), ("mid_amplitude_speed", True), ("particle_velocity", True)]
    if kind == "dpd_run":
        return [("temperature", True), ("pressure", True), ("energy_drift", True)]
    if kind == "mpm_run" and truthy_map(cfg, "wave_front"):
        return [("wave_speed", True), ("exact_wave_speed", False), ("rms_from_exact", False)]
    if kind == "mpm_run" and cfg.get("period_of"):
        return [("period", True), ("energy_drift", False), ("energy_max_deviation", False)]
    if kind == "mpm_run":
        return [("energy_max_deviation", False), ("energy_drift", False), ("particles", True)]
    if kind == "concurrent" and stage.baseline_of:  # nothing strikes a baseline: no speeds
        return [("momentum_change", True), ("dpd_temperature", True)]
    if kind == "concurrent":
        speeds = wave_speed_keys(cfg)[:2]
        if speeds:
            return [(k, True) for k in speeds] + [("momentum_change", True)]
        return [("momentum_change", True), ("dpd_temperature", True),
                ("max_interface_opening", False)]
    # A kind this script does not know: its first three results, none required.
    return [(k, False) for k in list(stage.results)[:3]]


def is_bad_number(value):
    v = as_float(value)
    return v is None or not math.isfinite(v)


def config_warnings(run):
    """What validation found legal but suspicious, file:line:col first."""
    # Shown under a "warning" heading already: "file:line:col: key: message".
    return [str(w).replace(": warning: ", ": ", 1) for w in run.manifest.get("config_warnings") or []]


def headline_warnings(stage):
    """Warnings for a finished stage: the driver's own (a modulus fitted to a
    pull that barely started), and a headline that is NaN, infinite or missing."""
    if stage.status != "ok":
        return []
    out = []
    for key, required in headline_keys(stage):
        r = stage.results.get(key)
        if r is None:
            if required:
                why = stage.attrs.get(key)
                out.append(f"{key} is missing" + (f" ({why})" if why else ""))
        elif is_bad_number(r.value):
            out.append(f"{key} is {r.value}")
    return stage.warnings + out + fit_bound_warnings(stage)


def fit_parameters(stage):
    """[(name, fitted value, lower, upper)] of a fit stage's free parameters."""
    free = stage.config.get("free") if isinstance(stage.config.get("free"), dict) else {}
    out = []
    for name, bounds in free.items():
        lo = hi = None
        if isinstance(bounds, (list, tuple)) and len(bounds) == 2:
            lo, hi = as_float(bounds[0]), as_float(bounds[1])
        r = stage.results.get(str(name))
        out.append((str(name), as_float(r.value) if r else None, lo, hi))
    return out


def at_bound(value, lo, hi, log_scale=False):
    """Within 0.1 % of the range from a bound, the range the optimiser
    searched (the logarithm's with optimizer.scale: log): the optimum may
    lie beyond it."""
    if value is None or lo is None or hi is None or hi <= lo:
        return None
    if log_scale and lo > 0 and value > 0:
        value, lo, hi = math.log(value), math.log(lo), math.log(hi)
    tol = 1e-3 * (hi - lo)
    if value <= lo + tol:
        return "lower"
    if value >= hi - tol:
        return "upper"
    return None


def fit_bound_warnings(stage):
    if stage.kind != "fit_dpd_potential":
        return []
    out = []
    optimizer = stage.config.get("optimizer")
    log_scale = isinstance(optimizer, dict) and optimizer.get("scale") == "log"
    for name, value, lo, hi in fit_parameters(stage):
        side = at_bound(value, lo, hi, log_scale)
        if side:
            out.append(f"parameter {name} = {value:.6g} ended at its {side} bound "
                       f"[{lo:g}, {hi:g}]: the best fit may lie outside the bounds")
    return out
