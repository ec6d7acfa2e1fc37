source "$(dirname "$0")/lib.sh"
# Concurrent tension (seed §5.3.2, a smaller rod: tests/integration/configs/
# concurrent_tension_small.yaml): MPM ends, DPD middle, rigid grips pulled
# apart at 1 Å/ps each. On the 9 Å grid with DDMP and the MPM points' E
# taken from the all-DPD rod, the concurrent rod's elastic slope (mean axial
# stress, 0 to 4 % strain) is within 5 % of the all-DPD rod's, and the
# momentum-conserving interface stays closed. On the seed's 4 Å grid the
# rod without an interface treatment separates at an interface (the
# opening between the last MPM and the first DPD lattice plane passes 3 Å)
# while the treated one stays below 0.5 Å over the same strain.
"$PBMS" run "$(dirname "$0")/configs/concurrent_tension_small.yaml" > run.txt 2>&1 || { cat run.txt; fail "tension run"; }
"$PY" - <<'PYEOF'
from summary_checks import Checks, summary_values
checks = Checks()
check = checks.check
value = summary_values("concurrent_tension_small")
e_c, e_d = value("tension", "youngs_modulus"), value("tension_all_dpd", "youngs_modulus")
e_m = value("tension_all_mpm", "youngs_modulus")
check(abs(e_c / e_d - 1) < 0.05,
      f"elastic slope 0-4 %: concurrent {e_c:.1f} GPa, all DPD {e_d:.1f} GPa ({100 * (e_c / e_d - 1):+.1f} %, within 5 %)")
print(f"info all MPM {e_m:.1f} GPa ({100 * (e_m / e_d - 1):+.1f} % from the E it was given)")
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
