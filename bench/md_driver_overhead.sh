#!/usr/bin/env bash
# md_driver against plain lmp on the same LAMMPS inputs, side by side, one
# rank each: the MD isotherm of configs/md_isotherm.yaml (5 pressures, 2,048 atoms, 37,500 steps).
# Prints BENCH md_driver_overhead <ratio> x (target <= 1.03) and the ratio
# for the whole `pbms run` job (mpirun, coupler, handshake included).
set -euo pipefail
ROOT="$1"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
work="$(mktemp -d -t pbms-bench.XXXXXX)"
trap 'rm -rf "$work"' EXIT
cd "$work"
now() { date +%s.%N; }

t0=$(now)
"$ROOT/pbms" run "$ROOT/configs/md_isotherm.yaml" --ranks md=1 >run.txt 2>&1 || { cat run.txt; exit 1; }
t1=$(now)
run=runs/md_isotherm
stage_s=$(/usr/bin/python3 -c "import yaml; print(yaml.safe_load(open('$run/summary.yaml'))['stages']['isotherm']['wall_s'])")

# The same inputs through plain lmp, one process each, as a user would.
mkdir lmp && cp "$run"/isotherm/p*.in lmp/
cd lmp
t2=$(now)
for f in p*.in; do lmp -in "$f" -log none -screen none -nocite; done
t3=$(now)
cd ..

/usr/bin/python3 - "$t0" "$t1" "$t2" "$t3" "$stage_s" <<'PY'
import sys
t0, t1, t2, t3, stage = map(float, sys.argv[1:])
lmp = t3 - t2
print(f"md_driver stage {stage:.2f} s, whole pbms job {t1 - t0:.2f} s, plain lmp {lmp:.2f} s")
print(f"BENCH md_driver_overhead {stage / lmp:.4f} x")
print(f"BENCH pbms_job_overhead {(t1 - t0) / lmp:.4f} x")
print(f"BENCH lmp_isotherm_wall {lmp:.2f} s")
PY
