source "$(dirname "$0")/lib.sh"
export PBMS_NO_PLOTS=1  # the runs here are checked by their numbers, not their plots
# The same isotherm on 1 and on 2 md_driver ranks agrees within statistics.
cfg="$(dirname "$0")/configs/small_isotherm.yaml"
"$PBMS" run "$cfg" --ranks md=1 > out1.txt 2>&1 || { cat out1.txt; fail "1-rank run"; }
rm -rf one && mv runs/small_isotherm one
"$PBMS" run "$cfg" --ranks md=2 > out2.txt 2>&1 || { cat out2.txt; fail "2-rank run"; }
rm -rf two && mv runs/small_isotherm two
[ "$(yget one/manifest.yaml layout.1.ranks)" = 1 ] || fail "first run did not use 1 rank"
[ "$(yget two/manifest.yaml layout.1.ranks)" = 2 ] || fail "second run did not use 2 ranks"
"$PY" - <<'PYEOF'
import sys, h5py, numpy as np
t = [h5py.File(f"{d}/results.h5")["isotherm/isotherm"] for d in ("one", "two")]
bad = 0
for col in ("lattice_parameter", "volume_per_atom"):
    a, b = t[0][col][:], t[1][col][:]
    ea, eb = t[0][col + "_std_error"][:], t[1][col + "_std_error"][:]
    z = np.abs(a - b) / np.sqrt(ea**2 + eb**2)
    print(col, "1 rank:", a, "2 ranks:", b, "z:", z)
    # Block standard errors from 10 blocks are themselves uncertain by ~25 %;
    # |z| < 5 keeps the false-alarm rate negligible while catching real bias.
    bad += int(np.any(z > 5))
    # And in absolute terms the runs agree to 0.05 %.
    bad += int(np.any(np.abs(a - b) / a > 5e-4))
sys.exit(1 if bad else 0)
PYEOF
echo "1 passed, 0 failed"
