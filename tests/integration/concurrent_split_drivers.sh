source "$(dirname "$0")/lib.sh"
# Split equals monolithic with the real drivers (issue 17): the small
# concurrent bar (the left half DPD through the grid with the pair
# thermostat on, the right half elastic MPM, hit by a DPD flyer) run by
# dpd_driver and mpm_driver on 1+1, 2+2 and 1+3 ranks, oversubscribed, for
# 200 steps, against the same stage advanced in one process by
# concurrent_monolithic (both parts built as the drivers build them, an
# InProcessLink between them, no band or reach). After 200 steps every
# particle and point agrees: max |dx| <= 1e-11 of the body's length and
# max |dv| <= 1e-10 of the largest speed, with the seed's interface
# treatment and with the momentum-conserving one, a grip on each side
# pulled on a velocity ramp, all with the midpoint move (grid.move's
# default); the same with the step-start move on 1+1 ranks; and, with the
# solvers swapped, the DPD flyer striking MPM points.
CONFIG="$(dirname "$0")/configs/concurrent_small.yaml"
MONO="$ROOT/build/bin/concurrent_monolithic"
[ -x "$MONO" ] || fail "concurrent_monolithic is not built"

compare() {  # RUN_DIR REFERENCE
  "$PY" - "$1" "$2" <<'PYEOF'
import sys
import h5py
import numpy as np
import yaml

run, ref_path = sys.argv[1], sys.argv[2]
ref = {int(r[0]): r[1:] for r in np.loadtxt(ref_path, ndmin=2)}
config = yaml.safe_load(open(f"{run}/config.yaml"))
stage = config["stages"][0]
lo, hi = np.array(stage["box"]["lo"]), np.array(stage["box"]["hi"])
periodic = np.array(["xyz"[a] in stage["box"]["periodic"] for a in range(3)])
length = 115.68  # the target's length along x
dx = dv = vmax = 0.0
seen = 0
for name in ("dpd_particles", "mpm_particles"):
    with h5py.File(f"{run}/impact/{name}.h5md", "r") as f:
        g = f["particles/all"]
        assert g["position/step"][-1] == 200, g["position/step"][:]
        assert g["position/value"].dtype == np.float64
        ids = g["id/value"][:] if "value" in g["id"] else g["id"][:]
        x, v = g["position/value"][-1], g["velocity/value"][-1]
    for i, pid in enumerate(ids):
        r = ref[int(pid)]
        d = x[i] - r[:3]
        period = hi - lo
        d = np.where(periodic, d - period * np.round(d / period), d)
        dx = max(dx, np.abs(d).max())
        dv = max(dv, np.abs(v[i] - r[3:]).max())
        seen += 1
vmax = max(np.linalg.norm(r[3:]) for r in ref.values())
print(f"{run}: {seen} of {len(ref)} compared; max |dx| = {dx / length:.2e} of the length, "
      f"max |dv| = {dv / vmax:.2e} of vmax {vmax:.2f} Å/ps")
assert seen == len(ref), "particles missing"
assert vmax > 1.0, "a body at rest"
assert dx <= 1e-11 * length, "positions differ"
assert dv <= 1e-10 * vmax, "velocities differ"
PYEOF
}

# The grips moved as their ramps say over the 2 ps: v (t - T/2), the
# MPM one 1 x (2 - 0.5) Å along x, the DPD one 0.5 x (2 - 0.25) Å along y;
# every member of each grip (the sites that start in its slab of
# concurrent_small.yaml: mpm_far 98-104 Å, dpd_near 10-16 Å along x) and no
# other particle.
grips_ramped() {  # RUN_DIR
  "$PY" - "$1" <<'PYEOF'
import sys
import h5py
import numpy as np
run = sys.argv[1]
def moved(name, axis, expect, slab):
    with h5py.File(f"{run}/impact/{name}.h5md", "r") as f:
        x = f["particles/all/position/value"]
        x0, d = x[0], x[-1] - x[0]
    member = (x0[:, 0] > slab[0]) & (x0[:, 0] < slab[1])
    on = np.abs(d[:, axis] - expect) < 1e-9
    print(f"{name}: {on.sum()} particles moved {expect} Å along {'xyz'[axis]}; the grip's slab "
          f"holds {member.sum()}")
    return member.sum() > 0 and np.array_equal(on, member)
ok = moved("mpm_particles", 0, 1.5, (98, 104)) and moved("dpd_particles", 1, 0.875, (10, 16))
sys.exit(0 if ok else 1)
PYEOF
}

