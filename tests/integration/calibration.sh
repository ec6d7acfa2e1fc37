source "$(dirname "$0")/lib.sh"
# configs/calibration.yaml on 2 + 2 ranks: DPD tension -> J2 MPM material by
# {from:} -> MPM tension of the same rod, measured by the same rules. A
# consistency check of the hand-off (the MPM material is made from the DPD
# rod's reading), validation label since 2026-12-05; the physics check
# beside it in the default suite is mpm_rod_law, the MPM rod against its
# own constitutive law.
# Asserted: both rods report a gauge (the Cauchy stress and strain of
# their middle 90 A, analysis::GaugeSection) and the MPM material holds the
# DPD gauge's E, nu and density (its automatic time step, 0.5 h / c with c
# the P-wave speed from those three, is checked to 1e-6). Issue 18's chain
# criterion: the MPM rod's gauge modulus within 5 % of the DPD rod's, and
# its gauge stress, which a J2 rod without hardening caps at the yield
# stress, peaking within 5 % of the DPD gauge's yield stress (its first
# load drop). The rod measure, sum(sigma_xx V) / (A0 L), is printed for
# both: it carries the grips and the starting section (docs/hierarchy.md).
start=$(date +%s)
"$PBMS" run "$ROOT/configs/calibration.yaml" > out.txt 2>&1 || { cat out.txt; fail "run"; }
echo "wall time $(( $(date +%s) - start )) s"
"$PY" - runs/calibration <<'PYEOF'
import math, sys, yaml
run = sys.argv[1]
s = yaml.safe_load(open(f"{run}/summary.yaml"))["stages"]
dpd, mpm = s["tension"]["results"], s["mpm_tension"]["results"]
el = s["elastic_298K"]["results"]
bad = 0
def check(ok, msg):
    global bad
    print(f"{'ok  ' if ok else 'FAIL'} {msg}")
    bad += not ok
check(all(k in r for r in (dpd, mpm) for k in ("gauge_youngs_modulus", "gauge_yield_stress")),
      "both rods report gauge_youngs_modulus and gauge_yield_stress")
E, nu, rho = dpd["gauge_youngs_modulus"]["value"], el["poisson_ratio_100"]["value"], el["density"]["value"]
M = E * 1e9 * (1 - nu) / ((1 + nu) * (1 - 2 * nu))
c = math.sqrt(M / rho) / 100.0  # Å/ps
dt = 0.5 * 3.615 / c
got = mpm["time_step"]["value"]
check(abs(got / dt - 1) < 1e-6,
      f"MPM material from DPD: time step {got:.7g} ps = 0.5 h / c for E {E:.2f} GPa, nu {nu:.4f}, rho {rho:.1f} kg/m^3")
d, m = dpd["gauge_youngs_modulus"], mpm["gauge_youngs_modulus"]
check(abs(m["value"] / d["value"] - 1) <= 0.05,
      f"gauge E: MPM {m['value']:.2f} +- {m['std_error']:.2f} GPa vs DPD {d['value']:.2f} +- {d['std_error']:.2f} GPa "
      f"({100 * (m['value'] / d['value'] - 1):+.1f} %, tolerance 5 %)")
d, m = dpd["gauge_yield_stress"]["value"], mpm["gauge_max_stress"]["value"]
check(abs(m / d - 1) <= 0.05,
      f"gauge yield: MPM plateau {m:.2f} GPa vs DPD first load drop {d:.2f} GPa ({100 * (m / d - 1):+.1f} %, tolerance 5 %)")
for key in ("youngs_modulus", "max_stress"):
    print(f"     rod measure {key}: DPD {dpd[key]['value']:.2f}, MPM {mpm[key]['value']:.2f} GPa")
print(f"     gauge yield strain: DPD {dpd['gauge_yield_strain']['value']:.4f}, MPM {mpm['gauge_yield_strain']['value']:.4f}")
sys.exit(1 if bad else 0)
PYEOF
echo "1 passed, 0 failed"
