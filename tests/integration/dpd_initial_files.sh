source "$(dirname "$0")/lib.sh"
export PBMS_NO_PLOTS=1  # the runs here are checked by their numbers, not their plots
# A dpd_run starts from a LAMMPS data file that Debian's lmp wrote (864
# particles at 298 K), and a second stage from the first one's H5MD file:
# both keep every particle and the velocities (T at step 0).
command -v lmp >/dev/null || fail "lmp (Debian package lammps) is not installed"
cat > lmp.in <<'LMP'
units metal
lattice fcc 7.23
region b block 0 6 0 6 0 6
create_box 1 b
create_atoms 1 box
mass 1 508.37
velocity all create 298 5
write_data cu.data
LMP
lmp -in lmp.in -log none -screen none
# The config names files relative to itself; run it from here.
sed "s#../../configs/potentials#$ROOT/configs/potentials#" "$(dirname "$0")/configs/dpd_initial_files.yaml" > cfg.yaml
"$PBMS" run cfg.yaml --ranks dpd=2 > out.txt 2>&1 || { cat out.txt; fail "run"; }
# The second run starts from the first one's H5MD file (its last frame).
cp runs/dpd_initial_files/from_data/particles.h5md state.h5md
sed "s/name: dpd_initial_files/name: from_h5md/; s/name: from_data/name: from_h5md/; s#{lammps_data: cu.data}#{h5md: state.h5md}#" cfg.yaml > cfg2.yaml
"$PBMS" run cfg2.yaml --ranks dpd=2 > out2.txt 2>&1 || { cat out2.txt; fail "run from H5MD"; }
"$PY" - <<'PYEOF'
import sys, h5py, yaml
first = h5py.File("runs/dpd_initial_files/results.h5")
bad = 0
for run, st in (("dpd_initial_files", "from_data"), ("from_h5md", "from_h5md")):
    s = yaml.safe_load(open(f"runs/{run}/summary.yaml"))["stages"]
    f = h5py.File(f"runs/{run}/results.h5")
    n = s[st]["results"]["particles"]["value"]
    t0 = f[f"{st}/probes/T"][0]
    ref = 298.0 if st == "from_data" else first["from_data/probes/T"][-1]
    # LAMMPS metal k_B is 8.617343e-5 eV/K, ours the CODATA 2018 8.617333262e-5.
    ok = n == 864 and abs(t0 - ref) < 1e-5 * ref
    bad += not ok
    print(f"{'ok  ' if ok else 'FAIL'} {st}: {n:.0f} particles, T at step 0 {t0:.6f} K (expected {ref:.6f})")
sys.exit(1 if bad else 0)
PYEOF
echo "1 passed, 0 failed"
