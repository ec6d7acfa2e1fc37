source "$(dirname "$0")/lib.sh"
# Plain `lmp` replays the inputs md_driver wrote for configs/md_isotherm.yaml's 0 GPa
# and 5 GPa points (the lattice parameter and V/V0(5 GPa) are read there) on
# as many ranks as md_driver had. The script holds md_driver's run chunks
# as they ran (`run N start S stop E pre no`), so both follow the same
# trajectory; plain lmp prints its averages with %.20g. Pressure, volume per
# atom and lattice parameter must then agree to 1e-9 relative: far above the
# 1e-16 of the two summation orders (fix ave/time against md_driver's mean of
# the same samples; measured: 0), far below any change of the trajectory (a
# 1-rank replay of a 2-rank run moves the lattice parameter by 3e-5 and the
# pressure by more than its own value).
# The Birch-Murnaghan fit is redone here with scipy on md_driver's table.
run="$1"
ranks=$(yget "$run/manifest.yaml" layout.1.ranks)
[ "$(yget "$run/manifest.yaml" layout.1.program)" = md_driver ] || fail "layout.1 is not md_driver"
for i in 0 3; do
  cp "$run/isotherm/p$i.in" .
  grep -q "pre no post no" "p$i.in" || fail "p$i.in does not hold the chunked runs"
  mpirun --bind-to none --oversubscribe -np "$ranks" lmp -in "p$i.in" -log none -nocite \
    -screen "lmp_p$i.txt" > /dev/null 2>&1 || { tail -20 "lmp_p$i.txt"; fail "lmp on p$i.in"; }
done
"$PY" - "$run" "$ranks" <<'PYEOF'
import sys, h5py, numpy as np
from scipy.optimize import least_squares
run, ranks = sys.argv[1], sys.argv[2]
bad = 0
with h5py.File(f"{run}/results.h5") as f:
    t = {k: f["isotherm/isotherm"][k][:] for k in ("pressure_target", "pressure", "volume_per_atom",
                                                   "lattice_parameter", "volume_ratio")}
    v0_ours = f["isotherm/equilibrium_volume"][()]
    b_ours = f["isotherm/bulk_modulus"][()]
    bp_ours = f["isotherm/bulk_modulus_derivative"][()]
assert t["pressure_target"][0] == 0 and t["pressure_target"][3] == 5e4, t["pressure_target"]
for i in (0, 3):
    line = [l for l in open(f"lmp_p{i}.txt") if l.startswith("PBMS_AVERAGES")]
    if not line:
        print(f"FAIL lmp printed no PBMS_AVERAGES for p{i}")
        bad += 1
        continue
    w = line[-1].split()
    lmp = {"pressure": float(w[2]), "volume_per_atom": float(w[4]), "lattice_parameter": float(w[6])}
    for k, ref in lmp.items():
        ours = t[k][i]
        rel = abs(ours - ref) / abs(ref)
        ok = rel < 1e-9
        bad += not ok
        print(f"{'ok  ' if ok else 'FAIL'} p{i} ({t['pressure_target'][i] / 1e4:g} GPa) {k}: md_driver "
              f"{ours:.15g}, plain lmp on {ranks} ranks {ref:.15g}, relative difference {rel:.1e} "
              f"(tolerance 1e-9)")

# Birch-Murnaghan, as core/src/analysis/equation_of_state.cpp, fitted independently.
def bm(v, v0, b0, bp):
    x = (v0 / v) ** (2.0 / 3.0)
    return 1.5 * b0 * (x ** 3.5 - x ** 2.5) * (1 + 0.75 * (bp - 4) * (x - 1))
vol, p = t["volume_per_atom"], t["pressure"]
fit = least_squares(lambda q: (bm(vol, q[0] * vol[0], q[1] * 1e6, q[2]) - p) / 1e6,
                    [1.0, 1.3, 5.0], xtol=1e-15, ftol=1e-15, gtol=1e-15)
v0, b0, bp = fit.x[0] * vol[0], fit.x[1] * 1e6 / 1e4, fit.x[2]
# The fit's optimum is known to ~sqrt(machine epsilon) relative to the
# parameters' scatter: 1e-6 separates the two optimisers from a wrong formula.
for name, ours, ref in (("V0", v0_ours, v0), ("B0", b_ours, b0), ("B0'", bp_ours, bp)):
    rel = abs(ours - ref) / abs(ref)
    ok = rel < 1e-6
    bad += not ok
    print(f"{'ok  ' if ok else 'FAIL'} Birch-Murnaghan {name}: md_driver {ours:.10g}, scipy {ref:.10g}, "
          f"relative difference {rel:.1e} (tolerance 1e-6)")
ratio = t["volume_ratio"][3]
rel = abs(ratio - t["volume_per_atom"][3] / v0) / ratio
ok = rel < 1e-6
bad += not ok
print(f"{'ok  ' if ok else 'FAIL'} V/V0 at 5 GPa {ratio:.8f}, from the table and scipy's V0 "
      f"{t['volume_per_atom'][3] / v0:.8f}")
sys.exit(1 if bad else 0)
PYEOF
echo "1 passed, 0 failed"
