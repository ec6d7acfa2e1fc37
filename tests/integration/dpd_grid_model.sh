source "$(dirname "$0")/lib.sh"
# The DPD/MPM-grid model (seed §5.2) against DPD-only from the same
# equilibrated state, on one rank: the impact's wave speed within 5 % and
# the tension rod's Young's modulus within 5 % at h = 4 Å, with the same
# stress measure and strain window (configs/dpd_grid_impact.yaml,
# configs/dpd_grid_tension.yaml): by the rod's mean virial stress at the
# seed's rate, and by the grips' force over the initial cross-section on
# the slower ramped pull, where that force measures the rod (seeds 1, 2 and
# 2026: grid -0.5 to -1.5 % of DPD-only).
"$PBMS" run "$ROOT/configs/dpd_grid_impact.yaml" > impact.txt 2>&1 || { cat impact.txt; fail "impact run"; }
"$PBMS" run "$ROOT/configs/dpd_grid_tension.yaml" > tension.txt 2>&1 || { cat tension.txt; fail "tension run"; }
"$PY" - <<'PYEOF'
import sys, yaml
bad = 0
def check(ok, text):
    global bad
    bad += not ok
    print(f"{'ok  ' if ok else 'FAIL'} {text}")
def results(run, stage):
    return yaml.safe_load(open(f"runs/{run}/summary.yaml"))["stages"][stage]["results"]
grid = results("dpd_grid_impact", "impact")["wave_speed"]["value"]
dpd = results("dpd_grid_impact", "impact_dpd_only")["wave_speed"]["value"]
check(abs(grid / dpd - 1) < 0.05, f"impact wave speed: grid {grid:.0f} m/s, DPD-only {dpd:.0f} m/s ({100 * (grid / dpd - 1):+.1f} %, within 5 %)")
grid = results("dpd_grid_tension", "tension")["youngs_modulus"]["value"]
dpd = results("dpd_grid_tension", "tension_dpd_only")["youngs_modulus"]["value"]
check(abs(grid / dpd - 1) < 0.05, f"Young's modulus: grid {grid:.2f} GPa, DPD-only {dpd:.2f} GPa ({100 * (grid / dpd - 1):+.1f} %, within 5 %)")
grid = results("dpd_grid_tension", "modulus_grid")["grip_youngs_modulus"]["value"]
dpd = results("dpd_grid_tension", "modulus_dpd_only")["grip_youngs_modulus"]["value"]
check(abs(grid / dpd - 1) < 0.05, f"Young's modulus by the grips' force: grid {grid:.2f} GPa, DPD-only {dpd:.2f} GPa ({100 * (grid / dpd - 1):+.1f} %, within 5 %)")
sys.exit(1 if bad else 0)
PYEOF
echo "1 passed, 0 failed"
