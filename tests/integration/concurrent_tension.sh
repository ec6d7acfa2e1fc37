source "$(dirname "$0")/lib.sh"
# Concurrent tension (seed §5.3.2, a smaller rod: tests/integration/configs/
# concurrent_tension_small.yaml): MPM ends, DPD middle, rigid grips pulled
# apart at 1 Å/ps each. Without an interface treatment the rod separates
# at an interface (the opening between the last MPM and the first DPD
# lattice plane passes 3 Å); with the momentum-conserving one it stays
# below 0.5 Å over the same strain. The elastic slopes of the concurrent
# and the all-DPD rod (mean axial stress, 0 to 4 % strain) are printed:
# they differ (docs/concurrent.md).
"$PBMS" run "$(dirname "$0")/configs/concurrent_tension_small.yaml" > run.txt 2>&1 || { cat run.txt; fail "tension run"; }
"$PY" - <<'PYEOF'
import math
from summary_checks import Checks, summary_values
checks = Checks()
check = checks.check
value = summary_values("concurrent_tension_small")
untreated = value("tension_untreated", "max_interface_opening")
treated = value("tension", "max_interface_opening")
check(untreated > 3.0, f"no treatment: the rod separates at the interface (opening up to {untreated:.2f} Å)")
check(treated < 0.5, f"momentum-conserving interface: the opening stays at {treated:.2f} Å or less")
e_c, e_d = value("tension", "youngs_modulus"), value("tension_all_dpd", "youngs_modulus")
print(f"info elastic slope 0-4 %: concurrent {e_c:.1f} GPa, all DPD {e_d:.1f} GPa ({100 * (e_c / e_d - 1):+.1f} %)")
checks.exit()
PYEOF
echo "1 passed, 0 failed"
