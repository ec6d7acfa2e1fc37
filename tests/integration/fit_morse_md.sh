source "$(dirname "$0")/lib.sh"
# Morse fitted to the MD isotherm of EAM copper at 298 K, 0-10 GPa
# (configs/fit_morse_md.yaml, about 8 minutes on two cores): the DPD volume per
# atom is within 0.5 % of MD's at every pressure, held-out ones included, in
# the fit and again on a crystal of 4,000 mesoparticles.
"$PBMS" run "$ROOT/configs/fit_morse_md.yaml" > out.txt 2>&1 || { cat out.txt; fail "run"; }
"$PY" - <<'PYEOF'
import sys, h5py, numpy as np
f = h5py.File("runs/fit_morse_md/results.h5")
md = f["isotherm/isotherm"]
fit = f["fit/isotherm"]
check = f["check_4000/isotherm"]
v_md = md["volume_per_atom"][:]
bad = 0
for name, v in (("fit (judge crystal)", fit["volume_per_atom"][:]),
                ("4,000 mesoparticles", check["volume_per_atom"][:])):
    rel = (v - v_md) / v_md
    ok = np.abs(rel).max() <= 0.005
    bad += not ok
    print(f"{'ok  ' if ok else 'FAIL'} {name}: largest |V_DPD - V_MD| / V_MD = {np.abs(rel).max():.2e} (tolerance 0.5 %)")
    for p, r, h in zip(md["pressure"][:] / 1e4, rel, fit["held_out"][:]):
        print(f"       {p:5.2f} GPa  {100 * r:+.3f} %{'  (held out)' if h else ''}")
sys.exit(1 if bad else 0)
PYEOF
echo "1 passed, 0 failed"
