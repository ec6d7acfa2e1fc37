#!/usr/bin/python3
"""The report page (scripts/report.py) of runs in every state, from small
run directories this test writes itself (no build, no MPI: seconds).

    report_states.py ROOT

- failed: a stage that finished, the concurrent stage that failed (with
  H5MD frames up to the failure) and one never started. The page says the
  run failed, where and why, shows the finished stage's numbers, draws the
  failed stage's body and shows the last stage as not run; the last lines
  name the page and give the numbers and the failure.
- running: the page says so, with the step reached, reloads itself, and
  draws no body of the stage still running.
- finished with bad results: a NaN headline, a missing one, a fit parameter
  at its bound: warnings at the top, in the stage and in the last lines;
  the fit's targets against its fitted values.
- damaged: a manifest that is not YAML, a results.h5 that is not HDF5, a
  truncated PNG: the page is still written, names the unreadable files,
  leaves the broken PNG out, and still draws the body (here of a concurrent
  stage without wave:).
- another job's run (--run-id that does not match): nothing written; a
  directory that is not a run: exit 1.

Every page is checked to be self-contained: images inline as PNG data
URIs, no script, style or image from elsewhere, and the self-check element
the browser test reads.
"""

import os
import re
import shutil
import subprocess
import sys
from html.parser import HTMLParser

import h5py
import numpy as np
import yaml
from checklist import Checklist

ROOT = sys.argv[1]
REPORT = os.path.join(ROOT, "scripts", "report.py")
check = Checklist()

CONFIG = {
    "run": {"name": "states", "output": "runs"},
    "stages": [
        {"name": "elastic", "kind": "md_elastic", "material": "cu"},
        {"name": "impact", "kind": "concurrent", "material": "cu_cg",
         "wave": {"axis": "x", "speeds": [{"name": "dpd_half", "near_slab": "a", "far_slab": "b"}]}},
        {"name": "later", "kind": "dpd_elastic", "material": "cu_cg"},
    ],
}
LAYOUT = [{"program": "coupler", "ranks": 1, "first_world_rank": 0},
          {"program": "md_driver", "ranks": 2, "first_world_rank": 1},
          {"program": "dpd_driver", "ranks": 1, "first_world_rank": 3},
          {"program": "mpm_driver", "ranks": 2, "first_world_rank": 4}]
ELASTIC = {"c11": {"value": 169.92, "unit": "GPa"}, "c12": {"value": 122.63, "unit": "GPa"},
           "c44": {"value": 76.21, "unit": "GPa", "std_error": 0.05},
           "lattice_parameter": {"value": 3.615, "unit": "Å"}}
FAILURE = {"program": "dpd_driver", "rank": 0, "stage": "impact", "step": 12,
           "message": "DPD particle 7 has a non-finite position: the step blew up"}


def write_yaml(path, data, header):
    with open(path, "w", encoding="utf-8") as f:
        f.write(f"# {header}\n")
        yaml.safe_dump(data, f, sort_keys=False, allow_unicode=True)


def manifest(status, stage_status, **extra):
    m = {"pbms_version": "0.1.0", "git_hash": "abc1234", "config": "/x/states.yaml",
         "command": "./pbms run states.yaml", "run_id": "test-run-1", "host": "testhost",
         "started": "2026-01-01T10:00:00+0000", "status": status,
         "software": {"mpi": "Open MPI v4.1.4", "hdf5": "1.10.8"}, "layout": LAYOUT, "stages": []}
    for s in CONFIG["stages"]:
        prog = {"md_elastic": "md_driver"}.get(s["kind"], "dpd_driver")
        entry = {"name": s["name"], "kind": s["kind"], "program": prog,
                 "status": stage_status[s["name"]]}
        if entry["status"] == "ok":
            entry["wall_s"] = 1.5
        m["stages"].append(entry)
    m.update(extra)
    return m


