source "$(dirname "$0")/lib.sh"
export PBMS_NO_PLOTS=1  # checked by its numbers
# The gas of the sintering pair's grid (cells and gas lattice of a_cg/2)
# holds its pressure beside thermal copper: a ball of 141 mesoparticles at
# 298 K in a 72.3 Å box at 3 GPa, 50 ps (about 15 s). Against references
# the program did not make:
#  - the walls' pressure (their inward push over time and area, a
#    manometer in which no point's state enters) within 2 % of the 3 GPa
#    set by the gas's density and energy over 20-50 ps, and within the
#    issue's 5 % in every 5 ps window from 10 ps. Seeds 2026-2028: 2.954,
#    2.955 and 2.952 GPa over 20-50 ps; the windows 2.917-2.958. Before 2026-12-07 the suite read the gas's pressure from
#    its points' densities alone: that reading falls to 2.2 GPa here (it is
#    printed), while the walls hold;
#  - no gas point inside the ball at the start: none in the convex hull of
#    its particles (scipy's Delaunay). The gas lattice of a_cg/2 has sites
#    on the crystal's octahedral holes, 3.6 Å from the nearest particles,
#    beyond the clearance: before 2026-12-07 they were gas;
#  - the mass kept and the momentum, walls' impulse counted, to round-off.
"$PY" -c 'import sys, yaml, derived_config; yaml.safe_dump(derived_config.load(sys.argv[1]), sys.stdout)' \
  "$(dirname "$0")/configs/gas_box.yaml" > gas_box.yaml
"$PBMS" run gas_box.yaml > run.out 2>&1 || { tail -30 run.out; fail "the run failed"; }
"$PY" - runs/gas_box <<'PYEOF' || fail "the gas misses its references"
import sys
import h5py
import numpy as np
run = sys.argv[1]
bad = []
with h5py.File(f"{run}/results.h5", "r") as f:
    g = f["gas/gas_pressure_series"]
    t, walls, points = g["time"][:], g["pressure_on_walls"][:], g["pressure_away_from_body"][:]
    late = float(f["gas/gas_pressure_on_walls"][()])
    print(f"the walls: {late:.4f} GPa over 20-50 ps; the points' own reading {points[-1]:.3f} GPa at {t[-1]:.0f} ps")
    if abs(late / 3.0 - 1.0) > 0.02:
        bad.append(f"the walls feel {late:.4f} GPa over 20-50 ps, more than 2 % off 3 GPa")
    windows = []
    for lo in np.arange(10.0, t[-1] - 1e-9, 5.0):
        w = walls[(t > lo) & (t <= lo + 5.0)].mean()
        windows.append(f"{w:.3f}")
        if abs(w / 3.0 - 1.0) > 0.05:
            bad.append(f"the walls feel {w:.4f} GPa over {lo:.0f}-{lo + 5:.0f} ps")
    print("the walls in 5 ps windows from 10 ps:", " ".join(windows), "GPa")
    if f["gas/momentum_change"][()] > 1e-12:
        bad.append(f"momentum changed by {f['gas/momentum_change'][()]:.3g} of M c")
    mass = f["gas/dpd_ledger/mass"][:] + f["gas/mpm_ledger/mass"][:]
    if np.ptp(mass) > 1e-12 * mass[0]:
        bad.append(f"the mass changed by {np.ptp(mass):.3g} g/mol")
from scipy.spatial import Delaunay
with h5py.File(f"{run}/gas/mpm_particles.h5md", "r") as gas, h5py.File(f"{run}/gas/dpd_particles.h5md", "r") as cu:
    x_gas = gas["particles/all/position/value"][0]
    x_cu = cu["particles/all/position/value"][0]
    inside = int(np.count_nonzero(Delaunay(x_cu).find_simplex(x_gas) >= 0))
    print(f"{x_cu.shape[0]} particles; {x_gas.shape[0]} gas points, {inside} inside the particles' convex hull")
    if inside:
        bad.append(f"{inside} gas points inside the ball (its particles' convex hull)")
for b in bad:
    print("FAIL:", b)
sys.exit(1 if bad else 0)
PYEOF
echo "1 passed, 0 failed"
