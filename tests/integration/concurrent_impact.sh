source "$(dirname "$0")/lib.sh"
# Concurrent DPD/MPM impact (seed §5.3.1, configs/concurrent_impact.yaml):
# the laterally periodic target half DPD (dpd_driver) and half elastic MPM
# (mpm_driver), hit by a DPD flyer, against the same target all DPD and all
# MPM (the regions' solvers swapped). Checks what the split run must show:
# the wave crosses the interface into the MPM half; each half's speed
# against the same half of the single-solver runs; the interface opens
# without a treatment, and with the momentum-conserving one it opens little
# and moves as the same two lattice planes do all DPD. The figures of the seed's
# treatment, which reflects the wave at the interface here, are printed.
"$PBMS" run "$ROOT/configs/concurrent_impact.yaml" > run.txt 2>&1 || { cat run.txt; fail "concurrent impact run"; }
"$PY" - <<'PYEOF'
import math
from summary_checks import Checks, summary_values
checks = Checks()
check = checks.check
value = summary_values("concurrent_impact")
def rel(a, b):
    return 100 * (a / b - 1)

mc_far, mc_near = value("concurrent", "wave_speed_far_half"), value("concurrent", "wave_speed_near_half")
un_near = value("concurrent_untreated", "wave_speed_near_half")
dpd_near, dpd_far = value("all_dpd", "wave_speed_near_half"), value("all_dpd", "wave_speed_far_half")
mpm_near, mpm_far = value("all_mpm", "wave_speed_near_half"), value("all_mpm", "wave_speed_far_half")
check(math.isfinite(mc_far), f"momentum-conserving interface: the wave crosses into the MPM half")
check(abs(rel(mc_near, dpd_near)) < 10, f"DPD half {mc_near:.0f} m/s vs all-DPD {dpd_near:.0f} m/s ({rel(mc_near, dpd_near):+.1f} %, within 10 %)")
check(abs(rel(mc_far, mpm_far)) < 10, f"MPM half {mc_far:.0f} m/s vs all-MPM {mpm_far:.0f} m/s ({rel(mc_far, mpm_far):+.1f} %, within 10 %)")
print(f"info all-DPD far half {dpd_far:.0f} m/s, all-MPM near half {mpm_near:.0f} m/s, untreated DPD half {un_near:.0f} m/s")
# The same halves timed half way up each slab's velocity rise, the speed a
# jump condition gives. Seeds 1-3 and 2026: DPD half -0.6 to -0.7 %, MPM
# half -4.0 to -8.7 % (first motion: +2.3 to +2.9 % and -4.4 to -5.5 %).
mc_fn, mc_ff = value("concurrent", "front_speed_near_half"), value("concurrent", "front_speed_far_half")
dpd_fn, mpm_ff = value("all_dpd", "front_speed_near_half"), value("all_mpm", "front_speed_far_half")
check(abs(rel(mc_fn, dpd_fn)) < 3, f"mid-amplitude: DPD half {mc_fn:.0f} m/s vs all-DPD {dpd_fn:.0f} m/s ({rel(mc_fn, dpd_fn):+.1f} %, within 3 %)")
check(abs(rel(mc_ff, mpm_ff)) < 10, f"mid-amplitude: MPM half {mc_ff:.0f} m/s vs all-MPM {mpm_ff:.0f} m/s ({rel(mc_ff, mpm_ff):+.1f} %, within 10 %)")
un_open = value("concurrent_untreated", "max_interface_opening")
un_end = value("concurrent_untreated", "interface_opening")
mc_open = value("concurrent", "max_interface_opening")
mc_close = value("concurrent", "max_interface_closing")
check(un_open > 2.0, f"no treatment: the interface opens by up to {un_open:.2f} Å (more than 2 Å; {un_end:.2f} Å at the end)")
check(mc_open < 0.5, f"momentum-conserving: the largest opening is {mc_open:.2f} Å (below 0.5 Å)")
# The front also brings any two planes nearer: the same two planes in the
# body all DPD close by about 0.4 Å as it passes. With the interface the
# jump must follow theirs, sample by sample.
import h5py
import numpy as np
def jump(stage):
    with h5py.File("runs/concurrent_impact/results.h5", "r") as f:
        o = f[stage]["interface"]["opening"][:]
    return o - o[0]
ref = jump("all_dpd")
dpd_close = value("all_dpd", "max_interface_closing")
for stage, bound in (("concurrent", 0.5), ("concurrent_untreated", None)):
    worst = float(np.max(np.abs(jump(stage) - ref)))
    if bound is None:
        print(f"info {stage}: the jump departs from all-DPD's by up to {worst:.2f} Å")
        continue
    check(worst < bound, f"momentum-conserving: the jump (closing up to {mc_close:.2f} Å) follows the "
          f"same planes all DPD (closing up to {dpd_close:.2f} Å) within {worst:.2f} Å (below {bound} Å)")
print(f"info no treatment: wave in the MPM half: {value('concurrent_untreated', 'first_motion_mpm_near')} ps")
print(f"info seed's treatment: MPM half first motion {value('concurrent_seed', 'first_motion_mpm_near')} ps, "
      f"largest opening {value('concurrent_seed', 'max_interface_opening'):.2f} Å, end {value('concurrent_seed', 'interface_opening'):.2f} Å")
checks.exit()
PYEOF
echo "1 passed, 0 failed"
