"""Replays every strained-crystal input an md_elastic stage wrote with plain
`lmp`, on as many ranks as md_driver had, and compares.

md_driver writes each input as it ran it (the MD runs chunk by chunk), and
each prints its stress averages with %.20g, so the replay follows the same
trajectory: the stresses and the constants derived from them must agree to
1e-9 relative (the two means differ by summation order only, ~1e-16; a
different seed or rank count moves them by far more than 1e-9).

usage: elastic_vs_lmp.py RUN_DIR STAGE
"""
import subprocess
import sys

import h5py
import yaml

run, stage = sys.argv[1], sys.argv[2]
manifest = yaml.safe_load(open(f"{run}/manifest.yaml"))
ranks = next(l["ranks"] for l in manifest["layout"] if l["program"] == "md_driver")
with h5py.File(f"{run}/results.h5") as f:
    results = {k: f[f"{stage}/{k}"][()] for k in
               ("c11", "c12", "c44", "c11_at_t", "c12_at_t", "c44_at_t") if k in f[stage]}
    table = {k: f[f"{stage}/strains/{k}"][:] for k in
             ("temperature", "mode", "strain", "stress_xx", "stress_yy", "stress_zz", "stress_xy")}
bad = 0


def check(ok, what):
    global bad
    bad += not ok
    print(("ok   " if ok else "FAIL ") + what)


def lmp_stress(tag):
    """Stress (GPa, tension positive) printed by plain lmp for one input."""
    screen = f"lmp_{stage}_{tag}.txt"
    subprocess.run(["mpirun", "--bind-to", "none", "--oversubscribe", "-np", str(ranks), "lmp",
                    "-in", f"{run}/{stage}/{tag}.in", "-log", "none", "-nocite", "-screen", screen],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT)
    line = [l for l in open(screen) if l.startswith("PBMS_STRESS_BAR")][-1].split()
    return {k: -float(line[line.index(k) + 1]) / 1e4 for k in ("pxx", "pyy", "pzz", "pxy")}


constants = {}
for row in range(len(table["strain"])):
    t, mode, e = table["temperature"][row], int(table["mode"][row]), table["strain"][row]
    tag = f"{'hot' if t > 0 else 'cold'}_{'xy' if mode else 'xx'}_{'plus' if e > 0 else 'minus'}"
    s = lmp_stress(tag)
    worst = max(abs(table[f"stress_{c[1:]}"][row] - s[c]) / max(abs(s[c]), 1e-3) for c in s)
    check(worst < 1e-9, f"{stage}/{tag}: md_driver stresses vs plain lmp on {ranks} ranks, "
          f"largest relative difference {worst:.1e} (tolerance 1e-9)")
    constants.setdefault(t, {})[(mode, e > 0)] = s
for t, s in constants.items():
    e = abs(table["strain"][table["temperature"] == t][0])
    lmp_c = {"c11": (s[(0, True)]["pxx"] - s[(0, False)]["pxx"]) / (2 * e),
             "c12": (s[(0, True)]["pyy"] - s[(0, False)]["pyy"]) / (2 * e),
             "c44": (s[(1, True)]["pxy"] - s[(1, False)]["pxy"]) / (2 * e)}
    for k, ref in lmp_c.items():
        key = f"{k}_at_t" if t > 0 else k
        ours = results[key]
        rel = abs(ours - ref) / abs(ref)
        check(rel < 1e-9, f"{stage} {key} at {t:g} K: md_driver {ours:.12g} GPa, plain lmp "
              f"{ref:.12g} GPa, relative difference {rel:.1e}")
sys.exit(1 if bad else 0)
