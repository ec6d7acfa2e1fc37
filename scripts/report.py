#!/usr/bin/python3
"""Write a run's report page, RUN_DIR/report.html.

Usage: /usr/bin/python3 scripts/report.py [--last-lines | --quiet] [--run-id ID] RUN_DIR
       (or: ./pbms report RUN_DIR)

The page is one self-contained HTML file: the plots are inline (base64 data
URIs), there is no script or style from elsewhere, so it opens from disk
without a server or network, and can be mailed or copied alone. It shows
the run (status, command, host, git hash, layout), the failure of a failed
run, each stage (what it does, its key numbers with units and error bars,
its plots, wall time and ranks; a fit's targets against its fitted values;
pictures of a concurrent stage's body at a few times), warnings (a
headline result that is NaN, infinite or missing), and every file with the
reader to open it in. Stages that have not run yet are shown as pending: the
launcher rewrites the page while the job runs.

The pictures of a concurrent body are also written beside the page, as
RUN_DIR/<stage>_body.png, and reused while newer than the H5MD files.

  --last-lines  after writing, print the page's path and, per stage, the
                numbers that matter most, and the warnings (the end of
                `./pbms run`)
  --quiet       print nothing (the launcher's rewrite while the job runs)
  --run-id ID   write only if RUN_DIR/manifest.yaml is that job's (run_id):
                the launcher never rewrites another run's page

Exit status 0 when the page was written (or skipped for --run-id), 1 when
RUN_DIR is not a run directory or the page could not be written.
"""

import argparse
import base64
import datetime
import html
import math
import os
import signal
import sys
import time
import urllib.parse

import report_run as rr

# ---------------------------------------------------------------- formatting

SUPERSCRIPTS = str.maketrans("0123456789-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")
BAR_PER_GPA = 1.0e4
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
# Plots plot.py draws for the whole run, not one stage (their names may
# begin with a stage's name: a stage called "tension" and tension_curves.png).
RUN_LEVEL_PNGS = {"concurrent_snapshots.png", "profiles.png", "tension_curves.png",
                  "impact_slabs_compared.png"}
# Failures of single candidates of a fit, stored as attributes; counted, not listed.
FIT_FAILURE_ATTR = ("evaluation_", "_failure")


def esc(value):
    return html.escape(str(value), quote=True)


def pretty_unit(unit):
    """'Å^3' -> 'Å³'; '1' (dimensionless) -> ''."""
    unit = str(unit or "")
    if unit in ("", "1"):
        return ""
    out, i = [], 0
    while i < len(unit):
        if unit[i] == "^":
            j = i + 1
            while j < len(unit) and (unit[j].isdigit() or (unit[j] == "-" and j == i + 1)):
                j += 1
            out.append(unit[i + 1:j].translate(SUPERSCRIPTS))
            i = j
        else:
            out.append(unit[i])
            i += 1
    return "".join(out)


def fmt_number(value, error=None):
    """A value to the precision of its standard error: 3.6316 ± 0.0008."""
    v = rr.as_float(value)
    if v is None:
        return "missing" if value is None else str(value)
    if math.isnan(v):
        return "NaN"
    if math.isinf(v):
        return "∞" if v > 0 else "−∞"
    e = rr.as_float(error)
    if e is not None and math.isfinite(e) and e > 0:
        decimals = max(0, 1 - math.floor(math.log10(e)))
        if decimals <= 6 and abs(v) < 1e9:
            return f"{v:.{decimals}f} ± {e:.{decimals}f}"
        return f"{v:.6g} ± {e:.2g}"
    if v == int(v) and abs(v) < 1e6:
        return str(int(v))
    return f"{v:.6g}"


def fmt_result(result):
    unit = pretty_unit(result.unit)
    return fmt_number(result.value, result.error) + (f" {unit}" if unit else "")


def fmt_wall(seconds):
    if seconds is None:
        return ""
    if seconds < 60:
        return f"{seconds:.3g} s"
    if seconds < 3600:
        return f"{int(seconds // 60)} min {seconds % 60:.0f} s"
    return f"{int(seconds // 3600)} h {int(seconds % 3600 // 60):02d} min"


def fmt_size(n):
    for unit in ("B", "KB", "MB", "GB"):
        if n < 1024 or unit == "GB":
            return f"{n:.0f} {unit}" if unit == "B" else f"{n:.1f} {unit}"
        n /= 1024.0
    return ""


