"""Physics and bookkeeping checks on a finished md_isotherm run of EAM Cu."""
import sys
import h5py
import numpy as np
import yaml

run = sys.argv[1]
summary = yaml.safe_load(open(f"{run}/summary.yaml"))
manifest = yaml.safe_load(open(f"{run}/manifest.yaml"))
stage = summary["stages"]["isotherm"]
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


check(stage["status"] == "ok", "stage status ok")
check(manifest["status"] == "ok", "manifest status ok")
check(manifest["git_hash"] != "", "manifest records the git hash")
check("lammps" in manifest["software"], "manifest records the LAMMPS version")
res = stage["results"]
a = res["lattice_parameter"]["value"]
B = res["bulk_modulus"]["value"]
check(res["bulk_modulus"]["unit"] == "GPa", "bulk modulus unit is GPa")
check(abs(a - 3.632) / 3.632 < 0.002, f"lattice parameter {a:.5f} Å near 3.632 Å")
check(abs(B - 135.0) / 135.0 < 0.05, f"bulk modulus {B:.2f} GPa within 5 % of 135")

with h5py.File(f"{run}/results.h5", "r") as f:
    g = f["isotherm/isotherm"]
    p = g["pressure_target"][:]
    ratio = g["volume_ratio"][:]
    check(g["pressure"].attrs["unit"] in ("bar", b"bar"), "pressure column has unit bar")
    check(f["isotherm/bulk_modulus"].attrs["unit"] in ("GPa", b"GPa"), "scalar has a unit")
    i5 = int(np.argmin(abs(p - 5e4)))
    check(abs(p[i5] - 5e4) < 1, "a 5 GPa point exists")
    check(abs(ratio[i5] - 0.9656) / 0.9656 < 0.002,
          f"V/V0 at 5 GPa = {ratio[i5]:.5f}, within 0.2 % of 0.9656")
    check(np.all(np.diff(ratio) < 0), "volume falls with pressure")

sys.exit(1 if failures else 0)
