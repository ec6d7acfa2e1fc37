source "$(dirname "$0")/lib.sh"
# The conservation ledger of a concurrent stage (issue 17, item 5) has a row
# for every step, and its rows are the state the particle files hold. The
# small concurrent bar (DPD half on 2 ranks, MPM half on 1, momentum-
# conserving interface, a DPD flyer) runs 60 steps; at steps 0 and 60 the
# ledger's DPD pair energy, DPD-MPM interface pair energy, kinetic energies
# and total momentum must equal what this script computes from the H5MD
# frames with the Morse formula of the config (minimum image across the
# periodic axes), to 1e-9: round-off of sums over ~1e4 pairs is ~1e-13.
# An interface pair counted once per rank, or half, or at the wrong step's
# positions misses by far more (half the interface energy is 240 eV).
CONFIG="$(dirname "$0")/configs/concurrent_small.yaml"
sed "s/name: concurrent_small/name: ledger/; s/launch: {dpd: 1, mpm: 2}/launch: {dpd: 2, mpm: 1}/;
     s/steps: 300/steps: 60/" "$CONFIG" > ledger.yaml
echo "    particles_every: 60" >> ledger.yaml
"$PBMS" run ledger.yaml > ledger.out 2>&1 || { tail -20 ledger.out; fail "the run failed"; }
"$PY" - runs/ledger <<'PYEOF' || fail "the ledger does not match the particle files"
import sys
import h5py
import numpy as np
import yaml

run = sys.argv[1]
config = yaml.safe_load(open(f"{run}/config.yaml"))
stage = config["stages"][0]
pot = config["materials"][stage["material"]]["potential"]
d0, alpha, r0, rc = (float(pot[k]) for k in ("d0", "alpha", "r0", "cutoff"))
box = stage["box"]
period = np.array(box["hi"], float) - np.array(box["lo"], float)
periodic = np.array(["xyz"[a] in box["periodic"] for a in range(3)])
mvv2e = 1.0364269e-4  # g/mol Å²/ps² to eV (LAMMPS metal)

def morse(r):
    e = lambda s: d0 * (np.exp(-2 * alpha * (s - r0)) - 2 * np.exp(-alpha * (s - r0)))
    return e(r) - e(rc)

def pairs(a, b=None):
    """Morse energy of the pairs within a (b None) or between a and b, minimum image."""
    total = 0.0
    for i in range(len(a)):
        other = a[i + 1:] if b is None else b
        d = other - a[i]
        d = np.where(periodic, d - period * np.round(d / period), d)
        r = np.linalg.norm(d, axis=1)
        total += morse(r[r < rc]).sum()
    return total

def frame(name, k):
    with h5py.File(f"{run}/impact/{name}.h5md", "r") as f:
        g = f["particles/all"]
        return g["position/step"][k], g["position/value"][k], g["velocity/value"][k]

mass = float(config["materials"][stage["material"]]["mass"])
with h5py.File(f"{run}/results.h5", "r") as f:
    dl = {k: v[:] for k, v in f["impact/dpd_ledger"].items()}
    ml = {k: v[:] for k, v in f["impact/mpm_ledger"].items()}
steps, dt = int(stage["steps"]), float(stage.get("time_step", 0.001))
worst = {}
for k in (0, -1):
    step, xd, vd = frame("dpd_particles", k)
    _, xm, vm = frame("mpm_particles", k)
    row = int(step)
    own, interface = pairs(xd), pairs(xd, xm)
    checks = [("dpd potential_energy", dl["potential_energy"][row], own),
              ("interface_pair_energy", dl["interface_pair_energy"][row], interface),
              ("dpd kinetic_energy", dl["kinetic_energy"][row], 0.5 * mass * (vd ** 2).sum() * mvv2e),
              ("mpm kinetic_energy", ml["kinetic_energy"][row], 0.5 * mass * (vm ** 2).sum() * mvv2e)]
    for axis in range(3):
        c = f"momentum_{'xyz'[axis]}"
        checks.append((c, dl[c][row] + ml[c][row], mass * (vd[:, axis].sum() + vm[:, axis].sum())))
    for name, got, ref in checks:
        rel = abs(got - ref) / max(abs(ref), 1.0)
        worst[name] = max(worst.get(name, 0.0), rel)
        print(f"step {row}: {name} ledger {got:.10g}, from the particle files {ref:.10g}, diff {rel:.1e}")
for name in ("dpd", "mpm"):
    table = dl if name == "dpd" else ml
    rows = len(table["time"])
    spacing = np.diff(table["time"])
    print(f"{name}_ledger: {rows} rows, time steps {spacing.min():.6g} to {spacing.max():.6g} ps")
    assert rows == steps + 1, f"{name}_ledger has {rows} rows for {steps} steps"
    assert np.allclose(spacing, dt, rtol=1e-9), "the rows are not one step apart"
    assert np.ptp(table["mass"]) == 0.0, "the mass changed"
for name, rel in worst.items():
    assert rel <= 1e-9, f"{name} differs by {rel:.1e}"
PYEOF
echo "1 passed, 0 failed"
