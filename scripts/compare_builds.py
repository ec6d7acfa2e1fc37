#!/usr/bin/python3
"""Runs workflow configs with two PBMS checkouts and compares what they report.

Usage: scripts/compare_builds.py OLD_ROOT NEW_ROOT WORK [--only old|new] [CONFIG ...]

Each CONFIG (a path relative to the checkouts' roots; default: every file in
configs/ and tests/integration/configs/) runs as `ROOT/pbms run ROOT/CONFIG`
in WORK/old/<name>/ and WORK/new/<name>/, with the same seeds and rank counts
(the config's own). A side that already has a finished run is not run again,
so the old side can run first and the new one later (--only). Then, per
config, it compares:
  - the exit code, and for a run that failed the error line, without timings
    and with each checkout's path as <root>;
  - every value of summary.yaml but the timings (wall times, steps per
    second, seconds packing and waiting): bitwise, else the relative
    difference is printed;
  - every numeric dataset of results.h5 alike (the tables the plots read).
Exit 0 when every compared config agrees bitwise.
"""
import math
import os
import re
import subprocess
import sys
import time
from pathlib import Path

import yaml

try:
    import h5py
    import numpy as np
except ImportError:  # the summaries are still compared
    h5py = None


# Keys that time the run rather than describe its result.
TIMING = re.compile(r"wall|per_second|seconds|waiting_fraction")


def all_configs(root):
    found = sorted(Path(root, "configs").glob("*.yaml"))
    found += sorted(Path(root, "tests/integration/configs").glob("*.yaml"))
    return [str(p.relative_to(root)) for p in found]


def run_side(root, config, work):
    work.mkdir(parents=True, exist_ok=True)
    done = work / "exit_code"
    if done.exists():
        return
    env = dict(os.environ, PBMS_SKIP_BUILD="1")
    t0 = time.time()
    with open(work / "console.txt", "w") as out:
        rc = subprocess.call([f"{root}/pbms", "run", f"{root}/{config}", "--overwrite"],
                             cwd=work, stdout=out, stderr=subprocess.STDOUT, env=env)
    (work / "seconds").write_text(f"{time.time() - t0:.1f}\n")
    done.write_text(f"{rc}\n")


def run_dir(work):
    dirs = [p.parent for p in work.glob("*/*/manifest.yaml")]
    return dirs[0] if dirs else None


def flatten(node, prefix=""):
    if isinstance(node, dict):
        for k, v in node.items():
            yield from flatten(v, f"{prefix}.{k}" if prefix else str(k))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from flatten(v, f"{prefix}[{i}]")
    else:
        yield prefix, node


def relative(a, b):
    if isinstance(a, float) and isinstance(b, float):
        if math.isnan(a) and math.isnan(b):
            return 0.0
        scale = max(abs(a), abs(b))
        return abs(a - b) / scale if scale > 0 else 0.0
    return None


def compare_summaries(old, new):
    """Lines describing every difference (wall times left out)."""
    a = dict(flatten(yaml.safe_load(old.read_text())))
    b = dict(flatten(yaml.safe_load(new.read_text())))
    diffs = []
    for key in sorted(set(a) | set(b)):
        if TIMING.search(key):
            continue
        if key not in a or key not in b:
            diffs.append(f"{key}: only in {'new' if key in b else 'old'}")
            continue
        x, y = a[key], b[key]
        if isinstance(x, float) and isinstance(y, float) and math.isnan(x) and math.isnan(y):
            continue
        if x != y:
            r = relative(x, y)
            diffs.append(f"{key}: {x!r} vs {y!r}" + (f" (rel {r:.2e})" if r is not None else ""))
    return diffs, len(a)


def datasets(path):
    out = {}
    with h5py.File(path, "r") as f:
        def visit(name, obj):
            if isinstance(obj, h5py.Dataset) and obj.dtype.kind in "fiu":
                out[name] = obj[()]
        f.visititems(visit)
    return out


def compare_results(old, new):
    if h5py is None:
        return ["h5py missing: results.h5 not compared"], 0
    a, b = datasets(old), datasets(new)
    diffs = []
    for key in sorted(set(a) | set(b)):
        if TIMING.search(key):
            continue
        if key not in a or key not in b:
            diffs.append(f"{key}: only in {'new' if key in b else 'old'}")
            continue
        x, y = np.asarray(a[key], dtype=float), np.asarray(b[key], dtype=float)
        if x.shape != y.shape:
            diffs.append(f"{key}: shape {x.shape} vs {y.shape}")
        elif not np.array_equal(x, y, equal_nan=True):
            scale = np.maximum(np.abs(x), np.abs(y))
            with np.errstate(invalid="ignore", divide="ignore"):
                rel = np.where(scale > 0, np.abs(x - y) / scale, 0.0)
            diffs.append(f"{key}: max rel {np.nanmax(rel):.2e}")
    return diffs, len(a)


def error_line(work, root):
    text = (work / "console.txt").read_text(errors="replace").replace(str(root), "<root>")
    lines = [l for l in text.splitlines() if "error" in l.lower() or "failed" in l.lower()]
    if not lines:
        return ""
    return re.sub(r"\d+(\.\d+)? ?s\b", "<t>", lines[-1])


def compare(config, old_work, new_work, old_root, new_root):
    rc_old = (old_work / "exit_code").read_text().strip()
    rc_new = (new_work / "exit_code").read_text().strip()
    if rc_old != rc_new:
        return False, [f"exit code {rc_old} vs {rc_new}"]
    if rc_old != "0":
        a, b = error_line(old_work, old_root), error_line(new_work, new_root)
        return a == b, [f"both exit {rc_old}: {a!r}" if a == b else f"errors: {a!r} vs {b!r}"]
    old_dir, new_dir = run_dir(old_work), run_dir(new_work)
    diffs, n = compare_summaries(old_dir / "summary.yaml", new_dir / "summary.yaml")
    rdiffs, m = compare_results(old_dir / "results.h5", new_dir / "results.h5")
    lines = [f"summary: {n} values, {len(diffs)} differ; results.h5: {m} datasets, "
             f"{len(rdiffs)} differ"]
    return not diffs and not rdiffs, lines + ["  " + d for d in diffs + rdiffs]


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    old_root, new_root, work = (Path(a).resolve() for a in argv[:3])
    rest = argv[3:]
    only = None
    if rest[:1] == ["--only"]:
        only, rest = rest[1], rest[2:]
    configs = rest or all_configs(new_root)
    same = True
    for config in configs:
        name = config.replace("/", "_").removesuffix(".yaml")
        old_work, new_work = work / "old" / name, work / "new" / name
        if only in (None, "old"):
            run_side(old_root, config, old_work)
        if only in (None, "new"):
            run_side(new_root, config, new_work)
        if only is not None:
            print(f"{config}: ran {only}", flush=True)
            continue
        ok, lines = compare(config, old_work, new_work, old_root, new_root)
        same &= ok
        secs = [(w / "seconds").read_text().strip() for w in (old_work, new_work)]
        print(f"{'SAME' if ok else 'DIFF'} {config} ({secs[0]} s / {secs[1]} s)")
        for l in lines:
            print(f"  {l}")
        sys.stdout.flush()
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
