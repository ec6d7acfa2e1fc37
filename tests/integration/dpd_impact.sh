source "$(dirname "$0")/lib.sh"
# configs/dpd_impact.yaml (seed §5.2.1) on 2 ranks: the wave speed from the
# first motion of the two slabs lies between the model's own bar speed
# sqrt(E<100>/rho) and longitudinal speed sqrt(C11/rho) at 298 K (its
# dpd_elastic stage), with 5 % slack either way.
"$PBMS" run "$ROOT/configs/dpd_impact.yaml" > out.txt 2>&1 || { cat out.txt; fail "run"; }
s=runs/dpd_impact/summary.yaml
"$PY" - "$s" <<'PYEOF'
import sys, yaml
s = yaml.safe_load(open(sys.argv[1]))
v = s["stages"]["impact"]["results"]["wave_speed"]["value"]
bar = s["stages"]["elastic_298K"]["results"]["bar_speed"]["value"]
lon = s["stages"]["elastic_298K"]["results"]["longitudinal_speed"]["value"]
ok = 0.95 * bar <= v <= 1.05 * lon
print(f"{'ok  ' if ok else 'FAIL'} wave speed {v:.0f} m/s in [0.95 x {bar:.0f}, 1.05 x {lon:.0f}] m/s (seed: 3846)")
sys.exit(0 if ok else 1)
PYEOF
echo "1 passed, 0 failed"
