source "$(dirname "$0")/lib.sh"
# md_bodies (issue 31: the MD reference of the sintering pair), a small pair
# of copper spheres, 2 ps. Against references the program did not make:
#  - the atoms: the fcc sites within 3 a of each centre, counted here;
#  - the closest approach at the start: one lattice constant, the gap between
#    the two poles set by the centres, and no neck (the rule of the DPD
#    pair's probe, held to its own tests in NeckProbe.*);
#  - NVT: the temperature over the second half within 10 % of 298 K;
#  - bodies that overlap are refused before LAMMPS runs, naming both;
#  - the script it writes replays with plain lmp on as many ranks to the
#    same neck table (the same trajectory).
"$PY" - > pair.yaml <<'PYEOF'
import yaml
a = 3.615
material = {"kind": "eam_alloy", "potential": "/usr/share/lammps/potentials/Cu_mishin1.eam.alloy",
            "element": "Cu", "mass": 63.546, "lattice": "fcc", "lattice_constant": a}
stage = {"name": "pair", "kind": "md_bodies", "material": "cu",
         "bodies": [{"name": "left", "region": {"style": "sphere", "centre": [10 * a, 10 * a, 10 * a], "radius": 3 * a}},
                    {"name": "right", "region": {"style": "sphere", "centre": [17 * a, 10 * a, 10 * a], "radius": 3 * a}}],
         "temperature": 298, "time": "2 ps", "sample_every": 50,
         "necks": [{"name": "pair", "first": "left", "second": "right"}], "neck_stable_time": "1 ps"}
overlap = dict(stage, name="overlap", bodies=[
    stage["bodies"][0],
    {"name": "right", "region": {"style": "sphere", "centre": [15.5 * a, 10 * a, 10 * a], "radius": 3 * a}}])
for name, stages in (("pair", [stage]), ("overlap", [overlap])):
    yaml.safe_dump({"run": {"name": name, "seed": 2026, "output": "runs"}, "launch": {"md": 2},
                    "materials": {"cu": material}, "stages": stages}, open(f"{name}.yaml", "w"))
PYEOF
"$PBMS" run pair.yaml > run.out 2>&1 || { tail -30 run.out; fail "the run failed"; }
if "$PBMS" run overlap.yaml > overlap.out 2>&1; then fail "overlapping bodies were run"; fi
grep -q "bodies 'left' and 'right' overlap" overlap.out || { tail -5 overlap.out; fail "the overlap is not named"; }
(cd runs/pair/pair && mpirun -np 2 lmp -in bodies.in -log replay.log -screen none -nocite) ||
  fail "bodies.in does not replay with plain lmp"
"$PY" - runs/pair <<'PYEOF' || fail "md_bodies misses its references"
import sys
import h5py
import numpy as np

run = sys.argv[1]
bad = []
cells = np.stack(np.meshgrid(*[np.arange(-4, 5)] * 3, indexing="ij"), -1).reshape(-1, 1, 3)
basis = np.array([[0, 0, 0], [0.5, 0.5, 0], [0.5, 0, 0.5], [0, 0.5, 0.5]])
sites = (cells + basis).reshape(-1, 3)
per_sphere = int((np.linalg.norm(sites, axis=1) <= 3 + 1e-9).sum())
with h5py.File(f"{run}/results.h5", "r") as f:
    g = f["pair"]
    atoms = float(g["atoms"][()])
    neck = g["neck_pair"]
    closest0, width0 = float(neck["closest"][0]), float(neck["width"][0])
    temperature = float(g["temperature"][()])
print(f"atoms {atoms:.0f} (two spheres of {per_sphere}), closest at the start {closest0:.4f} Å, "
      f"neck {width0:.2f} Å, temperature {temperature:.1f} K")
if atoms != 2 * per_sphere:
    bad.append(f"{atoms:.0f} atoms, not 2 x {per_sphere}")
if abs(closest0 - 3.615) > 1e-6:
    bad.append(f"the poles start {closest0:.4f} Å apart, not a = 3.615 Å")
if width0 != 0.0:
    bad.append(f"a neck of {width0:.2f} Å between spheres a lattice constant apart")
if abs(temperature / 298.0 - 1.0) > 0.1:
    bad.append(f"NVT held {temperature:.1f} K, not 298 K within 10 %")
# The replay: LAMMPS' own thermo of the last step against the stage's log.
def last_thermo(path):
    rows = [l.split() for l in open(path) if l.split()[:1] and l.split()[0].isdigit() and len(l.split()) == 3]
    return rows[-1]
stage, replay = last_thermo(f"{run}/pair/bodies.log"), last_thermo(f"{run}/pair/replay.log")
print(f"last thermo: stage {stage}, plain lmp {replay}")
if stage != replay:
    bad.append(f"plain lmp ends at {replay}, the stage at {stage}")
for b in bad:
    print("FAIL:", b)
sys.exit(1 if bad else 0)
PYEOF
echo "PASS"
