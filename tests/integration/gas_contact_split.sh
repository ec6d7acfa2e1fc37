source "$(dirname "$0")/lib.sh"
export PBMS_NO_PLOTS=1  # checked by its numbers
# A gas in frictionless contact with a body (gas.contact: frictionless),
# across programs as in one process: the ball of gas_box.yaml in its gas
# at 3 GPa for 200 steps, run by dpd_driver and mpm_driver on 1+1 and 2+2
# ranks with the midpoint move (the fields meet again at the midpoints) and
# on 1+1 ranks with the step-start move, each against the same stage
# advanced in one process by
# concurrent_monolithic (an InProcessLink between the parts). A consistency
# check of the exchange of each side's own nodal fields: every particle and
# gas point agrees to max |dx| <= 1e-11 of the box and max |dv| <= 1e-10 of
# the largest speed. Beside it, against references the program did not
# make: the body's momentum, walls' impulse counted, to 1e-12 of M c (the
# contact's impulses cancel bit for bit, unit test
# FrictionlessContact.TheSwappedCallGivesTheExactNegative) and its mass;
# and the contact does what it is for: the gas is driven against the ball
# without entering it (no gas point in its particles' convex hull).
MONO="$ROOT/build/bin/concurrent_monolithic"
[ -x "$MONO" ] || fail "concurrent_monolithic is not built"
for case in "midpoint 1 1" "midpoint 2 2" "step_start 1 1"; do
  set -- $case
  name="contact_$1_$2_$3"
  "$PY" - "$(dirname "$0")/configs/gas_box.yaml" "$name" "$2" "$3" "$1" > "$name.yaml" <<'PYEOF'
import sys
import yaml
import derived_config
config = derived_config.load(sys.argv[1])
config["run"]["name"] = sys.argv[2]
config["launch"] = {"dpd": int(sys.argv[3]), "mpm": int(sys.argv[4])}
ball, gas = config["stages"]
ball["steps"] = 500
gas["gas"].update({"contact": "frictionless", "settle_time": "0 ps"})
gas["grid"]["move"] = sys.argv[5]
gas.update({"steps": 200, "sample_every": 50, "particles_every": 200})
yaml.safe_dump(config, sys.stdout, sort_keys=False)
PYEOF
  "$PBMS" run "$name.yaml" > "$name.out" 2>&1 || { tail -20 "$name.out"; fail "$name failed"; }
  [ -f "mono_$1.txt" ] || "$MONO" "runs/$name" gas "mono_$1.txt" || fail "concurrent_monolithic failed"
  "$PY" - "runs/$name" "mono_$1.txt" <<'PYEOF' || fail "$name misses its references"
import sys
import h5py
import numpy as np
from scipy.spatial import Delaunay
run, ref_path = sys.argv[1], sys.argv[2]
ref = {int(r[0]): r[1:] for r in np.loadtxt(ref_path, ndmin=2)}
box = 72.3
dx = dv = 0.0
seen = 0
final = {}
for name in ("dpd_particles", "mpm_particles"):
    with h5py.File(f"{run}/gas/{name}.h5md", "r") as f:
        g = f["particles/all"]
        assert g["position/step"][-1] == 200, g["position/step"][:]
        ids = g["id/value"][:] if "value" in g["id"] else g["id"][:]
        x, v = g["position/value"][-1], g["velocity/value"][-1]
    final[name] = x
    for i, pid in enumerate(ids):
        r = ref[int(pid)]
        dx = max(dx, np.abs(x[i] - r[:3]).max())
        dv = max(dv, np.abs(v[i] - r[3:]).max())
        seen += 1
vmax = max(np.linalg.norm(r[3:]) for r in ref.values())
inside = int(np.count_nonzero(Delaunay(final["dpd_particles"]).find_simplex(final["mpm_particles"]) >= 0))
with h5py.File(f"{run}/results.h5", "r") as f:
    dp = float(f["gas/momentum_change"][()])
    mass = f["gas/dpd_ledger/mass"][:] + f["gas/mpm_ledger/mass"][:]
print(f"{run}: {seen} of {len(ref)} compared; max |dx| = {dx / box:.2e} of the box, max |dv| = "
      f"{dv / vmax:.2e} of vmax {vmax:.2f} Å/ps; momentum change {dp:.1e} of M c; "
      f"{inside} gas points in the ball")
bad = []
if seen != len(ref): bad.append("particles missing")
if not dx <= 1e-11 * box: bad.append("positions differ from the one-process run")
if not dv <= 1e-10 * vmax: bad.append("velocities differ from the one-process run")
if not dp < 1e-12: bad.append(f"momentum changed by {dp:.3g} of M c")
if np.ptp(mass) > 1e-12 * mass[0]: bad.append("the mass changed")
if inside: bad.append(f"{inside} gas points in the ball")
for b in bad:
    print("FAIL:", b)
sys.exit(1 if bad else 0)
PYEOF
done
echo "1 passed, 0 failed"
