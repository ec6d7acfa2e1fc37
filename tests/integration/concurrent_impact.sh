source "$(dirname "$0")/lib.sh"
# Concurrent DPD/MPM impact (seed §5.3.1, configs/concurrent_impact.yaml):
# the laterally periodic target half DPD (dpd_driver) and half elastic MPM
# (mpm_driver), hit by a DPD flyer, with the momentum-conserving interface
# and the ghost-force correction (its dead loads measured on the target at
# rest), against the same target all DPD and all MPM (the regions' solvers
# swapped).
# Physics, against the model's own longitudinal speed √(C11/ρ) (C11 and ρ
# of the DPD crystal at 298 K, recomputed here from elastic_298K's):
# - each half's wave speed (first motion of two slabs 50 Å apart) within
#   5 % of it;
# - the interface's displacement jump within 0.15 Å of the same planes'
#   all DPD, sample by sample;
# - the body's momentum (flyer included) kept to round-off.
# Consistency with the single-solver runs, and what the ghost forces and
# the other treatments do, are checked or printed beside them. With the
# argument `seeds` the physics checks run on seeds 1, 2 and 3 instead
# (validation).
if [ "${1:-}" = "seeds" ]; then
  for seed in 1 2 3; do
    sed -e "s/^run: {name: concurrent_impact, seed: 2026}/run: {name: concurrent_impact_$seed, seed: $seed}/" \
      "$ROOT/configs/concurrent_impact.yaml" > "impact_$seed.yaml"
    grep -q "seed: $seed}" "impact_$seed.yaml" || fail "seed $seed not set"
    "$PBMS" run "impact_$seed.yaml" > "run_$seed.txt" 2>&1 || { cat "run_$seed.txt"; fail "concurrent impact, seed $seed"; }
  done
  RUNS="concurrent_impact_1 concurrent_impact_2 concurrent_impact_3"
else
  "$PBMS" run "$ROOT/configs/concurrent_impact.yaml" > run.txt 2>&1 || { cat run.txt; fail "concurrent impact run"; }
  RUNS="concurrent_impact"
fi
RUNS="$RUNS" "$PY" - <<'PYEOF'
import math
import os

import h5py
import numpy as np
from summary_checks import Checks, summary_values

checks = Checks()
check = checks.check


def rel(a, b):
    return 100 * (a / b - 1)


def jump(run, stage):
    with h5py.File(f"runs/{run}/results.h5", "r") as f:
        o = f[stage]["interface"]["opening"][:]
    return o - o[0]


def physics(run):
    """The checks against √(C11/ρ) and all DPD."""
    value = summary_values(run)
    c11 = value("elastic_298K", "c11")  # GPa
    rho = value("elastic_298K", "density")  # kg/m^3
    c = math.sqrt(c11 * 1e9 / rho)
    for half in ("near_half", "far_half"):
        v = value("concurrent", f"wave_speed_{half}")
        check(abs(rel(v, c)) < 5, f"{run}: {half} ({'DPD' if half == 'near_half' else 'MPM'}) "
              f"wave speed {v:.0f} m/s, {rel(v, c):+.1f} % of √(C11/ρ) = {c:.0f} m/s (within 5 %)")
        u = value("concurrent_uncorrected", f"wave_speed_{half}")
        print(f"info {run}: without the ghost-force correction the {half} reads {u:.0f} m/s "
              f"({rel(u, c):+.1f} %)")
    worst = float(np.max(np.abs(jump(run, "concurrent") - jump(run, "all_dpd"))))
    check(worst < 0.15, f"{run}: the interface jump follows the same planes all DPD within "
          f"{worst:.3f} Å (below 0.15 Å)")
    return value, c


runs = os.environ["RUNS"].split()
for run in runs:
    value, c = physics(run)
if len(runs) > 1:
    checks.exit()

# Consistency with the single-solver runs (the same program, other solvers).
mc_far, mc_near = value("concurrent", "wave_speed_far_half"), value("concurrent", "wave_speed_near_half")
un_near = value("concurrent_untreated", "wave_speed_near_half")
dpd_near, dpd_far = value("all_dpd", "wave_speed_near_half"), value("all_dpd", "wave_speed_far_half")
mpm_near, mpm_far = value("all_mpm", "wave_speed_near_half"), value("all_mpm", "wave_speed_far_half")
check(abs(rel(mc_near, dpd_near)) < 5, f"consistency: DPD half {mc_near:.0f} m/s vs all-DPD {dpd_near:.0f} m/s ({rel(mc_near, dpd_near):+.1f} %, within 5 %)")
check(abs(rel(mc_far, mpm_far)) < 5, f"consistency: MPM half {mc_far:.0f} m/s vs all-MPM {mpm_far:.0f} m/s ({rel(mc_far, mpm_far):+.1f} %, within 5 %)")
print(f"info all-DPD far half {dpd_far:.0f} m/s, all-MPM near half {mpm_near:.0f} m/s, untreated DPD half {un_near:.0f} m/s")
# Timed half way up each slab's velocity rise (what a jump condition gives)
# the strong front in the DPD half runs at a shock's speed, 8-12 % above
# √(C11/ρ) in the half and all DPD alike (seeds 1-3 and 2026); the MPM half
# is 10-15 % below it, all MPM 6.5 % (0.68 points a cell smear the front).
mc_fn, mc_ff = value("concurrent", "front_speed_near_half"), value("concurrent", "front_speed_far_half")
dpd_fn, mpm_ff = value("all_dpd", "front_speed_near_half"), value("all_mpm", "front_speed_far_half")
check(abs(rel(mc_fn, dpd_fn)) < 3, f"mid-amplitude: DPD half {mc_fn:.0f} m/s vs all-DPD {dpd_fn:.0f} m/s ({rel(mc_fn, dpd_fn):+.1f} %, within 3 %)")
check(abs(rel(mc_ff, mpm_ff)) < 10, f"mid-amplitude: MPM half {mc_ff:.0f} m/s vs all-MPM {mpm_ff:.0f} m/s ({rel(mc_ff, mpm_ff):+.1f} %, within 10 %)")
print(f"info mid-amplitude: DPD half {rel(mc_fn, c):+.1f} %, MPM half {mc_ff:.0f} m/s "
      f"({rel(mc_ff, c):+.1f} %), all-MPM {rel(mpm_ff, c):+.1f} % of √(C11/ρ)")
