source "$(dirname "$0")/lib.sh"
# 200 steps of the disks on 1, 2 and 4 MPM ranks (oversubscribed) agree to
# 1e-10 relative in every particle position and velocity.
cfg="$(dirname "$0")/configs/mpm_disks_200.yaml"
for n in 1 2 4; do
  "$PBMS" run "$cfg" --ranks mpm=$n > out_$n.txt 2>&1 || { cat out_$n.txt; fail "run on $n ranks"; }
  cp runs/mpm_disks_200/disks/particles.h5md particles_$n.h5md
done
"$PY" - <<'PYEOF'
import sys, h5py, numpy as np
def last(n):
    g = h5py.File(f"particles_{n}.h5md")["particles/all"]
    assert g["position/step"][-1] == 200
    return g["position/value"][-1], g["velocity/value"][-1]
x1, v1 = last(1)
bad = 0
for n in (2, 4):
    x, v = last(n)
    dx = np.abs(x - x1).max() / np.abs(x1).max()
    dv = np.abs(v - v1).max() / np.abs(v1).max()
    ok = dx < 1e-10 and dv < 1e-10
    bad += not ok
    print(f"{'ok  ' if ok else 'FAIL'} {n} ranks vs 1: positions {dx:.1e}, velocities {dv:.1e} (tolerance 1e-10)")
sys.exit(1 if bad else 0)
PYEOF
echo "1 passed, 0 failed"
