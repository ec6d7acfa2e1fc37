source "$(dirname "$0")/lib.sh"
export PBMS_NO_PLOTS=1  # the runs here are checked by their numbers, not their plots
# 100 DPD thermostat steps (1,152 particles, free surfaces in z, a rigid
# moving wall) on 1, 2 and 4 ranks (oversubscribed): every final position
# agrees with the 1-rank run to 1e-9 Å and every final velocity to 1e-10 Å/ps.
# The same for 100 Shardlow steps and 100 DPDE steps (dpd_ranks_shardlow.yaml):
# their pair sweep order does not depend on the decomposition either.
# Velocity bound: the ranks sum each particle's pair forces in another order,
# and 100 steps of that round-off leave at most 1.6e-12 Å/ps here (positions
# 7e-14 Å), with velocities up to 2.8 Å/ps. 1e-10 Å/ps leaves a factor ~60 for
# other compilers and CPUs; a real decomposition error (a pair missed across
# a boundary, a noise draw keyed to the rank: F dt / m or sigma sqrt(dt) / m)
# moves velocities by 1e-3 Å/ps or more.
cfg="$(dirname "$0")/configs/dpd_ranks.yaml"
shardlow_cfg="$(dirname "$0")/configs/dpd_ranks_shardlow.yaml"
# Each rank count reruns the same run names on purpose: --overwrite.
for n in 1 2 4; do
  "$PBMS" run "$cfg" --ranks dpd=$n --overwrite > out_$n.txt 2>&1 || { cat out_$n.txt; fail "run on $n ranks"; }
  cp runs/dpd_ranks/thermostat/particles.h5md particles_$n.h5md
  cp runs/dpd_ranks/initial_forces/particles.h5md forces_$n.h5md
  "$PBMS" run "$shardlow_cfg" --ranks dpd=$n --overwrite > out_shardlow_$n.txt 2>&1 ||
    { cat out_shardlow_$n.txt; fail "Shardlow run on $n ranks"; }
  cp runs/dpd_ranks_shardlow/shardlow/particles.h5md shardlow_$n.h5md
  cp runs/dpd_ranks_shardlow/dpde/particles.h5md dpde_$n.h5md
done
"$PY" - <<'PYEOF'
import sys, h5py, numpy as np
bad = 0
for scheme in ("velocity_verlet", "shardlow", "dpde"):
    prefix = "particles" if scheme == "velocity_verlet" else scheme
    def last(n):
        g = h5py.File(f"{prefix}_{n}.h5md")["particles/all"]
        assert g["position/step"][-1] == 100
        return g["position/value"][-1], g["velocity/value"][-1]
    x1, v1 = last(1)
    for n in (2, 4):
        x, v = last(n)
        dx = np.abs(x - x1).max()
        dv = np.abs(v - v1).max()
        ok = dx < 1e-9 and dv < 1e-10
        bad += not ok
        print(f"{'ok  ' if ok else 'FAIL'} {scheme}: {n} ranks vs 1: max |dx| {dx:.1e} Å "
              f"(tolerance 1e-9), max |dv| {dv:.1e} Å/ps (tolerance 1e-10)")
# steps: 0 wrote the forces of the final state: they sum to zero (Newton's
# third law, no rigid group in that stage) and match across rank counts.
f1 = h5py.File("forces_1.h5md")["particles/all/force/value"][0]
for n in (1, 2, 4):
    f = h5py.File(f"forces_{n}.h5md")["particles/all/force/value"][0]
    net = np.abs(f.sum(axis=0)).max() / np.abs(f).max()
    diff = np.abs(f - f1).max() / np.abs(f1).max()
    ok = net < 1e-10 and diff < 1e-9
    bad += not ok
    print(f"{'ok  ' if ok else 'FAIL'} steps: 0 forces on {n} ranks: |sum f| / max|f| {net:.1e}, vs 1 rank {diff:.1e}")
sys.exit(1 if bad else 0)
PYEOF
echo "1 passed, 0 failed"