def link(relpath, label=None):
    href = urllib.parse.quote(relpath.replace(os.sep, "/"))
    return f'<a href="{esc(href)}">{esc(label or relpath)}</a>'


def table(headers, rows, cls=""):
    """An HTML table; cells are HTML already."""
    head = "".join(f"<th>{esc(h)}</th>" for h in headers)
    body = "".join("<tr>" + "".join(f"<td>{c}</td>" for c in r) + "</tr>" for r in rows)
    return f'<table class="{cls}"><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>'


# ---------------------------------------------------------------- statuses

def shown_status(run, stage):
    """A stage left 'running' by a job that has ended did not finish: 'stopped'."""
    if stage.status == "running" and rr.run_status(run) in ("ok", "failed", "stopped"):
        return "stopped"
    return stage.status


def badge(status):
    return f'<span class="badge s-{esc(status)}">{esc(status)}</span>'


def failure_text(failure, with_stage=True):
    """'dpd_driver rank 0, stage 'impact', step 1: message' from the manifest's failure."""
    if not isinstance(failure, dict):
        return "no failure was recorded; see log.txt"
    where = []
    if failure.get("program"):
        rank = f" rank {failure['rank']}" if failure.get("rank") is not None else ""
        where.append(f"{failure['program']}{rank}")
    if failure.get("stage") and with_stage:
        where.append(f"stage '{failure['stage']}'")
    if failure.get("step") is not None:
        where.append(f"step {failure['step']}")
    msg = str(failure.get("message") or "no message")
    return (", ".join(where) + ": " if where else "") + msg


def progress_text(run, stage):
    cur = run.manifest.get("current")
    if not isinstance(cur, dict) or str(cur.get("stage")) != stage.name:
        return ""
    step, total = cur.get("step"), cur.get("total_steps")
    text = f"step {step}"
    if rr.as_float(total):
        text += f" of {total} ({100.0 * float(step or 0) / float(total):.0f} %)"
    if cur.get("sim_time_ps") is not None:
        text += f", {rr.as_float(cur['sim_time_ps']):.4g} ps simulated"
    return text


# ---------------------------------------------------------------- images

def png_is_whole(path):
    """True for a complete PNG file (signature, and IEND at the end): a plot
    being written while the page is built would show as a broken image."""
    try:
        with open(path, "rb") as f:
            head = f.read(8)
            f.seek(max(0, os.path.getsize(path) - 12))
            tail = f.read()
    except OSError:
        return False
    return head == PNG_SIGNATURE and b"IEND" in tail


def png_width(data):
    """The width in pixels from a PNG's IHDR chunk."""
    return int.from_bytes(data[16:20], "big") if len(data) >= 24 else 0


def img_tag(run_dir, name, caption):
    """An inline <figure> of RUN_DIR/name, or '' when it is not a whole PNG.
    Shown at 80 % of its pixel width: two plots of plot.py's usual width side
    by side, a wide one alone and still legible."""
    path = os.path.join(run_dir, name)
    if not png_is_whole(path):
        return ""
    with open(path, "rb") as f:
        raw = f.read()
    data = base64.b64encode(raw).decode("ascii")
    width = round(0.8 * png_width(raw))
    style = f' style="width:{width}px"' if width > 0 else ""
    return (f'<figure{style}><img src="data:image/png;base64,{data}" alt="{esc(name)}">'
            f'<figcaption>{caption or ""} {link(name, name)}</figcaption></figure>')


def png_owners(run):
    """{stage name or '': [png names]}: each PNG of the run directory goes to
    the stage with the longest name it begins with (<stage>_*.png)."""
    names = sorted(listdir(run.dir))
    stages = sorted((s.name for s in run.stages), key=len, reverse=True)
    owners = {}
    for n in names:
        if not n.endswith(".png"):
            continue
        owner = "" if n in RUN_LEVEL_PNGS else next(
            (s for s in stages if n.startswith(s + "_")), "")
        owners.setdefault(owner, []).append(n)
    return owners


def listdir(path):
    """The names in a directory; none when it cannot be read."""
    try:
        return os.listdir(path)
    except OSError:
        return []


# ---------------------------------------------------------------- body pictures

def body_png_name(stage):
    return f"{stage.name}_body.png"


def body_is_current(run_dir, stage):
    """The body picture exists and is newer than its H5MD files and this code."""
    png = os.path.join(run_dir, body_png_name(stage))
    if not png_is_whole(png):
        return False
    sources = [os.path.join(run_dir, stage.name, f"{p}_particles.h5md") for p in ("dpd", "mpm")]
    sources += [os.path.join(os.path.dirname(os.path.abspath(__file__)), "report_body.py")]
    newest = max((os.path.getmtime(s) for s in sources if os.path.exists(s)), default=0)
    return os.path.getmtime(png) >= newest


