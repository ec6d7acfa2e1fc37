#!/usr/bin/python3
"""results.h5 and summary.yaml can be read while the job is still running.

    read_while_running.py ROOT

Starts `./pbms run tests/integration/configs/readers_poll.yaml` (twelve short
stages; the coupler rewrites results.h5 and summary.yaml after each) and,
until it ends, reads both files over and over as a user would: h5py opens
results.h5, reads every dataset and attribute and keeps the file open for
a while (HDF5 1.10 locks the files it opens, so a writer updating the file
in place would fail to open it, or the reader would fail to open it in the
middle of an update); yaml loads summary.yaml. The coupler writes each file
to a temporary name and renames it over the old one.

Passes when the run succeeds, no read ever fails, reads happened while
stages were still to come (at least five distinct numbers of finished
stages seen in each file before the job ended), what was seen never
shrank, and the final files hold all twelve stages.
"""

import os
import subprocess
import sys
import time

import h5py
import yaml
from checklist import Checklist

STAGES = 12


def read_results(path):
    """Every stage group, dataset and attribute; the number of stages."""
    with h5py.File(path, "r") as f:
        n = 0
        for name, g in f.items():
            n += 1
            dict(g.attrs)
            for item in g.values():
                if isinstance(item, h5py.Dataset):
                    item[()]
                    dict(item.attrs)
                else:
                    for col in item.values():
                        col[()]
                        dict(col.attrs)
        time.sleep(0.05)  # a user's session keeps the file open a while
        return n


def read_summary(path):
    with open(path) as f:
        s = yaml.safe_load(f)
    if not isinstance(s, dict) or "stages" not in s:
        raise ValueError(f"summary.yaml without stages: {s!r:.200}")
    return sum(1 for v in (s["stages"] or {}).values() if v.get("status") == "ok")


def main():
    root = sys.argv[1]
    run = os.path.join("runs", "readers_poll")
    subprocess.run(["rm", "-rf", run], check=True)  # this test reruns its own run name
    log = open("out.txt", "w")
    job = subprocess.Popen([os.path.join(root, "pbms"), "run",
                            os.path.join(root, "tests/integration/configs/readers_poll.yaml")],
                           stdout=log, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL)
    seen = {"results.h5": [], "summary.yaml": []}
    errors = []
    reads = 0
    while job.poll() is None:
        for name, reader in (("results.h5", read_results), ("summary.yaml", read_summary)):
            path = os.path.join(run, name)
            if not os.path.exists(path):
                continue
            try:
                seen[name].append(reader(path))
                reads += 1
            except FileNotFoundError:
                pass  # not written yet (the run directory is made at start)
            except Exception as e:
                errors.append(f"{name}: {type(e).__name__}: {e}")
        time.sleep(0.01)
    rc = job.wait()
    log.close()

    check = Checklist()

    if rc != 0:
        print(open("out.txt").read())
    check(rc == 0, f"the run succeeded while being read (exit {rc})")
    check(not errors, f"{reads} reads while it ran, none failed"
          + ("" if not errors else f": {len(errors)} failed, first: {errors[0]}"))
    for name, counts in seen.items():
        distinct = sorted(set(counts))
        check(len(distinct) >= 5, f"{name}: read at {len(distinct)} distinct stage counts "
              f"{distinct} while running")
        check(all(a <= b for a, b in zip(counts, counts[1:])), f"{name}: never went backwards")
    check(read_results(os.path.join(run, "results.h5")) == STAGES, "final results.h5: 12 stages")
    check(read_summary(os.path.join(run, "summary.yaml")) == STAGES, "final summary.yaml: 12 stages")
    leftovers = [n for n in os.listdir(run) if n.endswith(".tmp")]
    check(not leftovers, f"no temporary files left: {leftovers}")
    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
