source "$(dirname "$0")/lib.sh"
# Concurrent DPD/MPM impact (seed §5.3.1, configs/concurrent_impact.yaml):
# the laterally periodic target half DPD (dpd_driver) and half elastic MPM
# (mpm_driver), hit by a DPD flyer, against the same target all DPD and all
# MPM (the regions' solvers swapped). Checks what the split run must show:
# the wave crosses the interface into the MPM half; each half's speed
# against the same half of the single-solver runs; the interface opens
# without a treatment and much less with one. The figures of the seed's
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
un_open = value("concurrent_untreated", "max_interface_opening")
un_end = value("concurrent_untreated", "interface_opening")
mc_open = value("concurrent", "max_interface_opening")
check(un_open > 2.0, f"no treatment: the interface opens by up to {un_open:.2f} Å (more than 2 Å; {un_end:.2f} Å at the end)")
# The planes' centres of mass fluctuate thermally by about 0.05 Å, and the
# interface contracts briefly at the start (docs/concurrent.md).
check(mc_open < 0.6, f"momentum-conserving: the largest opening is {mc_open:.2f} Å (below 0.6 Å)")
print(f"info no treatment: wave in the MPM half: {value('concurrent_untreated', 'first_motion_mpm_near')} ps")
print(f"info seed's treatment: MPM half first motion {value('concurrent_seed', 'first_motion_mpm_near')} ps, "
      f"largest opening {value('concurrent_seed', 'max_interface_opening'):.2f} Å, end {value('concurrent_seed', 'interface_opening'):.2f} Å")
checks.exit()
PYEOF
echo "1 passed, 0 failed"