def render_body(run, stage):
    """Writes RUN_DIR/<stage>_body.png when it is out of date; returns None,
    or why there is no picture."""
    if shown_status(run, stage) not in ("ok", "failed", "stopped"):
        return "the pictures are drawn when the stage has ended"
    if body_is_current(run.dir, stage):
        return None
    out = os.path.join(run.dir, body_png_name(stage))
    tmp = os.path.join(run.dir, f".{body_png_name(stage)}.{os.getpid()}.partial.png")
    interface = stage.attrs.get("interface")
    title = f"stage '{stage.name}'" + (f" ({interface} interface)" if interface else "")
    try:
        import report_body
        why = report_body.render_body(os.path.join(run.dir, stage.name), tmp, title, stage.config)
        if why is None:
            os.replace(tmp, out)
        return why
    except Exception as e:  # noqa: BLE001 - a damaged or half-written file: no picture
        return f"could not draw the body: {type(e).__name__}: {e}"
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


# ---------------------------------------------------------------- sections

def code(value):
    return f"<code>{esc(value)}</code>" if str(value).strip() else ""


def facts_table(rows):
    return table(["", ""], [(f"<b>{esc(k)}</b>", v) for k, v in rows if v], "facts")


def layout_text(run):
    items = []
    for item in run.manifest.get("layout") or []:
        if isinstance(item, dict):
            n = item.get("ranks")
            items.append(f"{item.get('program')} × {n}")
    return ", ".join(items)


def duration_text(manifest):
    try:
        start = datetime.datetime.strptime(str(manifest["started"]), "%Y-%m-%dT%H:%M:%S%z")
        end = datetime.datetime.strptime(str(manifest["finished"]), "%Y-%m-%dT%H:%M:%S%z")
    except (KeyError, ValueError):
        return ""
    return fmt_wall((end - start).total_seconds())


def header_section(run, all_warnings):
    m = run.manifest
    status = rr.run_status(run)
    parts = [f"<h1>Run <code>{esc(run.name)}</code> {badge(status)}</h1>"]
    if status in ("failed", "stopped"):
        parts.append(failure_box(run))
    if status == "running":
        parts.append(running_box(run))
    if all_warnings:
        items = "".join(f'<li><a href="#stage-{esc(s)}">{esc(s)}</a>: {esc(w)}</li>' if s else
                        f"<li>{esc(w)}</li>" for s, w in all_warnings)
        parts.append(f'<div class="box warn"><b>Warnings ({len(all_warnings)})</b><ul>{items}</ul></div>')
    software = m.get("software") if isinstance(m.get("software"), dict) else {}
    parts.append(facts_table([
        ("started", esc(m.get("started", ""))),
        ("finished", esc(m.get("finished", "")) + (f" ({duration_text(m)})" if duration_text(m) else "")),
        ("command", code(str(m.get("command", "")).strip())),
        ("config", esc(m.get("config", ""))),
        ("host", esc(m.get("host", ""))),
        ("git hash", code(m.get("git_hash", ""))),
        ("PBMS version", esc(m.get("pbms_version", ""))),
        ("layout (program × ranks)", esc(layout_text(run))),
        ("software", esc(", ".join(f"{k} {v}" for k, v in software.items()))),
        ("run directory", code(os.path.abspath(run.dir))),
    ]))
    return "\n".join(parts)


def failure_box(run):
    failure = run.manifest.get("failure")
    failed = [s.name for s in run.stages if s.status == "failed"]
    where = f" in stage <a href=\"#stage-{esc(failed[0])}\">{esc(failed[0])}</a>" if failed else ""
    tail = log_tail(run.dir)
    tail_html = f"<details open><summary>last lines of log.txt</summary><pre>{esc(tail)}</pre></details>" \
        if tail else ""
    return (f'<div class="box fail"><b>The run failed{where}.</b>'
            f"<p>{esc(failure_text(failure))}</p>{tail_html}</div>")


def log_tail(run_dir, lines=12):
    try:
        with open(os.path.join(run_dir, "log.txt"), encoding="utf-8", errors="replace") as f:
            return "".join(f.readlines()[-lines:])
    except OSError:
        return ""


