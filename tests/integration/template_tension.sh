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
# Nested regions: the core/shell template as it stands (DPD core, MPM
# shell) and with its two solver words swapped. The DPD count must be the
# flyer's lattice sites plus the core's, then plus the shell's, each
# counted here from the fcc lattice and the template's geometry.
cp "$ROOT/configs/templates/concurrent_core_shell.yaml" core_shell.yaml
sed -e 's/name: my_core_shell/name: shell_core/' -e 's/solver: mpm, region: {style: block/solver: SWAP, region: {style: block/' \
    -e 's/solver: dpd, region: {style: sphere/solver: mpm, region: {style: sphere/' -e 's/solver: SWAP/solver: dpd/' \
    core_shell.yaml > shell_core.yaml
"$PBMS" run core_shell.yaml > cs.txt 2>&1 || { cat cs.txt; fail "the core/shell template did not run"; }
"$PBMS" run shell_core.yaml > sc.txt 2>&1 || { cat sc.txt; fail "the swapped core/shell did not run"; }
"$PY" - <<'PYEOF'
import itertools, math
from summary_checks import Checks, summary_values
a, c = 7.23, Checks()
basis = [(0, 0, 0), (0.5, 0.5, 0), (0.5, 0, 0.5), (0, 0.5, 0.5)]
def sites(lo, hi):  # fcc sites with lo <= x < hi (a block region is half-open)
    out = []
    for i, j, k in itertools.product(range(-3, 10), repeat=3):
        for b in basis:
            x = ((i + b[0]) * a, (j + b[1]) * a, (k + b[2]) * a)
            if all(lo[d] <= x[d] < hi[d] for d in range(3)):
                out.append(x)
    return out
cube = sites((0, 0, 0), (57.84, 57.84, 57.84))
flyer = sites((-14.46, 0, 0), (-1, 57.84, 57.84))
core = [x for x in cube if math.dist(x, (28.92, 28.92, 28.92)) <= 16]
for run, dpd in (("my_core_shell", len(flyer) + len(core)), ("shell_core", len(flyer) + len(cube) - len(core))):
    v = summary_values(run)
    c.check(v("impact", "dpd_particles") == dpd and v("impact", "mpm_points") == len(cube) + len(flyer) - dpd,
            f"{run}: {v('impact', 'dpd_particles'):.0f} DPD particles, {v('impact', 'mpm_points'):.0f} MPM points "
            f"(expected {dpd} and {len(cube) + len(flyer) - dpd}: flyer {len(flyer)}, core {len(core)}, cube {len(cube)})")
    c.check(abs(v("impact", "momentum_change")) < 1e-12, f"{run}: momentum kept ({v('impact', 'momentum_change'):.1e})")
c.exit()
PYEOF
echo "1 passed, 0 failed"
