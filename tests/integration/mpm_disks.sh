source "$(dirname "$0")/lib.sh"
# Colliding elastic disks with FLIP (configs/mpm_disks.yaml, 4 MPM ranks):
# total energy within 2 % through the collision; energies plotted.
"$PBMS" run "$ROOT/configs/mpm_disks.yaml" > out.txt 2>&1 || { cat out.txt; fail "run"; }
[ -f runs/mpm_disks/disks_energy.png ] || fail "no energy plot"
[ -f runs/mpm_disks/disks/grid.xdmf ] || fail "no XDMF grid output"
[ -f runs/mpm_disks/disks/particles.h5md ] || fail "no H5MD particle output"
dev=$(yget runs/mpm_disks/summary.yaml stages.disks.results.energy_max_deviation.value)
"$PY" -c "import sys; d=float('$dev'); print(f'largest |E - E0| / E0 = {d:.3%} (tolerance 2 %)'); sys.exit(d >= 0.02)" \
  || fail "energy not conserved"
# The collision really happened: kinetic energy dropped well below its start.
"$PY" - <<'PYEOF' || fail "no collision"
import sys, h5py
p = h5py.File("runs/mpm_disks/results.h5")["disks/probes"]
k = p["energy.kinetic"][:]
print(f"smallest kinetic / initial = {k.min() / k[0]:.3f}")
sys.exit(0 if k.min() < 0.2 * k[0] else 1)
PYEOF
echo "1 passed, 0 failed"