def running_box(run):
    cur = run.manifest.get("current") if isinstance(run.manifest.get("current"), dict) else {}
    stage = cur.get("stage")
    now = f"Now in stage <a href=\"#stage-{esc(stage)}\">{esc(stage)}</a>. " if stage else ""
    return (f'<div class="box run"><b>The job is running.</b> {now}'
            "The launcher rewrites this page when a stage ends (about every 10 s); it reloads "
            f"itself every 20 s. Written at {esc(time.strftime('%H:%M:%S'))}.</div>")


def overview_section(run):
    rows = []
    for s in run.stages:
        heads = "; ".join(f"{esc(k)} = {esc(fmt_result(s.results[k]))}"
                          for k, _ in rr.headline_keys(s) if k in s.results)
        rows.append((f'<a href="#stage-{esc(s.name)}">{esc(s.name)}</a>', esc(s.kind),
                     badge(shown_status(run, s)), esc(fmt_wall(s.wall_s)),
                     esc(rr.stage_programs(run, s)), heads))
    return "<h2>Stages</h2>" + table(["stage", "kind", "status", "wall time", "ranks", "key results"],
                                     rows, "overview")


def headline_cards(stage):
    cards = []
    for key, _ in rr.headline_keys(stage):
        r = stage.results.get(key)
        value = fmt_result(r) if r else "missing"
        bad = " bad" if r is None or rr.is_bad_number(r.value) else ""
        cards.append(f'<div class="card{bad}"><div class="k">{esc(key)}</div>'
                     f'<div class="v">{esc(value)}</div></div>')
    return f'<div class="cards">{"".join(cards)}</div>' if cards else ""


def results_details(stage):
    """Every result of the stage (x_error folded into x) in a collapsed table."""
    rows = []
    for key, r in stage.results.items():
        if key.endswith("_error") and key[:-6] in stage.results:
            continue
        cls = ' class="bad"' if rr.is_bad_number(r.value) else ""
        rows.append((esc(key), f"<span{cls}>{esc(fmt_number(r.value, r.error))}</span>",
                     esc(pretty_unit(r.unit))))
    if not rows:
        return ""
    return (f"<details><summary>all results ({len(rows)})</summary>"
            f"{table(['key', 'value', 'unit'], rows, 'results')}</details>")


def notes_details(stage):
    """The stage's text attributes in results.h5 (why a value was not measured,
    the interface, ...); a fit's failed candidates counted."""
    skip = {"kind", "status", "wall_s", "potential"}
    notes, failures = [], []
    for k, v in stage.attrs.items():
        if k.startswith(FIT_FAILURE_ATTR[0]) and k.endswith(FIT_FAILURE_ATTR[1]):
            failures.append(v)
        elif k not in skip:
            notes.append((esc(k), esc(v)))
    if failures:
        reasons = sorted(set(failures))
        notes.append(("failed candidates", esc(f"{len(failures)}; " + " | ".join(reasons[:3]))))
    return facts_table(notes) if notes else ""


def stage_files_inline(run, stage):
    files = stage_files(run, stage)
    if not files:
        return ""
    return "<p class=\"files\">Files: " + ", ".join(link(f) for f in files) + \
        ' (readers: <a href="#files">Files</a>)</p>'


def stage_section(run, stage, pngs):
    status = shown_status(run, stage)
    desc = rr.KIND_DESCRIPTIONS.get(stage.kind, "")
    parts = [f'<section class="stage" id="stage-{esc(stage.name)}">',
             f"<h2>{esc(stage.name)} {badge(status)}</h2>",
             f'<p class="what"><b>{esc(stage.kind or "unknown kind")}</b>: {esc(desc)}</p>',
             facts_table([("wall time", esc(fmt_wall(stage.wall_s))),
                          ("ranks", esc(rr.stage_programs(run, stage))),
                          ("progress", esc(progress_text(run, stage)) if status == "running" else "")])]
    parts.append(stage_state_box(run, stage, status))
    warnings = rr.headline_warnings(stage)
    if warnings:
        parts.append('<div class="box warn">' + "<br>".join(esc(w) for w in warnings) + "</div>")
    if stage.results:
        parts.append(headline_cards(stage))
    parts.append(safe_part(fit_section, stage))
    if stage.kind == "concurrent":
        parts.append(safe_part(body_section, run, stage))
    parts.append(plots_block(run, pngs, skip={body_png_name(stage)}))
    parts += [results_details(stage), notes_details(stage), stage_files_inline(run, stage),
              "</section>"]
    return "\n".join(p for p in parts if p)


