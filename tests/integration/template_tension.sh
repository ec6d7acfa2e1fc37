source "$(dirname "$0")/lib.sh"
# A concurrent tension written from its template alone (issue 33): the
# template copied as a user would, anywhere, and run as it stands. It must
# end ok with a Young's modulus, both programs' parts populated, and its
# report written.
cp "$ROOT/configs/templates/concurrent_tension.yaml" my_tension.yaml
"$PBMS" run my_tension.yaml > out.txt 2>&1 || { cat out.txt; fail "the template did not run"; }
"$PY" - <<'PYEOF'
import math
from summary_checks import Checks, summary_values
c = Checks()
v = summary_values("my_concurrent_tension")
e = v("tension", "youngs_modulus")
c.check(math.isfinite(e) and e > 0, f"Young's modulus {e:.1f} GPa")
c.check(v("tension", "dpd_particles") > 0 and v("tension", "mpm_points") > 0,
        f"{v('tension', 'dpd_particles'):.0f} DPD particles, {v('tension', 'mpm_points'):.0f} MPM points")
c.exit()
PYEOF
[ -s runs/my_concurrent_tension/report.html ] || fail "no report.html"
echo "1 passed, 0 failed"
