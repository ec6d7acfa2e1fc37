#!/usr/bin/env bash
# What checkpoints cost, in two stages that time their checkpoints
# themselves (gather and write; results.h5 attributes checkpoint_seconds,
# and mpm_checkpoint_seconds for a concurrent stage's MPM part):
#  - the concurrent DPD/MPM impact of configs/concurrent_impact.yaml (the
#    issue's case: 550 steps, a DPD part and an MPM part on a rank each, a
#    checkpoint every 50 steps, 10 in the stage; the parts write at once and
#    the slower one counts);
#  - the DPD impact of configs/dpd_impact.yaml (12,000 mesoparticles and a
#    flyer, 2 ranks, 450 steps, a checkpoint every 50, 8 in the stage).
# Each runs twice with checkpoints and twice without. The side-by-side
# difference of whole runs is below their run-to-run spread here (+-7 %), so
# it is printed for reference only. Prints each case's cost of one
# checkpoint, its overhead at every 50 steps and at one checkpoint every
# 30 minutes of wall time (a cluster job's interval, docs/checkpoints.md).
set -euo pipefail
ROOT="$1"
work="$(mktemp -d -t pbms-bench.XXXXXX)"
trap 'rm -rf "$work"' EXIT
cd "$work"
run() {  # run CONFIG STAGE: the stage's wall time, checkpoint seconds and count
  "$ROOT/pbms" run "$1" --overwrite > run.txt 2>&1 || { cat run.txt; exit 1; }
  local dir
  dir="$(grep -o "run '[^']*' -> [^ ]*" run.txt | head -1 | awk '{print $4}')"
  /usr/bin/python3 - "$dir" "$2" <<'PY'
import sys, h5py
g = h5py.File(f"{sys.argv[1]}/results.h5")[sys.argv[2]]
a = lambda k: float(g.attrs[k]) if k in g.attrs else 0.0
print(a("wall_s"), max(a("checkpoint_seconds"), a("mpm_checkpoint_seconds")),
      int(a("checkpoints_written")))
PY
}
measure() {  # measure CONFIG STAGE NAME
  cp "$ROOT/configs/$1" plain.yaml
  { sed 's/^run: {name: \([a-z_]*\)/run: {name: \1_checkpointed/' plain.yaml
    echo "checkpoint: {every_steps: 50}"; } > checkpointed.yaml
  { run plain.yaml "$2"; run plain.yaml "$2"; run checkpointed.yaml "$2"; run checkpointed.yaml "$2"; } > times.txt
  /usr/bin/python3 - times.txt "$3" "$2" <<'PY'
import sys
rows = [list(map(float, l.split())) for l in open(sys.argv[1])]
name, stage = sys.argv[2], sys.argv[3]
suffix = "" if name == "concurrent_impact" else f"_{name}"
plain = min(r[0] for r in rows[:2])
ck = min(rows[2:], key=lambda r: r[0])
wall, seconds, n = ck[0], ck[1], int(ck[2])
per = seconds / n
print(f"{name}: stage '{stage}' {plain:.3f} s without checkpoints, {wall:.3f} s with {n} "
      f"(of which {seconds:.4f} s in them)")
print(f"BENCH checkpoint_seconds{suffix} {per:.5f} s")
print(f"BENCH checkpoint_overhead_fraction_every_50_steps{suffix} {seconds / (wall - seconds):.4f} 1")
print(f"BENCH checkpoint_overhead_fraction{suffix} {per / 1800.0:.2e} 1")
print(f"BENCH checkpoint_side_by_side_ratio{suffix} {wall / plain:.4f} x")
PY
}
measure concurrent_impact.yaml concurrent concurrent_impact
measure dpd_impact.yaml impact dpd_impact