# The response (the impact less rest_corrected, the same body, start,
# correction and noise not struck): the two runs are one trajectory until
# the flyer's push reaches a particle, so before the near slab moves the far
# slab's response is round-off and the pulse's faint leading edge (3e-11 Å
# DPD, 5e-7 Å MPM on seed 2026), where the slabs' own drift is 0.1-0.26 Å;
# held below a thousandth of the 0.05 Å threshold. Its 0.05 Å first motions are printed:
# the DPD part cools from 298 K during the run (docs/concurrent.md, "The DPD
# part's temperature"), so they are not held to √(C11/ρ) at 298 K.
for half in ("near_half", "far_half"):
    residual = value("concurrent_response", f"baseline_residual_{half}")
    check(residual < 5e-5, f"response: the {half}'s far slab before its near slab moves, "
          f"{residual:.1e} Å (below 5e-5 Å)")
    v = value("concurrent_response", f"wave_speed_{half}")
    print(f"info response: {half} first motion (0.05 Å) {v:.0f} m/s ({rel(v, c):+.1f} % of √(C11/ρ))")
# The MPM half's lag behind DPD alone (5.7 % on these slabs) is the
# continuum's on cells of 4 Å, not the interface's: all MPM, timed on its
# response the same way, reads the same far slabs within 0.27 % of the
# concurrent MPM half on seeds 1, 2, 3 and 2026 (2026-12-08). A consistency
# check (the program against itself with other solvers), held to 1 %.
mc_resp = value("concurrent_response", "wave_speed_far_half")
mpm_resp = value("all_mpm_response", "wave_speed_far_half")
check(abs(rel(mc_resp, mpm_resp)) < 1, f"consistency, response: MPM half {mc_resp:.0f} m/s vs all-MPM "
      f"{mpm_resp:.0f} m/s ({rel(mc_resp, mpm_resp):+.2f} %, within 1 %)")
check(value("all_mpm_response", "baseline_residual_far_half") < 5e-5,
      "all-MPM response: the far slab is still before the near one moves")
# The ledger: the flyer is a free rigid body, and with either conserving
# interface (or none) the body's total momentum stays put to round-off, in
# units of M c (2.9 times its start during the impact before the flyer's
# nodes were balanced, 2026-12-04).
# All MPM, the DPD flyer strikes MPM points: mpm_driver holds the nodes the
# flyer holds (held nodes summed across the programs; 7.5e-3 M c, the
# flyer's whole momentum, before 2026-12-04, when it did not).
for stage in ("concurrent", "concurrent_uncorrected", "concurrent_untreated", "all_dpd", "all_mpm",
              "all_mpm_response"):
    dp = value(stage, "momentum_change")
    check(dp < 1e-12, f"{stage}: total momentum kept to {dp:.1e} of M c (1e-12)")
print(f"info momentum change, seed's treatment {value('concurrent_seed', 'momentum_change'):.3f} of M c")
un_open = value("concurrent_untreated", "max_interface_opening")
un_end = value("concurrent_untreated", "interface_opening")
mc_open = value("concurrent", "max_interface_opening")
mc_close = value("concurrent", "max_interface_closing")
# Without a treatment the MPM points at the interface feel no pair force
# from the DPD planes next to them: the compressive front closes the two
# planes by about 1 Å, seven times what it does to the same planes all
# DPD, and they stay closed (-0.76 Å at 10 ps); they do not open
# (seed fig 5.8 shows a separation; docs/concurrent.md says why not here).
un_close = value("concurrent_untreated", "max_interface_closing")
check(un_close > 3 * mc_close and un_close > 0.5,
      f"no treatment: the planes close by {un_close:.2f} Å (more than 0.5 Å and 3 times the "
      f"momentum-conserving interface's {mc_close:.2f} Å); largest opening {un_open:.2f} Å, {un_end:.2f} Å at the end")
# Bound from seeds 2026-2029 without the ghost-force correction
# (2026-12-05): largest opening 0.041-0.053 Å, the bound about twice that
# and far below what an untreated interface does (closing 1.06-1.10 Å); it
# was 0.5 Å until 2026-12-05. With the correction, seeds 1-3 and 2026:
# 0.057-0.073 Å (all DPD 0.062-0.067 Å).
check(mc_open < 0.1, f"momentum-conserving: the largest opening is {mc_open:.3f} Å (below 0.1 Å)")
for stage in ("concurrent_uncorrected", "concurrent_untreated"):
    worst = float(np.max(np.abs(jump("concurrent_impact", stage) - jump("concurrent_impact", "all_dpd"))))
    print(f"info {stage}: the jump departs from all-DPD's by up to {worst:.2f} Å")
print(f"info no treatment: wave in the MPM half: {value('concurrent_untreated', 'first_motion_mpm_near')} ps")
print(f"info seed's treatment: MPM half first motion {value('concurrent_seed', 'first_motion_mpm_near')} ps, "
      f"largest opening {value('concurrent_seed', 'max_interface_opening'):.2f} Å, end {value('concurrent_seed', 'interface_opening'):.2f} Å")
checks.exit()
PYEOF
echo "1 passed, 0 failed"
