source "$(dirname "$0")/lib.sh"
# Grips on a velocity ramp (motion `ramp_time` in DPD, group_velocity
# `ramp_time` in MPM): a grip reaches its velocity v linearly over T, so
# that by time t it has moved v t^2 / (2 T) within the ramp and v (t - T/2)
# after it. A small copper rod pulled by rigid grips for 2 ps
# (T = 0.995 ps: the ramp ends inside a step) in DPD-only, in the
# DPD/MPM-grid model and in MPM; each grip's
# displacement (its slab_displacement probe) must follow that law to 1e-9
# of the final displacement at every sample: the grips move rigidly, and
# both drivers take each step's velocity as the ramp's mean over the step.
# One DPD rod stage, run as DPD-only and through a 4 Å grid.
dpd_stage() {  # NAME [EXTRA LINE]
  cat <<YAML
  - name: $1
    kind: dpd_run
    mode: tension
    material: cu_cg
    box: {lo: [-30, -10, -10], hi: [110, 40, 40]}
    bodies:
      - {name: rod, region: {style: block, lo: [0, 0, 0], hi: [72.3, 28.92, 28.92]}}
    groups:
      - {name: left, region: {style: block, lo: [-1, -1, -1], hi: [12, 30, 30]}}
      - {name: right, region: {style: block, lo: [60, -1, -1], hi: [73, 30, 30]}}
    motion:
      - {group: left, kind: rigid, velocity: [-2, 0, 0], ramp_time: 0.995}
      - {group: right, kind: rigid, velocity: [2, 0, 0], ramp_time: 0.995}
    temperature: 298
    bath_temperature: 298
    steps: 200
    sample_every: 5
    tension: {specimen: rod, axis: x}
    probes:
      - {name: left, kind: slab_displacement, group: left}
      - {name: right, kind: slab_displacement, group: right}
${2:-}
YAML
}
{
  cat <<'YAML'
run: {name: ramp, seed: 5}
launch: {dpd: 1, mpm: 1}
materials:
  cu_cg:
    kind: dpd_mesoparticle
    mass: 508.37
    lattice_constant: 7.23
    potential: {style: morse, d0: 2.70736, alpha: 0.740826, r0: 5.472809, cutoff: 10, shift: true}
  cu: {kind: linear_elastic, density: 8.9 g/cm^3, youngs_modulus: 90 GPa, poisson_ratio: 0.38}
stages:
YAML
  dpd_stage dpd_only
  dpd_stage grid_model "    grid: {cell_size: 4}"
  cat <<'YAML'
  - name: mpm
    kind: mpm_run
    grid: {origin: [-21.69, -7.23, -7.23], cells: [32, 6, 6], cell_size: 3.615}
    bodies:
      - {name: rod, material: cu, region: {style: block, lo: [0, 0, 0], hi: [72.3, 28.92, 28.92]}, points_per_cell: [2]}
    groups:
      - {name: left, region: {style: block, lo: [-1, -1, -1], hi: [12, 30, 30]}}
      - {name: right, region: {style: block, lo: [60, -1, -1], hi: [73, 30, 30]}}
    boundary:
      - {kind: group_velocity, group: left, axes: [x, y, z], velocity: [-2, 0, 0], ramp_time: 0.995 ps}
      - {kind: group_velocity, group: right, axes: [x, y, z], velocity: [2, 0, 0], ramp_time: 0.995 ps}
    time_step: 0.01
    duration: 2
    sample_every: 5
    probes:
      - {name: left, kind: slab_displacement, group: left}
      - {name: right, kind: slab_displacement, group: right}
YAML
} > ramp.yaml
"$PBMS" run ramp.yaml > run.txt 2>&1 || { tail -30 run.txt; fail "the run failed"; }
"$PY" - <<'PYEOF'
import sys
import h5py
import numpy as np

T, v = 0.995, 2.0
def law(t):
    return np.where(t < T, 0.5 * t * t / T, t - 0.5 * T) * v
bad = 0
with h5py.File("runs/ramp/results.h5", "r") as f:
    for stage in ("dpd_only", "grid_model", "mpm"):
        g = f[stage]["probes"]
        t = g["time"][:]
        expected = law(t)
        worst = 0.0
        for grip, sign in (("left", -1.0), ("right", 1.0)):
            d = sign * g[f"{grip}.x"][:]
            worst = max(worst, np.abs(d - expected).max() / expected[-1])
        ok = t[-1] > 1.99 and worst < 1e-9
        bad += not ok
        print(f"{'ok  ' if ok else 'FAIL'} {stage}: grips at {expected[-1]:.4f} Å after {t[-1]:.2f} ps "
              f"(v (t - T/2)); largest departure from the ramp law {worst:.1e} of it")
sys.exit(1 if bad else 0)
PYEOF
echo "1 passed, 0 failed"
