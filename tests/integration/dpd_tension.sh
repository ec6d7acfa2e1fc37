source "$(dirname "$0")/lib.sh"
# configs/dpd_tension.yaml (seed §5.2.2) on 2 ranks: Young's modulus from
# the linear fit over the elastic part is within 10 % of the model's
# E<100> at 298 K (its dpd_elastic stage).
"$PBMS" run "$ROOT/configs/dpd_tension.yaml" > out.txt 2>&1 || { cat out.txt; fail "run"; }
s=runs/dpd_tension/summary.yaml
"$PY" - "$s" <<'PYEOF'
import sys, yaml
s = yaml.safe_load(open(sys.argv[1]))
e = s["stages"]["tension"]["results"]["youngs_modulus"]["value"]
e100 = s["stages"]["elastic_298K"]["results"]["youngs_modulus_100"]["value"]
ok = abs(e - e100) <= 0.10 * e100
print(f"{'ok  ' if ok else 'FAIL'} Young's modulus {e:.1f} GPa vs E<100> {e100:.1f} GPa at 298 K ({100 * (e / e100 - 1):+.1f} %, tolerance 10 %; seed: 87.2)")
sys.exit(0 if ok else 1)
PYEOF
echo "1 passed, 0 failed"