def stage_state_box(run, stage, status):
    if status == "failed":
        failure = run.manifest.get("failure")
        mine = isinstance(failure, dict) and str(failure.get("stage")) == stage.name
        text = failure_text(failure, False) if mine else "this stage failed; see the run's failure above"
        return f'<div class="box fail"><b>Failed.</b> {esc(text)}</div>'
    if status == "pending":
        why = " The run ended before it." if rr.run_status(run) in ("failed", "stopped") else ""
        return f'<div class="box idle">Not run yet.{why}</div>'
    if status == "stopped":
        failure = run.manifest.get("failure")
        mine = isinstance(failure, dict) and str(failure.get("stage")) == stage.name
        text = failure_text(failure, False) if mine else "the job ended while this stage ran"
        return f'<div class="box fail"><b>Stopped.</b> {esc(text)}</div>'
    if status == "running":
        return f'<div class="box run">Running: {esc(progress_text(run, stage) or "started")}.</div>'
    return ""


def safe_part(fn, *args):
    """A section that fails to build shows why, and the page goes on."""
    try:
        return fn(*args)
    except Exception as e:  # noqa: BLE001
        return f'<div class="box warn">This part could not be shown: {esc(type(e).__name__)}: {esc(e)}</div>'


def plots_block(run, pngs, skip=()):
    figs = [img_tag(run.dir, n, "") for n in pngs if n not in skip]
    figs = [f for f in figs if f]
    return f'<div class="plots">{"".join(figs)}</div>' if figs else ""


def body_section(run, stage):
    why = render_body(run, stage)
    if why:
        return f'<p class="note">No pictures of the body: {esc(why)}.</p>'
    xdmf = f"{stage.name}/concurrent.xdmf"
    explore = (f"open <code>{esc(xdmf)}</code> in ParaView (XDMF Reader)"
               if os.path.isfile(os.path.join(run.dir, xdmf)) else
               "<code>./pbms plot</code> writes <code>concurrent.xdmf</code> for ParaView")
    caption = ("The body at a few times, seen across the wave: coloured by solver (DPD particles "
               "and MPM points), by speed and by displacement since the first frame. Drawn with "
               f"matplotlib from <code>{esc(stage.name)}/dpd_particles.h5md</code> and "
               f"<code>mpm_particles.h5md</code>; to explore it, {explore}.")
    tag = img_tag(run.dir, body_png_name(stage), caption)
    return f'<div class="plots body">{tag}</div>' if tag else ""


# ---------------------------------------------------------------- fit

def column(cols, name):
    return cols.get(name, ([], ""))[0]


def fit_section(stage):
    if stage.kind != "fit_dpd_potential":
        return ""
    parts = ["<h3>Targets against the fitted DPD model</h3>", fit_sources(stage)]
    parts += [fit_elastic_table(stage.tables.get("elastic")),
              fit_isotherm_table(stage.tables.get("isotherm")),
              fit_parameter_table(stage)]
    potential = stage.attrs.get("potential")
    if potential:
        parts.append(f"<details><summary>the fitted potential</summary><pre>{esc(potential)}</pre>"
                     "</details>")
    return "\n".join(p for p in parts if p)


def fit_sources(stage):
    """'isotherm from isotherm.isotherm; c11 from elastic.c11 ...': where the targets came from."""
    found = []
    for group in ("isotherm", "elastic"):
        node = stage.config.get(group)
        if not isinstance(node, dict):
            continue
        for key, value in node.items():
            if isinstance(value, dict) and value.get("from"):
                found.append(f"{group}.{key} from {value['from']}")
    return f'<p class="note">Targets: {esc("; ".join(found))}.</p>' if found else ""


def fit_elastic_table(cols):
    if not cols or not column(cols, "target"):
        return ""
    index, target, fitted = column(cols, "index"), column(cols, "target"), column(cols, "fitted")
    errors = column(cols, "fitted_std_error")
    unit = pretty_unit(cols.get("target", ([], "GPa"))[1])
    rows = []
    for i, t in enumerate(target):
        f = fitted[i] if i < len(fitted) else None
        name = f"C{int(index[i])}" if i < len(index) else str(i)
        dev = f"{100.0 * (f - t) / t:+.3g} %" if f is not None and t else ""
        rows.append((name, esc(fmt_number(t)), esc(fmt_number(f, errors[i] if i < len(errors) else None)), dev))
    return table(["elastic constant", f"target ({unit})", f"fitted ({unit})", "deviation"], rows, "fit")