def write_h5md(path, n, frames, blow_up_at=None):
    """A small H5MD file: n particles on a line along x, moving in x."""
    rng = np.random.default_rng(n)
    x0 = np.column_stack([np.arange(n, dtype=float) * 3.6, rng.random(n) * 20, rng.random(n) * 20])
    with h5py.File(path, "w") as f:
        g = f.create_group("particles/all")
        g.create_group("box").attrs["boundary"] = np.array([b"none", b"periodic", b"periodic"])
        for name in ("position", "velocity"):
            s = g.create_group(name)
            s["step"] = np.arange(frames) * 100
            s["time"] = np.arange(frames) * 0.5
        pos = np.stack([x0 + [0.1 * k, 0, 0] for k in range(frames)])
        vel = np.stack([np.tile([5.0 - k, 0.0, 0.0], (n, 1)) for k in range(frames)])
        if blow_up_at is not None:
            pos[blow_up_at:, 0, :] = np.nan
        g["position/value"] = pos
        g["position/value"].attrs["unit"] = "Angstrom"
        g["velocity/value"] = vel
        g["velocity/value"].attrs["unit"] = "Angstrom ps-1"


def make_run(path, status, stage_status, results, **extra):
    os.makedirs(path)
    write_yaml(os.path.join(path, "config.yaml"), CONFIG, "resolved")
    write_yaml(os.path.join(path, "manifest.yaml"), manifest(status, stage_status, **extra),
               "what ran, with which software")
    write_yaml(os.path.join(path, "summary.yaml"), {"run": "states", "stages": results},
               "scalar results per stage")
    with open(os.path.join(path, "log.txt"), "w") as f:
        f.write("[2026-01-01 10:00:00] run 'states'\n[2026-01-01 10:00:05] the last log line\n")


def run_report(args):
    p = subprocess.run(["/usr/bin/python3", REPORT] + args, capture_output=True, text=True,
                       timeout=120)
    return p.returncode, p.stdout, p.stderr


class Page(HTMLParser):
    """The tags the checks look at."""

    def __init__(self, text):
        super().__init__()
        self.imgs, self.hrefs, self.scripts, self.links, self.selfcheck = [], [], [], [], None
        self.feed(text)

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "img":
            self.imgs.append(a)
        elif tag == "a" and "href" in a:
            self.hrefs.append(a["href"])
        elif tag == "script":
            self.scripts.append(a)
        elif tag == "link":
            self.links.append(a)
        if a.get("id") == "pbms-selfcheck":
            self.selfcheck = a


def read_page(run):
    with open(os.path.join(run, "report.html"), encoding="utf-8") as f:
        text = f.read()
    return text, Page(text)


def check_self_contained(name, text, page):
    remote = [h for h in page.hrefs if re.match(r"^[a-z]+://", h)]
    check(not remote, f"{name}: no link leaves the run directory ({remote[:2]})")
    check(all(i.get("src", "").startswith("data:image/png;base64,") for i in page.imgs),
          f"{name}: all {len(page.imgs)} images are inline PNG data URIs")
    check(not any("src" in s for s in page.scripts) and not page.links,
          f"{name}: no script or style file from elsewhere")
    check(page.selfcheck is not None and page.selfcheck.get("data-checked") == "no",
          f"{name}: the self-check element is there, for the browser to fill in")
    check("http://" not in text and "https://" not in text, f"{name}: no http(s) address at all")


def failed_run(base):
    run = os.path.join(base, "failed")
    results = {"elastic": {"kind": "md_elastic", "status": "ok", "wall_s": 1.5, "results": ELASTIC},
               "impact": {"kind": "concurrent", "status": "failed", "results": {}}}
    make_run(run, "failed", {"elastic": "ok", "impact": "failed", "later": "pending"}, results,
             failure=FAILURE, finished="2026-01-01T10:00:09+0000")
    os.makedirs(os.path.join(run, "impact"))
    write_h5md(os.path.join(run, "impact", "dpd_particles.h5md"), 40, 4, blow_up_at=3)
    write_h5md(os.path.join(run, "impact", "mpm_particles.h5md"), 30, 4)
    rc, out, err = run_report(["--last-lines", run])
    check(rc == 0, f"failed run: report.py exits 0 (got {rc}; {err.strip()[-300:]})")
    text, page = read_page(run)
    check("The run failed" in text and FAILURE["message"] in text,
          "failed run: the page says the run failed, and the failure's message")
    check('id="stage-later"' in text and "Not run yet" in text,
          "failed run: the stage never started is shown, as not run")
    check("169.92 GPa" in text and "76.210 ± 0.050 GPa" in text,
          "failed run: the finished stage's numbers, with units and error bar")
    check(any(i.get("alt") == "impact_body.png" for i in page.imgs)
          and os.path.isfile(os.path.join(run, "impact_body.png")),
          "failed run: the failed concurrent stage's body is drawn up to the failure, "
          "beside the page and inline")
    check("the last log line" in text, "failed run: the end of log.txt is on the page")
    lines = out.splitlines()
    check(bool(lines) and lines[0] == f"pbms: report: {os.path.abspath(run)}/report.html",
          f"failed run: the first last line is the page's path ({lines[:1]})")
    check(any("elastic (md_elastic, ok" in ln and "c11 169.92 GPa" in ln for ln in lines),
          "failed run: a last line gives the finished stage's headline numbers")
    check(any("impact (concurrent, failed)" in ln and FAILURE["message"] in ln for ln in lines),
          "failed run: a last line gives the failure")
    check(any("later (dpd_elastic, pending)" in ln for ln in lines),
          "failed run: a last line shows the stage not run")
    check_self_contained("failed run", text, page)
    return run


