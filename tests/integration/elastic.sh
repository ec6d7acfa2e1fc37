source "$(dirname "$0")/lib.sh"
"$PBMS" run "$(dirname "$0")/configs/elastic_0K.yaml" > out.txt 2>&1 || { cat out.txt; fail "run"; }
"$PY" - <<'PYEOF'
import sys, yaml
r = yaml.safe_load(open("runs/elastic/summary.yaml"))["stages"]["elastic"]["results"]
ref = {"c11": 169.9, "c12": 122.6, "c44": 76.2}
bad = 0
for k, v in ref.items():
    got = r[k]["value"]
    ok = abs(got - v) / v < 0.01
    print(f"{'ok  ' if ok else 'FAIL'} {k} = {got:.2f} GPa (Mishin 2001: {v}, tolerance 1 %)")
    bad += not ok
b = r["bulk_modulus"]["value"]
print(f"bulk modulus {b:.2f} GPa, E<100> {r['youngs_modulus_100']['value']:.2f} GPa, a0 {r['lattice_parameter']['value']:.4f} Å")
bad += abs(r["lattice_parameter"]["value"] - 3.615) > 1e-3
sys.exit(1 if bad else 0)
PYEOF
# Every strained crystal of both stages, replayed by plain lmp: equal to 1e-9.
"$PY" "$(dirname "$0")/elastic_vs_lmp.py" runs/elastic elastic
"$PY" "$(dirname "$0")/elastic_vs_lmp.py" runs/elastic elastic_298K
echo "1 passed, 0 failed"
