source "$(dirname "$0")/lib.sh"
# First axial mode of a fixed-free bar at h, h/2, h/4 (configs/mpm_vibrating_bar.yaml):
# T = 4 L / c = 10 exactly; each period within 1 %, the error falling at
# least linearly as h halves.
"$PBMS" run "$ROOT/configs/mpm_vibrating_bar.yaml" > out.txt 2>&1 || { cat out.txt; fail "run"; }
"$PY" - <<'PYEOF'
import sys, yaml
st = yaml.safe_load(open("runs/mpm_vibrating_bar/summary.yaml"))["stages"]
errs = []
bad = 0
for name in ("h_2_5", "h_1_25", "h_0_625"):
    T = st[name]["results"]["period"]["value"]
    e = abs(T / 10.0 - 1)
    errs.append(e)
    ok = e < 0.01
    bad += not ok
    print(f"{'ok  ' if ok else 'FAIL'} {name}: period {T:.5f}, error {e:.3%}")
for a, b in zip(errs, errs[1:]):
    ok = b <= 0.5 * a
    bad += not ok
    print(f"{'ok  ' if ok else 'FAIL'} error ratio on halving h: {a / b:.2f} (>= 2)")
sys.exit(1 if bad else 0)
PYEOF
echo "1 passed, 0 failed"