def running_run(base):
    run = os.path.join(base, "running")
    results = {"elastic": {"kind": "md_elastic", "status": "ok", "wall_s": 1.5, "results": ELASTIC}}
    make_run(run, "running", {"elastic": "ok", "impact": "running", "later": "pending"}, results,
             current={"stage": "impact", "step": 500, "total_steps": 1000, "sim_time_ps": 1.0})
    os.makedirs(os.path.join(run, "impact"))
    write_h5md(os.path.join(run, "impact", "dpd_particles.h5md"), 40, 2)
    rc, out, _ = run_report([run])
    check(rc == 0 and out.strip() == os.path.join(run, "report.html"),
          "running run: report.py exits 0 and prints the page's path")
    text, page = read_page(run)
    check("The job is running" in text and "step 500 of 1000 (50 %)" in text,
          "running run: the page says the job runs, and the step reached")
    check('http-equiv="refresh"' in text, "running run: the page reloads itself")
    check(text.count("Not run yet") == 1, "running run: the last stage is pending")
    check(not os.path.exists(os.path.join(run, "impact_body.png")) and "drawn when the stage has ended" in text,
          "running run: no body drawn from files still being written")
    check_self_contained("running run", text, page)


def fit_results():
    return {"objective": {"value": 6.5e7, "unit": "1"},
            "max_residual_trained": {"value": 0.01, "unit": "1"},
            "max_residual_held_out": {"value": 0.02, "unit": "1"},
            "d0": {"value": 3.5, "unit": "eV"}, "alpha": {"value": 0.74, "unit": "1/Å"}}


def write_fit_h5(path):
    with h5py.File(path, "w") as f:
        g = f.create_group("fit")
        g.attrs["kind"], g.attrs["status"] = "fit_dpd_potential", "ok"
        g.attrs["evaluation_3_failure"] = "DPD isotherm: unstable"
        for name, data, unit in (("index", [11, 12, 44], "1"), ("target", [170.0, 122.0, 76.0], "GPa"),
                                 ("fitted", [168.0, 123.0, 75.5], "GPa")):
            g[f"elastic/{name}"] = np.array(data, dtype=float)
            g[f"elastic/{name}"].attrs["unit"] = unit
        for name, data, unit in (("pressure", [0.0, 1e4], "bar"),
                                 ("volume_per_atom_target", [11.8, 11.7], "Å^3"),
                                 ("volume_per_atom", [11.81, 11.69], "Å^3"),
                                 ("residual", [0.001, -0.001], "1"), ("held_out", [0, 1], "1")):
            g[f"isotherm/{name}"] = np.array(data, dtype=float)
            g[f"isotherm/{name}"].attrs["unit"] = unit


