source "$(dirname "$0")/lib.sh"
# Concurrent tension (seed §5.3.2, a smaller rod: tests/integration/configs/
# concurrent_tension_small.yaml): MPM ends, DPD middle, rigid grips reaching
# 1 Å/ps each over 5 ps, on the 9 Å grid with DDMP, the MPM points' E the
# slope of the same rod all DPD. Stress is the body's mean axial stress over
# its nominal cross-section, E its slope over 0-4 % strain.
#
# Physics checks:
#  - a rod of two materials in series: the concurrent rod's E is the series
#    rule's, 1 / E = 0.5 / E_DPD + 0.5 / E_MPM (half its length each), from
#    the same rod all DPD and all MPM: the interface neither softens nor
#    stiffens it. Measured +0.10, -0.16, +0.02 % on seeds 2026-2028
#    (midpoint move; -0.26 and -0.17 % for 2027-2028 with the step-start move);
#  - the MPM continuum reads its own law: the same rod in mpm_run, its gauge
#    (the middle third) against the hypoelastic law's E ln(1 + e) at the
#    gauge's strains, recomputed here (as mpm_rod_law.sh does);
#  - on the seed's 4 Å grid the rod without an interface treatment
#    separates at an interface (the opening between the last MPM and the
#    first DPD lattice plane passes 3 Å), the treated one stays below 0.5 Å.
# Consistency checks (the program against itself):
#  - the concurrent rod within 5 % of the all-DPD rod (seed fig. 5.12);
#  - the concurrent stage's all-MPM rod against the same rod in mpm_run,
#    same measure: the concurrent MPM part (points on DPD sites, handed
#    over, held grips) runs as the MPM solver alone. Measured -0.13, -0.25,
#    -0.10 % on seeds 2026-2028.
"$PBMS" run "$(dirname "$0")/configs/concurrent_tension_small.yaml" > run.txt 2>&1 || { cat run.txt; fail "tension run"; }
"$PY" - <<'PYEOF'
from summary_checks import Checks, law_gauge_modulus, summary_values
checks = Checks()
check = checks.check
value = summary_values("concurrent_tension_small")
e_c, e_d = value("tension", "youngs_modulus"), value("tension_all_dpd", "youngs_modulus")
e_m = value("tension_all_mpm", "youngs_modulus")
series = 1.0 / (0.5 / e_d + 0.5 / e_m)
check(abs(e_c / series - 1) < 0.01,
      f"physics: concurrent {e_c:.2f} GPa against the series rule of all DPD {e_d:.2f} and all MPM "
      f"{e_m:.2f} GPa, {series:.2f} GPa ({100 * (e_c / series - 1):+.2f} %, within 1 %)")
check(abs(e_c / e_d - 1) < 0.05,
      f"consistency: concurrent {e_c:.1f} GPa, all DPD {e_d:.1f} GPa "
      f"({100 * (e_c / e_d - 1):+.1f} %, within 5 %)")
e_run = value("tension_mpm_run", "youngs_modulus")
check(abs(e_m / e_run - 1) < 0.01,
      f"consistency: all MPM {e_m:.2f} GPa against the same rod in mpm_run {e_run:.2f} GPa "
      f"({100 * (e_m / e_run - 1):+.2f} %, within 1 %; {100 * (e_m / e_d - 1):+.1f} % from the E "
      f"it was given: the law's large-strain Cauchy stress and the 5 ps ramp)")
law, fitted = law_gauge_modulus(e_d, "concurrent_tension_small", "tension_mpm_run", value)
gauge = value("tension_mpm_run", "gauge_youngs_modulus")
check(abs(gauge / law - 1) <= 0.02,
      f"physics: the MPM rod's gauge {gauge:.2f} GPa against its law's {law:.2f} GPa "
      f"({100 * (gauge / law - 1):+.2f} %, within 2 %; fit to a strain of {fitted[-1]:.4f})")
treated_9 = value("tension", "max_interface_opening")
check(treated_9 < 0.5, f"9 Å grid, momentum-conserving interface: the opening stays at {treated_9:.2f} Å or less")
untreated = value("tension_4A_untreated", "max_interface_opening")
treated = value("tension_4A", "max_interface_opening")
check(untreated > 3.0, f"4 Å grid, no treatment: the rod separates at the interface (opening up to {untreated:.2f} Å)")
check(treated < 0.5, f"4 Å grid, momentum-conserving interface: the opening stays at {treated:.2f} Å or less")
# Nor may the planes be pushed into each other.
for stage in ("tension", "tension_4A"):
    closing = value(stage, "max_interface_closing")
    check(closing < 0.5, f"{stage}: the planes come nearer by {closing:.2f} Å at most (below 0.5 Å)")
checks.exit()
PYEOF
echo "1 passed, 0 failed"