def fit_isotherm_table(cols):
    if not cols or not column(cols, "volume_per_atom_target"):
        return ""
    p, unit = cols.get("pressure", ([], "bar"))
    scale, p_unit = (1.0 / BAR_PER_GPA, "GPa") if unit == "bar" else (1.0, pretty_unit(unit))
    target, fitted = column(cols, "volume_per_atom_target"), column(cols, "volume_per_atom")
    resid, held = column(cols, "residual"), column(cols, "held_out")
    rows = []
    for i, t in enumerate(target):
        rows.append((esc(fmt_number(p[i] * scale)) if i < len(p) else "", esc(f"{t:.6g}"),
                     esc(f"{fitted[i]:.6g}") if i < len(fitted) else "",
                     esc(f"{100.0 * resid[i]:+.3g} %") if i < len(resid) else "",
                     "held out" if i < len(held) and held[i] > 0.5 else "trained"))
    return table([f"pressure ({p_unit})", "target V/atom (Å³)", "fitted V/atom (Å³)", "residual",
                  "used"], rows, "fit")


def fit_parameter_table(stage):
    rows = []
    for name, value, lo, hi in rr.fit_parameters(stage):
        side = rr.at_bound(value, lo, hi)
        flag = f'<span class="bad">at the {side} bound</span>' if side else ""
        rows.append((esc(name), esc(fmt_number(value)), esc(fmt_number(lo)), esc(fmt_number(hi)), flag))
    return table(["free parameter", "fitted", "lower bound", "upper bound", ""], rows, "fit") \
        if rows else ""


# ---------------------------------------------------------------- files

READERS_BY_NAME = {
    "config.yaml": "the resolved config: defaults filled in, quantities in metal units (YAML)",
    "manifest.yaml": "what ran where: stages, layout, software, failure (YAML)",
    "summary.yaml": "every scalar result with its unit (YAML)",
    "results.h5": "h5py: a group per stage, scalars and tables, units as attributes; "
                  "readable while the job runs",
    "log.txt": "the coupler's log (text)",
    "mpirun.log": "the output of the job's mpirun (text)",
    "concurrent.xdmf": "ParaView, XDMF Reader: both parts and the grid in one view",
    "potential.yaml": "the fitted potential: a material's potential_file",
    "evaluations.journal": "the fit's candidates, one YAML line each (--resume replays them)",
}
READERS_BY_EXT = {
    ".h5md": "H5MD particles: MDAnalysis or h5py; for OVITO, `./pbms export RUN_DIR` writes "
             ".xyz beside it",
    ".xyz": "extended XYZ: OVITO, ASE",
    ".xdmf": "ParaView: File ▸ Open, XDMF Reader (Xdmf3 Reader T); the .h5 beside it holds the data",
    ".h5": "HDF5: h5py; ParaView through the .xdmf beside it",
    ".in": "LAMMPS input (text)",
    ".log": "log (text)",
    ".data": "LAMMPS data file (text)",
    ".yaml": "YAML",
    ".png": "plot (shown above)",
}


def reader_for(relpath):
    name = os.path.basename(relpath)
    if name in READERS_BY_NAME:
        return READERS_BY_NAME[name]
    return READERS_BY_EXT.get(os.path.splitext(name)[1], "")


def stage_files(run, stage):
    """The stage's files: those the manifest lists and those in <stage>/."""
    files = list(stage.files)
    sub = os.path.join(run.dir, stage.name)
    if os.path.isdir(sub):
        for n in sorted(listdir(sub)):
            rel = f"{stage.name}/{n}"
            if os.path.isfile(os.path.join(run.dir, rel)) and rel not in files:
                files.append(rel)
    return [f for f in files if os.path.exists(os.path.join(run.dir, f))]


def file_row(run, rel):
    path = os.path.join(run.dir, rel)
    size = fmt_size(os.path.getsize(path)) if os.path.isfile(path) else ""
    return (link(rel), esc(size), esc(reader_for(rel)))