def warned_run(base):
    run = os.path.join(base, "warned")
    os.makedirs(run)
    config = {"run": {"name": "warned"}, "stages": [
        {"name": "isotherm", "kind": "md_isotherm"},
        {"name": "fit", "kind": "fit_dpd_potential",
         "free": {"d0": [2.0, 3.5], "alpha": [0.5, 1.0]},
         "elastic": {"c11": {"from": "md_elastic.c11"}}}]}
    write_yaml(os.path.join(run, "config.yaml"), config, "resolved")
    m = {"status": "ok", "run_id": "w", "layout": LAYOUT[:3], "stages": [
        {"name": "isotherm", "kind": "md_isotherm", "program": "md_driver", "status": "ok"},
        {"name": "fit", "kind": "fit_dpd_potential", "program": "coupler", "status": "ok"}]}
    write_yaml(os.path.join(run, "manifest.yaml"), m, "what ran")
    iso = {"lattice_parameter": {"value": 3.615, "unit": "Å"},
           "bulk_modulus": {"value": float("nan"), "unit": "GPa"}}
    write_yaml(os.path.join(run, "summary.yaml"), {"run": "warned", "stages": {
        "isotherm": {"kind": "md_isotherm", "status": "ok", "results": iso},
        "fit": {"kind": "fit_dpd_potential", "status": "ok", "results": fit_results()}}}, "summary")
    write_fit_h5(os.path.join(run, "results.h5"))
    rc, out, _ = run_report(["--last-lines", run])
    text, page = read_page(run)
    check(rc == 0 and "Warnings (3)" in text,
          "bad results: the page opens with 3 warnings (NaN, missing, at a bound)")
    warn = [ln for ln in out.splitlines() if ln.startswith("pbms: warning: ")]
    check(any("isotherm: bulk_modulus is nan" in w for w in warn)
          and any("isotherm: bulk_modulus_derivative is missing" in w for w in warn)
          and any("fit: parameter d0 = 3.5 ended at its upper bound" in w for w in warn),
          f"bad results: the last lines warn of each ({len(warn)} warnings)")
    check("C11" in text and "target (GPa)" in text and "-1.18 %" in text and "held out" in text,
          "fit: the page tables the targets against the fitted values, with deviations")
    check("elastic.c11 from md_elastic.c11" in text and "at the upper bound" in text,
          "fit: the page names where the targets came from and flags the parameter at its bound")
    check_self_contained("bad results", text, page)


def damaged_run(base, failed):
    run = os.path.join(base, "damaged")
    shutil.copytree(failed, run)
    with open(os.path.join(run, "manifest.yaml"), "w") as f:
        f.write("status: [unclosed\n  : :\n")
    with open(os.path.join(run, "results.h5"), "wb") as f:
        f.write(b"not HDF5 at all" * 10)
    with open(os.path.join(run, "impact_body.png"), "rb") as f:
        head = f.read(2000)
    with open(os.path.join(run, "elastic_half.png"), "wb") as f:
        f.write(head)  # a plot cut off while it was written
    os.remove(os.path.join(run, "impact_body.png"))
    config = dict(CONFIG, stages=[dict(s) for s in CONFIG["stages"]])
    del config["stages"][1]["wave"]  # no wave axis: the body's long axis is across
    write_yaml(os.path.join(run, "config.yaml"), config, "resolved")
    rc, _, err = run_report([run])
    text, page = read_page(run)
    check(rc == 0 and "Traceback" not in err, "damaged run: report.py still writes the page")
    check(any(i.get("alt") == "impact_body.png" for i in page.imgs),
          "damaged run: the body is drawn from the H5MD files (no wave: in the config)")
    check("manifest.yaml could not be read" in text and "results.h5 could not be read" in text,
          "damaged run: the page names the files it could not read")
    check(not any(i.get("alt") == "elastic_half.png" for i in page.imgs),
          "damaged run: a truncated PNG is left out, not shown broken")
    check('id="stage-later"' in text, "damaged run: the stages still come from config.yaml")


def foreign_and_missing(base, failed):
    before = os.path.getmtime(os.path.join(failed, "report.html"))
    rc, out, _ = run_report(["--run-id", "another-job", "--last-lines", failed])
    check(rc == 0 and out == "" and os.path.getmtime(os.path.join(failed, "report.html")) == before,
          "another job's run directory: nothing written, nothing printed")
    rc, _, err = run_report(["--run-id", "test-run-1", "--quiet", failed])
    check(rc == 0 and os.path.getmtime(os.path.join(failed, "report.html")) >= before,
          "this job's run directory (--run-id matches): the page is rewritten")
    empty = os.path.join(base, "not_a_run")
    os.makedirs(empty)
    rc, _, err = run_report([empty])
    check(rc == 1 and "not a run directory" in err, "a directory without a manifest: exit 1")
    leftovers = [n for d in os.listdir(base) for n in os.listdir(os.path.join(base, d))
                 if n.startswith(".") or n.endswith(".tmp")]
    check(not leftovers, f"no temporary file left behind ({leftovers[:3]})")


def main():
    base = os.path.abspath("runs")
    shutil.rmtree(base, ignore_errors=True)
    os.makedirs(base)
    failed = failed_run(base)
    running_run(base)
    warned_run(base)
    damaged_run(base, failed)
    foreign_and_missing(base, failed)
    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
