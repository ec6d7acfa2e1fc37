source "$(dirname "$0")/lib.sh"
# The sintering pair run by DPD alone (seed §6.2.2, assembly 0; issue 31):
# configs/sintering_dpd_only.yaml, two copper mesoparticle models against
# MD's pair. Against references the program did not make:
#  - the neck between two spheres grows on the surface energy it frees: the
#    model whose (100) surface energy is the larger makes the wider neck.
#    The surface energies are lattice sums recomputed here (the Morse pair
#    sum below; scripts/sutton_chen_surface.py for Sutton-Chen), not the
#    program's;
#  - with `all` (the validation test, the whole config with the MD pair):
#    the neck of the model fitted with MD's surface energy is within 25 % of
#    the MD pair's, measured by the same rule (the issue's bound). Seeds
#    2026-2028: -8.1, -13.3, +2.7 %; the Morse model: +31 to +50 %.
# The default run is 30 ps of each pair after a 10 ps sphere, the stable
# neck the mean over its last 10 ps.
CONFIG="$ROOT/configs/sintering_dpd_only.yaml"
ALL=0
[ "${1:-}" = all ] && ALL=1
"$PY" - "$CONFIG" "$ALL" > pair.yaml <<'PYEOF'
import sys
import yaml
import derived_config
config = derived_config.load(sys.argv[1])
config["run"] = {"name": "pair", "seed": 2026, "output": "runs"}
if sys.argv[2] != "1":
    config["launch"] = {"dpd": 1}
    del config["materials"]["cu_mishin"]
    config["stages"] = [s for s in config["stages"] if s["kind"] != "md_bodies"]
    for s in config["stages"]:
        s["steps"] = 1000 if s["name"].startswith("sphere") else 3000
        if s["name"].startswith("pair"):
            s["neck_stable_time"] = "10 ps"
            s["particles_every"] = 0
yaml.safe_dump(config, sys.stdout, sort_keys=False)
PYEOF
"$PBMS" run pair.yaml > run.out 2>&1 || { tail -30 run.out; fail "the run failed"; }
"$PY" - runs/pair "$ALL" "$CONFIG" "$ROOT" <<'PYEOF' || fail "the DPD-only pair misses its references"
import os
import subprocess
import sys
import h5py
import numpy as np
import yaml

run, everything, config_path, root = sys.argv[1], sys.argv[2] == "1", sys.argv[3], sys.argv[4]
config = yaml.safe_load(open(config_path))
J_PER_M2 = 16.021766  # eV/Å² in J/m²

def morse_surface_energy(p, a):
    """(100) surface energy of a static fcc crystal of a shifted Morse pair:
    the pairs a cut between two (100) planes breaks, over twice the area."""
    phi = lambda r: p["d0"] * (np.exp(-2 * p["alpha"] * (r - p["r0"])) - 2 * np.exp(-p["alpha"] * (r - p["r0"])))
    rc = p["cutoff"]
    n = int(np.ceil(rc / a)) + 2
    cells = np.array([[i, j, k] for i in range(-n, n + 1) for j in range(-n, n + 1) for k in range(-n, n + 1)])
    basis = np.array([[0, 0, 0], [0.5, 0.5, 0], [0.5, 0, 0.5], [0, 0.5, 0.5]])
    sites = ((cells[:, None, :] + basis[None]).reshape(-1, 3)) * a
    broken = 0.0
    # The sites of one a x a column below the cut (z <= 0), each against every site above it.
    below = sites[(sites[:, 0] >= 0) & (sites[:, 0] < a - 1e-9) & (sites[:, 1] >= 0) & (sites[:, 1] < a - 1e-9)
                  & (sites[:, 2] <= 1e-9) & (sites[:, 2] > -rc - a)]
    above = sites[sites[:, 2] > 1e-9]
    for s in below:
        r = np.linalg.norm(above - s, axis=1)
        r = r[r < rc]
        broken += np.sum(phi(r) - phi(rc))
    return -broken / (2 * a * a) * J_PER_M2

def sutton_chen_surface_energy(path):
    out = subprocess.run(["/usr/bin/python3", f"{root}/scripts/sutton_chen_surface.py", path],
                         capture_output=True, text=True, check=True).stdout
    for line in out.splitlines():
        if "surface" in line and "J/m" in line:
            return float(line.split("J/m")[0].split()[-1])
    raise SystemExit(f"no surface energy in: {out}")

gamma = {
    "cu_cg": morse_surface_energy(config["materials"]["cu_cg"]["potential"], config["materials"]["cu_cg"]["lattice_constant"]),
    "cu_cg_surface": sutton_chen_surface_energy(os.path.join(os.path.dirname(config_path), config["materials"]["cu_cg_surface"]["potential_file"])),
}
bad = []
with h5py.File(f"{run}/results.h5", "r") as f:
    scalar = lambda s, k: float(f[s][k][()]) if k in f[s] else None
    neck = {}
    for stage, material in (("pair", "cu_cg"), ("pair_surface", "cu_cg_surface")):
        w, touch = scalar(stage, "neck_width_pair"), scalar(stage, "contact_time_pair")
        print(f"{stage} ({material}, (100) surface {gamma[material]:.3f} J/m^2): stable neck {w:.2f} Å, "
              f"touch at {touch} ps, T {scalar(stage, 'temperature'):.1f} K")
        if scalar(stage, "particles") != 2096:
            bad.append(f"{stage}: {scalar(stage, 'particles'):.0f} particles, not the seed's 2 x 1,048")
        if touch is None or not w > 0.0:
            bad.append(f"{stage}: the spheres never formed a neck")
        neck[material] = w
    wider = max(neck, key=neck.get)
    higher = max(gamma, key=gamma.get)
    if wider != higher:
        bad.append(f"the wider neck is {wider}'s, the higher surface energy {higher}'s")
    if everything:
        md = scalar("pair_md", "neck_width_pair")
        for material in neck:
            print(f"  {material} against MD's {md:.2f} Å: {100 * (neck[material] / md - 1):+.1f} %")
        if abs(neck["cu_cg_surface"] / md - 1.0) > 0.25:
            bad.append(f"the surface-fitted model's neck {neck['cu_cg_surface']:.2f} Å is more than 25 % off MD's {md:.2f} Å")
if not os.path.isfile(f"{run}/necks.png"):
    bad.append("necks.png (fig. 6.7) was not written")
for b in bad:
    print("FAIL:", b)
sys.exit(1 if bad else 0)
PYEOF
echo "PASS"
