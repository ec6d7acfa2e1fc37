source "$(dirname "$0")/lib.sh"
# The seed's Appendix-2 bar with plain and DDMP gradients (configs/mpm_bar_1d.yaml).
"$PBMS" run "$ROOT/configs/mpm_bar_1d.yaml" > out.txt 2>&1 || { cat out.txt; fail "run"; }
[ -f runs/mpm_bar_1d/profiles.png ] || fail "pbms plot did not draw both profiles"
"$PY" - <<'PYEOF'
import sys, yaml
st = yaml.safe_load(open("runs/mpm_bar_1d/summary.yaml"))["stages"]
bad = 0
def check(name, ok, text):
    global bad
    print(f"{'ok  ' if ok else 'FAIL'} {name}: {text}")
    bad += not ok
for s in ("bar_mpm", "bar_ddmp"):
    r = st[s]["results"]
    c, p = r["wave_speed"]["value"], r["plateau_stress"]["value"]
    check(s, abs(c / 1000 - 1) < 0.01, f"wave speed {c:.2f} (c = 1000, tolerance 1 %)")
    check(s, abs(p / 2000 - 1) < 0.02, f"plateau stress {p:.1f} (f/A = 2000, tolerance 2 %)")
r = st["bar_ddmp"]["results"]
tv = r["variation_ratio_mpm_over_ddmp"]["value"]
check("bar_ddmp", tv >= 2, f"excess variation MPM/DDMP {tv:.2f} (>= 2: DDMP removes the cell-crossing oscillations)")
rms = r["rms_ratio_mpm_over_ddmp"]["value"]
# Reported, not asserted >= 2: most of the rms is the front's dispersion on
# this grid, which both schemes share (see docs/mpm-driver.md).
check("bar_ddmp", rms > 1, f"rms from the exact solution MPM/DDMP {rms:.3f} (> 1)")
sys.exit(1 if bad else 0)
PYEOF
echo "1 passed, 0 failed"
