source "$(dirname "$0")/lib.sh"
export PBMS_NO_PLOTS=1  # the runs here are checked by their numbers, not their plots
# 200 steps of the disks on 1, 2 and 4 MPM ranks (oversubscribed) agree to
# 1e-10 relative in every particle position and velocity, with plain and
# with DDMP gradients (whose nodal volumes, gradients and dual forces are
# completed across ranks; the grid is periodic in z, so periodic images are
# summed as well).
cfg="$(dirname "$0")/configs/mpm_disks_200.yaml"
sed 's/^    flip: 1.0$/    flip: 1.0\n    gradient: ddmp\n    ddmp_blend: face_vanishing/' "$cfg" > ddmp.yaml
grep -q "gradient: ddmp" ddmp.yaml || fail "could not make the DDMP variant of $cfg"
for variant in plain ddmp; do
  c="$cfg"
  [ "$variant" = ddmp ] && c=ddmp.yaml
  # Every variant and rank count reruns the run name mpm_disks_200 on purpose: --overwrite.
  for n in 1 2 4; do
    "$PBMS" run "$c" --ranks mpm=$n --overwrite > out_${variant}_$n.txt 2>&1 ||
      { cat out_${variant}_$n.txt; fail "$variant run on $n ranks"; }
    cp runs/mpm_disks_200/disks/particles.h5md particles_${variant}_$n.h5md
  done
done
"$PY" - <<'PYEOF'
import sys, h5py, numpy as np
def last(name):
    g = h5py.File(f"particles_{name}.h5md")["particles/all"]
    assert g["position/step"][-1] == 200
    return g["position/value"][-1], g["velocity/value"][-1]
bad = 0
for variant in ("plain", "ddmp"):
    x1, v1 = last(f"{variant}_1")
    for n in (2, 4):
        x, v = last(f"{variant}_{n}")
        dx = np.abs(x - x1).max() / np.abs(x1).max()
        dv = np.abs(v - v1).max() / np.abs(v1).max()
        ok = dx < 1e-10 and dv < 1e-10
        bad += not ok
        print(f"{'ok  ' if ok else 'FAIL'} {variant}: {n} ranks vs 1: positions {dx:.1e}, "
              f"velocities {dv:.1e} (tolerance 1e-10)")
# The two variants must differ, or the DDMP one did not switch on.
xp, _ = last("plain_1")
xd, _ = last("ddmp_1")
if np.abs(xp - xd).max() < 1e-8:
    print("FAIL: the DDMP run equals the plain one"); bad += 1
sys.exit(1 if bad else 0)
PYEOF
echo "1 passed, 0 failed"
