#!/usr/bin/env bash
# What checkpoints cost: the DPD impact of configs/dpd_impact.yaml (12,000
# mesoparticles and a flyer, 2 ranks, 450 steps) with a checkpoint every 50
# steps (8 in the impact stage), twice. The stage times its checkpoints
# itself (gather and write, results.h5 attribute checkpoint_seconds): the
# side-by-side difference of whole runs with and without is below their
# run-to-run spread here (+-7 %), so it is printed for reference only.
# Prints the cost of one checkpoint, the overhead at every 50 steps and at a
# checkpoint every 30 minutes of wall time (a cluster job's interval).
# The concurrent DPD/MPM stage writes no checkpoints yet (docs/checkpoints.md).
set -euo pipefail
ROOT="$1"
work="$(mktemp -d -t pbms-bench.XXXXXX)"
trap 'rm -rf "$work"' EXIT
cd "$work"
cp "$ROOT/configs/dpd_impact.yaml" plain.yaml
{ sed 's/^run: {name: \([a-z_]*\)/run: {name: \1_checkpointed/' plain.yaml; echo "checkpoint: {every_steps: 50}"; } > checkpointed.yaml
run() {  # run CONFIG: the impact stage's wall time and checkpoint seconds and count
  "$ROOT/pbms" run "$1" --overwrite > run.txt 2>&1 || { cat run.txt; exit 1; }
  local dir
  dir="$(grep -o "run '[^']*' -> [^ ]*" run.txt | head -1 | awk '{print $4}')"
  /usr/bin/python3 - "$dir" <<'PY'
import sys, h5py
g = h5py.File(f"{sys.argv[1]}/results.h5")["impact"]
a = lambda k: float(g.attrs[k]) if k in g.attrs else 0.0
print(a("wall_s"), a("checkpoint_seconds"), int(a("checkpoints_written")))
PY
}
{ run plain.yaml; run plain.yaml; run checkpointed.yaml; run checkpointed.yaml; } > times.txt
/usr/bin/python3 - times.txt <<'PY'
import sys
rows = [list(map(float, l.split())) for l in open(sys.argv[1])]
plain = min(r[0] for r in rows[:2])
ck = min(rows[2:], key=lambda r: r[0])
wall, seconds, n = ck[0], ck[1], int(ck[2])
per = seconds / n
print(f"impact stage: {plain:.3f} s without checkpoints, {wall:.3f} s with {n} "
      f"(of which {seconds:.4f} s in them)")
print(f"BENCH checkpoint_seconds {per:.5f} s")
print(f"BENCH checkpoint_overhead_fraction_every_50_steps {seconds / (wall - seconds):.4f} 1")
print(f"BENCH checkpoint_overhead_fraction {per / 1800.0:.2e} 1")
print(f"BENCH checkpoint_side_by_side_ratio {wall / plain:.4f} x")
PY
