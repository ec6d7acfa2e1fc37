"""Replays the input an md_tension stage wrote with plain `lmp`, on as many
ranks as md_driver had, and compares the stress-strain curve row by row:
the nanowire's (strain, virial and grip stresses) or the periodic crystal's
(strain, stresses xx, yy and zz), whichever the stage ran.

md_driver writes the input as it ran it (the MD runs chunk by chunk) and the
input prints every stress sample with %.20g (PBMS_SAMPLE lines), so the
replay follows the same trajectory: strain, virial and grip stresses must
agree to 1e-9 of the largest stress, and Young's modulus refitted from
lmp's curve to 1e-9 relative. Both differences are round-off of the same
numbers (~1e-15); a different seed or rank count moves them by far
more.

usage: tension_vs_lmp.py RUN_DIR STAGE
"""
import subprocess
import sys

import h5py
import numpy as np
import yaml

run, stage = sys.argv[1], sys.argv[2]
manifest = yaml.safe_load(open(f"{run}/manifest.yaml"))
ranks = next(l["ranks"] for l in manifest["layout"] if l["program"] == "md_driver")
stages = yaml.safe_load(open(f"{run}/config.yaml"))["stages"]
fit_max = float(next(s for s in stages if s["name"] == stage)["fit_max_strain"])
screen = f"lmp_{stage}_tension.txt"
subprocess.run(["mpirun", "--bind-to", "none", "--oversubscribe", "-np", str(ranks), "lmp",
                "-in", f"{run}/{stage}/tension.in", "-log", "none", "-nocite", "-screen", screen],
               check=True, stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT)
rows = np.array([[float(w) for w in l.split()[1:]] for l in open(screen)
                 if l.startswith("PBMS_SAMPLE")])
rows = rows[rows[:, 0] > 0]  # step 0 is before any window was averaged, as md_driver drops it
with h5py.File(f"{run}/results.h5") as f:
    g = f[f"{stage}/stress_strain"]
    # The columns of PBMS_SAMPLE after the step, in the order md_driver prints them.
    names = ["strain", "stress"] + (["grip_stress"] if "grip_stress" in g
                                    else ["stress_yy", "stress_zz"])
    table = {k: g[k][:] for k in names}
    E = f[f"{stage}/youngs_modulus"][()]
strain = table["strain"]
bad = 0


def check(ok, what):
    global bad
    bad += not ok
    print(("ok   " if ok else "FAIL ") + what)


check(rows.shape[0] == strain.size, f"{stage}: plain lmp printed {rows.shape[0]} samples, "
      f"md_driver's table has {strain.size}")
if rows.shape[0] == strain.size:
    scale = np.abs(rows[:, 2]).max()
    for col, name in enumerate(names, start=1):
        ref_scale = np.abs(rows[:, col]).max() if name == "strain" else scale
        d = np.abs(table[name] - rows[:, col]).max() / ref_scale
        check(d < 1e-9, f"{stage} {name}: md_driver vs plain lmp on {ranks} ranks, largest "
              f"difference {d:.1e} of the largest value (tolerance 1e-9)")
    sel = rows[:, 1] <= fit_max  # from the first sample on, as md_driver fits
    E_lmp = np.polyfit(rows[sel, 1], rows[sel, 2], 1)[0]
    rel = abs(E - E_lmp) / abs(E_lmp)
    check(rel < 1e-9, f"{stage} Young's modulus: md_driver {E:.10g} GPa, from plain lmp's curve "
          f"{E_lmp:.10g} GPa, relative difference {rel:.1e} (tolerance 1e-9)")
sys.exit(1 if bad else 0)