def files_section(run):
    top = sorted(n for n in listdir(run.dir)
                 if os.path.isfile(os.path.join(run.dir, n)) and not n.startswith(".")
                 and not n.endswith(".png") and n != "report.html")
    rows = [file_row(run, n) for n in top]
    for s in run.stages:
        rows += [file_row(run, f) for f in stage_files(run, s)]
    pngs = sum(1 for n in listdir(run.dir) if n.endswith(".png"))
    plots = f"{pngs} PNG pictures lie beside it (shown above). " if pngs else ""
    where = esc(os.path.abspath(run.dir))
    return ('<section id="files"><h2>Files</h2>'
            f"<p>Links are relative to this page, in <code>{where}</code>. "
            f"{plots}OVITO reads the particles after "
            f"<code>./pbms export {where}</code>; <code>./pbms plot {where}</code> redraws the "
            f"plots (with ParaView renders when pvpython is installed) and <code>./pbms report "
            f"{where}</code> this page.</p>"
            + table(["file", "size", "open it with"], rows, "files") + "</section>")


# ---------------------------------------------------------------- page

STYLE = """
body{font-family:system-ui,-apple-system,"Segoe UI",Roboto,sans-serif;margin:0 auto;max-width:1280px;
 padding:0 20px 40px;color:#1d2430;background:#fff;line-height:1.4}
h1{margin:18px 0 10px}h2{margin:28px 0 8px;border-bottom:1px solid #dde3ea;padding-bottom:4px}
code{background:#f3f5f8;padding:1px 4px;border-radius:3px}
table{border-collapse:collapse;margin:8px 0;font-size:14px}
th,td{border:1px solid #dde3ea;padding:3px 8px;text-align:left;vertical-align:top}
th{background:#f3f5f8}table.facts th{display:none}table.facts td:first-child{white-space:nowrap}
.badge{display:inline-block;padding:1px 9px;border-radius:10px;font-size:14px;color:#fff;vertical-align:middle}
.s-ok{background:#2e7d32}.s-failed,.s-stopped{background:#c62828}.s-running{background:#ef8f00}
.s-pending,.s-unknown{background:#8a94a3}
.box{border-radius:6px;padding:8px 12px;margin:10px 0}
.fail{background:#fdecea;border:1px solid #e57373}.warn{background:#fff6e0;border:1px solid #f0b400}
.run{background:#fff3e0;border:1px solid #ffb74d}.idle{background:#f3f5f8;border:1px solid #c5ccd6}
.cards{display:flex;flex-wrap:wrap;gap:10px;margin:10px 0}
.card{border:1px solid #c5ccd6;border-radius:6px;padding:6px 12px;min-width:160px}
.card .k{font-size:12px;color:#5b6675}.card .v{font-size:18px;font-weight:600}
.card.bad{border-color:#e57373;background:#fdecea}.bad{color:#c62828;font-weight:600}
.plots{display:flex;flex-wrap:wrap;gap:12px;align-items:flex-start}
.plots figure{margin:0;max-width:100%}.plots.body figure{width:100%!important}
.plots img{width:100%;height:auto;border:1px solid #eef1f4}
figcaption{font-size:13px;color:#5b6675}
.what{margin:4px 0}.note{color:#5b6675}.files{font-size:13px}
pre{background:#f3f5f8;padding:8px;white-space:pre-wrap;font-size:12px}
#pbms-selfcheck{margin-top:30px;font-size:12px;color:#5b6675}
"""

# Runs before anything else on the page: counts script errors from the
# start, and on load counts images that did not decode. A headless browser's
# --dump-dom shows the verdict in the attributes of #pbms-selfcheck.
SELF_CHECK = """
(function () {
  var errors = 0;
  window.addEventListener('error', function (e) {
    if (e.target && e.target !== window) return;  // an image: counted on load
    errors += 1;
  }, true);
  window.addEventListener('unhandledrejection', function () { errors += 1; });
  window.addEventListener('load', function () {
    var el = document.getElementById('pbms-selfcheck');
    try {
      var imgs = document.images, broken = [];
      for (var i = 0; i < imgs.length; i++) {
        if (!imgs[i].complete || imgs[i].naturalWidth === 0) broken.push(imgs[i].alt);
      }
      el.setAttribute('data-images', imgs.length);
      el.setAttribute('data-broken-images', broken.length);
      el.setAttribute('data-script-errors', errors);
      el.setAttribute('data-checked', 'yes');
      el.textContent = 'Page self-check: ' + imgs.length + ' images, ' + broken.length +
        ' broken' + (broken.length ? ' (' + broken.join(', ') + ')' : '') + '; ' + errors +
        ' script errors.';
      if (broken.length || errors) el.style.color = '#c62828';
    } catch (err) {
      el.setAttribute('data-script-errors', errors + 1);
      el.setAttribute('data-checked', 'failed');
    }
  });
})();
"""