for interface in seed momentum_conserving; do
  first=""
  for ranks in "1 1" "2 2" "1 3"; do
    set -- $ranks
    name="split_${interface}_$1_$2"
    # A grip on each side, on velocity ramps: both parts and the
    # reference must ramp them alike.
    sed "s/name: concurrent_small/name: $name/; s/launch: {dpd: 1, mpm: 2}/launch: {dpd: $1, mpm: $2}/;
         s/steps: 300/steps: 200/; s/interface: momentum_conserving/interface: $interface/;
         s/      - {group: flyer, kind: rigid_body, velocity: \[5, 0, 0\]}/&\n      - {group: mpm_far, kind: rigid, velocity: [1, 0, 0], ramp_time: 1}\n      - {group: dpd_near, kind: rigid, velocity: [0, 0.5, 0], ramp_time: 0.5}/" \
      "$CONFIG" > "$name.yaml"
    grep -q "ramp_time: 0.5" "$name.yaml" || fail "the grips were not added"
    echo "    particles_every: 200" >> "$name.yaml"
    "$PBMS" run "$name.yaml" > "$name.out" 2>&1 || { tail -20 "$name.out"; fail "$name failed"; }
    if [ -z "$first" ]; then
      first=$name
      "$MONO" "runs/$name" impact "mono_$interface.txt" || fail "concurrent_monolithic failed"
      grips_ramped "runs/$name" || fail "$name: the grips did not follow their ramps"
    fi
    compare "runs/$name" "mono_$interface.txt" || fail "$name differs from the monolithic run"
  done
done
# The step-start move (grid.move: step_start, what a gas in frictionless
# contact needs): one map a step, no midpoint sums across the programs;
# 1+1 ranks, momentum-conserving interface, the grips on their ramps.
name=split_step_start_1_1
sed "s/name: split_momentum_conserving_1_1/name: $name/;
     s/cells: \[38, 7, 7\]}/cells: [38, 7, 7], move: step_start}/" split_momentum_conserving_1_1.yaml > "$name.yaml"
grep -q "move: step_start" "$name.yaml" || fail "the step-start move was not set"
"$PBMS" run "$name.yaml" > "$name.out" 2>&1 || { tail -20 "$name.out"; fail "$name failed"; }
"$MONO" "runs/$name" impact "mono_$name.txt" || fail "concurrent_monolithic failed ($name)"
compare "runs/$name" "mono_$name.txt" || fail "$name differs from the monolithic run"
# The flyer strikes MPM points (the regions' solvers swapped): mpm_driver
# holds the nodes the flyer holds, from the held-node records summed across
# the programs, which the reference adds in one process. The body's
# momentum is kept to round-off (7.5e-3 M c in the impact before that).
name=split_flyer_on_mpm
sed "s/name: concurrent_small/name: $name/; s/launch: {dpd: 1, mpm: 2}/launch: {dpd: 2, mpm: 2}/;
     s/steps: 300/steps: 200/; s/solver: dpd,/solver: swap,/; s/solver: mpm,/solver: dpd,/;
     s/solver: swap,/solver: mpm,/" "$CONFIG" > "$name.yaml"
echo "    particles_every: 200" >> "$name.yaml"
"$PBMS" run "$name.yaml" > "$name.out" 2>&1 || { tail -20 "$name.out"; fail "$name failed"; }
"$MONO" "runs/$name" impact "mono_$name.txt" || fail "concurrent_monolithic failed ($name)"
compare "runs/$name" "mono_$name.txt" || fail "$name differs from the monolithic run"
dp=$(yget "runs/$name/summary.yaml" stages.impact.results.momentum_change.value)
"$PY" -c "import sys; print(f'$name: momentum change {float(sys.argv[1]):.1e} of M c'); sys.exit(0 if float(sys.argv[1]) < 1e-12 else 1)" "$dp" ||
  fail "$name: the momentum changed by $dp of M c"
echo "1 passed, 0 failed"
