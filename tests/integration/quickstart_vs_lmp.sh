source "$(dirname "$0")/lib.sh"
# Plain `lmp` on the very input md_driver ran at 0 GPa must give the same
# lattice parameter within 0.1 %.
run="$1"
cp "$run/isotherm/p0.in" .
lmp -in p0.in -log none -screen lmp_screen.txt -nocite >/dev/null
ref=$(awk '/^PBMS_AVERAGES/{print $7}' lmp_screen.txt | tail -1)
[ -n "$ref" ] || fail "lmp printed no PBMS_AVERAGES line"
ours=$("$PY" -c "import h5py; print(h5py.File('$run/results.h5')['isotherm/isotherm/lattice_parameter'][0])")
"$PY" - "$ours" "$ref" <<'PYEOF'
import sys
ours, ref = map(float, sys.argv[1:])
rel = abs(ours - ref) / ref
print(f"md_driver a = {ours:.5f} Å, plain lmp a = {ref:.5f} Å, relative difference {rel:.2e}")
sys.exit(0 if rel < 1e-3 else 1)
PYEOF
echo "1 passed, 0 failed"