def all_warnings(run):
    out = [("", p) for p in run.problems]
    out += [("", w) for w in rr.config_warnings(run)]
    for s in run.stages:
        out += [(s.name, w) for w in rr.headline_warnings(s)]
    return out


def page(run):
    owners = png_owners(run)
    status = rr.run_status(run)
    refresh = '<meta http-equiv="refresh" content="20">' if status == "running" else ""
    body = [header_section(run, all_warnings(run)), overview_section(run)]
    body += [safe_part(stage_section, run, s, owners.get(s.name, [])) for s in run.stages]
    if owners.get(""):
        body.append('<section id="run-plots"><h2>Plots of the whole run</h2>'
                    + plots_block(run, owners[""]) + "</section>")
    body.append(safe_part(files_section, run))
    stamp = time.strftime("%Y-%m-%d %H:%M:%S")
    body.append(f'<div id="pbms-selfcheck" data-checked="no">Written by scripts/report.py at '
                f"{esc(stamp)}. (The page's self-check did not run: scripts are off?)</div>")
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            f"<title>PBMS run {esc(run.name)}: {esc(status)}</title>"
            f'<meta name="viewport" content="width=device-width, initial-scale=1">{refresh}'
            f"<style>{STYLE}</style><script>{SELF_CHECK}</script></head>\n<body>\n"
            + "\n".join(body) + "\n</body></html>\n")


def write_atomic(path, content):
    """Writes to a temporary name and renames it: a reader (or a kill) never
    sees half a page."""
    tmp = os.path.join(os.path.dirname(path), f".{os.path.basename(path)}.{os.getpid()}.partial")
    try:
        with open(tmp, "w", encoding="utf-8") as f:
            f.write(content)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


# ---------------------------------------------------------------- last lines

def last_lines(run, report_path):
    """The end of `./pbms run`: where the page is, the headline numbers of
    each stage, and the warnings."""
    lines = [f"pbms: report: {os.path.abspath(report_path)}"]
    for s in run.stages:
        status = shown_status(run, s)
        head = f"pbms:   {s.name} ({s.kind}, {status}" + (f", {fmt_wall(s.wall_s)}" if s.wall_s else "") + ")"
        if status == "ok":
            nums = [f"{k} {fmt_result(s.results[k])}" for k, _ in rr.headline_keys(s) if k in s.results]
            head += (": " + ", ".join(nums)) if nums else ""
        elif status in ("failed", "stopped"):
            failure = run.manifest.get("failure")
            if isinstance(failure, dict) and str(failure.get("stage")) == s.name:
                head += ": " + failure_text(failure, False)
        lines.append(head)
    for stage, w in all_warnings(run):
        lines.append(f"pbms: warning: {stage + ': ' if stage else ''}{w}")
    return lines


# ---------------------------------------------------------------- main

def parse_args(argv):
    p = argparse.ArgumentParser(prog="report.py", description="Write RUN_DIR/report.html.")
    p.add_argument("run_dir", metavar="RUN_DIR")
    mode = p.add_mutually_exclusive_group()
    mode.add_argument("--last-lines", action="store_true",
                      help="also print the page's path, each stage's key numbers and the warnings")
    mode.add_argument("--quiet", action="store_true", help="print nothing")
    p.add_argument("--run-id", help="write only if the manifest's run_id is this one")
    return p.parse_args(argv)


def manifest_run_id(run_dir):
    m = rr.load_yaml(os.path.join(run_dir, "manifest.yaml"), [])
    return str(m.get("run_id", ""))


def main(argv):
    args = parse_args(argv)
    # A kill (the launcher ends its rewrite loop with SIGTERM) unwinds, so
    # that no temporary file is left behind.
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))
    run_dir = args.run_dir
    if not any(os.path.isfile(os.path.join(run_dir, f)) for f in ("manifest.yaml", "summary.yaml")):
        print(f"report.py: error: '{run_dir}' is not a run directory (no manifest.yaml)", file=sys.stderr)
        return 1
    if args.run_id is not None and manifest_run_id(run_dir) != args.run_id:
        return 0  # another job's run directory: not ours to rewrite
    run = rr.read_run(run_dir)
    out = os.path.join(run_dir, "report.html")
    try:
        write_atomic(out, page(run))
    except OSError as e:
        print(f"report.py: error: cannot write {out}: {e}", file=sys.stderr)
        return 1
    if args.last_lines:
        print("\n".join(last_lines(run, out)))
    elif not args.quiet:
        print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
