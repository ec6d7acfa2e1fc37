source "$(dirname "$0")/lib.sh"
export PBMS_NO_PLOTS=1  # the runs here are checked by their numbers, not their plots
# Checkpoint and resume of dpd_run (tests/integration/configs/checkpoint_dpd.yaml:
# 1,000 steps, a checkpoint every 100). Each case runs the stage whole, and
# again killed: the test holds the writer of the checkpoint after step 900
# between its data and its rename (PBMS_TEST_CHECKPOINT_PAUSE) and sends
# SIGKILL to a dpd_driver rank then. The kill must leave the half-written
# file under its temporary name, the manifest listing the checkpoints up to
# step 800 only; `./pbms run --resume` must go on from step 800 and end:
#  - on the same ranks, bitwise as the whole run: every summary.yaml value
#    (timings aside), every results.h5 dataset of the stage, and every H5MD
#    frame (one every 50 steps: the frames after step 800 that the killed
#    run wrote are dropped and written again);
#  - on 1 rank instead of 2 (a copy of the killed run), to the rank tests'
#    round-off: positions 1e-9 Å, velocities 1e-10 Å/ps (dpd_ranks.sh); the
#    grid pull's midpoint move to dpd_grid_1_2_4_ranks' 1e-4 Å and 1e-2 Å/ps;
# for a thermostatted pull with probes and a gauge on 2 ranks, a DPDE
# crystal (shardlow_dpde), a rigid flyer's impact and the pull on the
# DPD/MPM grid with its grips past a velocity ramp; and mpm_run (the
# colliding disks, 1,000 steps on 1 rank, resumed also on 2: round-off
# 1e-10 as mpm_ranks.sh; grid frames every 100 steps and their XDMF as
# well) for an elastic material with DDMP gradients, J2
# with plastic flow and an ideal gas; and an md_isotherm (256 atoms, 3
# pressures on 2 ranks) killed while writing the checkpoint after its second
# point, resumed from its first: every summary value and the isotherm table
# bitwise; and an md_elastic at 0 K (four strained states) the same way,
# every summary value and the strains table bitwise; and md_tension (LAMMPS
# restart files), a nanowire killed in its loading and a periodic crystal
# killed at the end of its equilibration: every summary value, the
# stress-strain table and every H5MD frame bitwise. The pull without a
# checkpoint: block ends bitwise as the whole run that wrote them: writing
# one disturbs nothing. SIGTERM to `./pbms run` during the pull: the job
# writes a checkpoint at the next step boundary and ends non-zero within
# 10 s, saying how to go on, and the resume from it is bitwise as above.
# SIGTERM to every task of the job (Slurm's way) during md_tension: the
# same, and the resume is bitwise up to the stop and round-off after.
# Then a resume with a changed key is refused, naming it.
#
# The argument picks the cases: dpd (the default suite's checkpoint_resume:
# dpd_run, the signals to ./pbms run and the refusal), mpm_md
# (checkpoint_resume_mpm_md, validation label: mpm_run, md_isotherm,
# md_elastic, md_tension and the signal to every task; the default suite
# resumes MPM points in checkpoint_concurrent), or all.
part="${1:-all}"
runs_part() { [ "$part" = all ] || [ "$part" = "$1" ]; }
case "$part" in all | dpd | mpm_md) ;; *) fail "unknown part '$part' (all, dpd or mpm_md)" ;; esac
base="$(dirname "$0")/configs/checkpoint_dpd.yaml"

"$PY" - "$base" <<'PYEOF'
import sys, copy, yaml
base = yaml.safe_load(open(sys.argv[1]))
def write(name, cfg):
    cfg = copy.deepcopy(cfg)
    cfg["run"]["name"] = name
    yaml.safe_dump(cfg, open(f"{name}.yaml", "w"), sort_keys=False)
pull = base
dpde = copy.deepcopy(base)
stage = dpde["stages"][0]
for k in ("mode", "groups", "motion", "tension", "probes"):
    stage.pop(k)
stage.update({"name": "dpde", "scheme": "shardlow_dpde", "gamma": 5})
stage["box"] = {"lo": [0, 0, -6], "hi": [57.84, 43.38, 49.38], "periodic": ["x", "y"]}
stage["bodies"] = [{"name": "crystal", "region": {"style": "block", "lo": [0, 0, 0], "hi": [57.84, 43.38, 43.38]}}]
stage["probes"] = [{"name": "e", "kind": "energy"}]
impact = copy.deepcopy(base)
stage = impact["stages"][0]
stage.update({"name": "impact", "mode": "impact"})
stage.pop("tension")
stage["bodies"] = [{"name": "rod", "region": {"style": "block", "lo": [0, 0, 0], "hi": [72.3, 21.69, 21.69]}},
                   {"name": "flyer", "region": {"style": "block", "lo": [-15.46, 0, 0], "hi": [-1, 21.69, 21.69]}}]
stage["groups"] = [{"name": "near", "region": {"style": "block", "lo": [10, -1, -1], "hi": [16, 23, 23]}},
                   {"name": "far", "region": {"style": "block", "lo": [50, -1, -1], "hi": [56, 23, 23]}}]
stage["motion"] = [{"group": "flyer", "kind": "rigid_body", "velocity": [5, 0, 0]}]
stage["impact"] = {"near_slab": "near", "far_slab": "far", "axis": "x"}
stage["probes"] = [{"name": "T", "kind": "temperature"}]
# The pull on the DPD/MPM grid, its grips on a 2 ps ramp that has ended by
# the checkpoint resumed from (the grid step holds their velocities).
gridpull = copy.deepcopy(base)
stage = gridpull["stages"][0]
stage.update({"name": "gridpull", "grid": {"cell_size": 4.0}})
for m in stage["motion"]:
    m["ramp_time"] = 2
# MPM: the colliding disks of mpm_disks_200.yaml for 1,000 steps, on one
# rank (the resume on another goes to 2): elastic with DDMP gradients, J2
# with plastic flow, ideal gas.
disks = yaml.safe_load(open(sys.argv[1].replace("checkpoint_dpd.yaml", "mpm_disks_200.yaml")))
disks["launch"] = {"mpm": 1}
disks["checkpoint"] = base["checkpoint"]
stage = disks["stages"][0]
stage.update({"duration": 2.0, "particles_every": 50, "grid_every": 100})
mpm_cases = {}
elastic = copy.deepcopy(disks)
elastic["stages"][0].update({"gradient": "ddmp", "ddmp_blend": "face_vanishing"})
mpm_cases["mpm_elastic"] = elastic
j2 = copy.deepcopy(disks)
j2["materials"]["disk_material"] = {"kind": "j2_plasticity", "density": 1000, "youngs_modulus": 1000,
                                    "poisson_ratio": 0.3, "yield_stress": 5, "hardening_modulus": 50}
mpm_cases["mpm_j2"] = j2
gas = copy.deepcopy(disks)
gas["materials"]["disk_material"] = {"kind": "ideal_gas", "density": 1000, "gamma": 1.4}
mpm_cases["mpm_gas"] = gas
for case, cfg in mpm_cases.items():
    write(f"{case}_whole", cfg)
    write(f"{case}_killed", cfg)
    write(f"{case}_other_ranks", cfg)
# MD: a small isotherm (256 atoms, 3 pressures), a checkpoint after each point.
md = yaml.safe_load(open(sys.argv[1].replace("tests/integration/configs/checkpoint_dpd.yaml", "configs/md_isotherm.yaml")))
md["launch"] = {"md": 2}
md["checkpoint"] = {"every_minutes": 30}
md["run"]["output"] = "runs"
md["stages"][0].update({"pressures": ["0 GPa", "2 GPa", "5 GPa"], "cells": [4, 4, 4],
                        "equilibration": "0.4 ps", "production": "0.8 ps"})
write("md_whole", md)
md["run"]["output"] = "runs_md"  # its own result cache: the whole run's would answer it
write("md_killed", md)
# MD elastic constants at 0 K: four strained states, a checkpoint after each.
elastic = copy.deepcopy(md)
elastic["stages"] = [{"name": "elastic", "kind": "md_elastic", "material": md["stages"][0]["material"],
                      "cells": [3, 3, 3]}]
elastic["run"]["output"] = "runs"
write("elastic_whole", elastic)
elastic["run"]["output"] = "runs_elastic"
write("elastic_killed", elastic)
# MD tension through LAMMPS restart files: a small nanowire (10 x 4 x 4
# cells, 0.4 ps at 300 K, then 2 % at 2 %/ps) and the periodic crystal, a
# checkpoint every 100 steps, each stage 700 steps.
tension = copy.deepcopy(md)
tension["checkpoint"] = {"every_steps": 100}
wire = {"name": "wire", "kind": "md_tension", "material": md["stages"][0]["material"],
        "cells": [10, 4, 4], "temperature": 300, "lattice_constant": 3.632,
        "strain_rate": "2 %/ps", "max_strain": 0.02, "fit_max_strain": 0.02,
        "equilibration": "0.4 ps", "sample_every": 10, "trajectory_every": 50}
bulk = dict(wire, name="bulk", lateral="periodic", cells=[4, 4, 4], temperature=298,
            initial_strain=-0.01, max_strain=0.01)
for case, stage in (("tension", wire), ("tension_periodic", bulk)):
    tension["stages"] = [stage]
    tension["run"]["output"] = "runs"
    write(f"{case}_whole", tension)
    tension["run"]["output"] = f"runs_{case}"
    write(f"{case}_killed", tension)
tension["stages"] = [wire]
tension["run"]["output"] = "runs_tension_signalled"
write("tension_signalled", tension)
plain = copy.deepcopy(pull)
plain.pop("checkpoint")
write("pull_plain", plain)
for case, cfg in (("pull", pull), ("dpde", dpde), ("impact", impact), ("gridpull", gridpull)):
    write(f"{case}_whole", cfg)
    write(f"{case}_killed", cfg)
    write(f"{case}_one_rank", cfg)
write("pull_signalled", pull)
PYEOF

# Runs CASE_killed, holds the checkpoint write after step 900 and kills a
# rank of PROGRAM: run_killed CASE STAGE [PROGRAM]
run_killed() {
  local case=$1 stage=$2 program=${3:-dpd_driver} run="$PWD/runs/${1}_killed"
  local partial="$run/$stage/checkpoints/step_000000000900.h5.partial"
  PBMS_TEST_CHECKPOINT_PAUSE="step_000000000900:120" "$PBMS" run "${case}_killed.yaml" \
    > "${case}_killed.out" 2>&1 &
  local pid=$!
  for _ in $(seq 1 600); do
    [ -f "$partial" ] && break
    kill -0 $pid 2>/dev/null || { cat "${case}_killed.out"; fail "$case: ended before the kill"; }
    sleep 0.1
  done
  [ -f "$partial" ] || fail "$case: no checkpoint write after step 900 to kill"
  kill -9 "$(job_process "$program")"
  timeout 60 tail --pid=$pid -f /dev/null || fail "$case: the job did not end after the kill"
  ! wait $pid || fail "$case: the killed job exited 0"
  [ -f "$partial" ] || fail "$case: the half-written checkpoint is gone"
  "$PY" - "$run" "$stage" <<'PYEOF' || fail "$case: the manifest lists an incomplete checkpoint"
import sys, yaml
m = yaml.safe_load(open(f"{sys.argv[1]}/manifest.yaml"))
s = next(s for s in m["stages"] if s["name"] == sys.argv[2])
steps = [c["step"] for c in s.get("checkpoints") or []]
assert steps and max(steps) == 800, steps
print(f"  killed during the write after step 900: the manifest lists {steps}")
PYEOF
}

compare() {  # compare WHOLE RESUMED STAGE POSITION_TOL VELOCITY_TOL [SUMMARY_RELATIVE_TOL]
  "$PY" - "$PWD/runs/$1" "$PWD/runs/$2" "$3" "$4" "$5" "${6:-1e-6}" <<'PYEOF'
import sys, yaml, h5py, numpy as np
a, b, stage, xtol, vtol, stol = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4]), float(sys.argv[5]), float(sys.argv[6])
timing = ("steps_per_second", "wall_s")
bad = []
sa = yaml.safe_load(open(f"{a}/summary.yaml"))["stages"][stage]["results"]
sb = yaml.safe_load(open(f"{b}/summary.yaml"))["stages"][stage]["results"]
exact = xtol == 0
for k, v in sa.items():
    if k in timing:
        continue
    w = sb.get(k, {}).get("value")
    same = w == v["value"] if exact else w is not None and abs(w - v["value"]) <= stol * max(1.0, abs(v["value"]))
    if not same:
        bad.append(f"summary {k}: {v['value']!r} whole, {w!r} resumed")
if exact:
    with h5py.File(f"{a}/results.h5") as fa, h5py.File(f"{b}/results.h5") as fb:
        def walk(g, h, path):
            for k in g:
                if isinstance(g[k], h5py.Group):
                    walk(g[k], h[k], f"{path}/{k}")
                elif k not in timing and not np.array_equal(g[k][()], h[k][()]):
                    bad.append(f"results.h5 {path}/{k} differs")
        walk(fa[stage], fb[stage], stage)
import os
if os.path.exists(f"{a}/{stage}/grid.h5"):  # mpm_run's grid frames and their XDMF
    with h5py.File(f"{a}/{stage}/grid.h5") as fa, h5py.File(f"{b}/{stage}/grid.h5") as fb:
        if sorted(fa) != sorted(fb):
            bad.append(f"grid frames {sorted(fb)}, the whole run's {sorted(fa)}")
        print(f"  grid: {len(fa)} frames compared")
        for g in fa:
            for d in fa[g]:
                x, y = fa[g][d][()], fb[g][d][()] if g in fb else None
                if y is None or (exact and not np.array_equal(x, y)) or np.max(np.abs(x - y)) > max(xtol, vtol) * max(1.0, np.max(np.abs(x))):
                    bad.append(f"grid {g}/{d} differs")
    if open(f"{a}/{stage}/grid.xdmf").read() != open(f"{b}/{stage}/grid.xdmf").read():
        bad.append("grid.xdmf differs")
with h5py.File(f"{a}/{stage}/particles.h5md") as fa, h5py.File(f"{b}/{stage}/particles.h5md") as fb:
    steps_a, steps_b = fa["particles/all/position/step"][()], fb["particles/all/position/step"][()]
    if not np.array_equal(steps_a, steps_b):
        bad.append(f"H5MD frames at steps {list(steps_b)}, the whole run's at {list(steps_a)}")
    elif exact:
        for q in ("position", "velocity"):
            if not np.array_equal(fa[f"particles/all/{q}/value"][()], fb[f"particles/all/{q}/value"][()]):
                bad.append(f"H5MD {q} frames differ")
        print(f"  H5MD: the same {len(steps_a)} frames, bit for bit")
    for q, tol in (("positions", xtol), ("velocities", vtol)):
        field = {"positions": "position", "velocities": "velocity"}[q]
        x, y = fa[f"particles/all/{field}/value"][-1], fb[f"particles/all/{field}/value"][-1]
        d = float(np.max(np.abs(x - y)))
        if (exact and not np.array_equal(x, y)) or d > tol:
            bad.append(f"final {q} differ by up to {d:.3g}")
        print(f"  final {q}: largest difference {d:.3g}")
for line in bad:
    print("  " + line)
sys.exit(1 if bad else 0)
PYEOF
}

if runs_part dpd; then
for spec in pull:pull dpde:dpde impact:impact gridpull:gridpull; do
  case=${spec%%:*} stage=${spec##*:}
  echo "== $case"
  "$PBMS" run "${case}_whole.yaml" > "${case}_whole.out" 2>&1 || { cat "${case}_whole.out"; fail "$case: the whole run"; }
  run_killed "$case" "$stage"
  cp -a "runs/${case}_killed" "runs/${case}_one_rank"
  "$PBMS" run "${case}_killed.yaml" --resume > "${case}_resumed.out" 2>&1 ||
    { cat "${case}_resumed.out"; fail "$case: the resume"; }
  grep -q "goes on from its checkpoint .*step_000000000800.h5" "${case}_resumed.out" ||
    { cat "${case}_resumed.out"; fail "$case: the resume did not go on from step 800"; }
  compare "${case}_whole" "${case}_killed" "$stage" 0 0 || fail "$case: resumed on 2 ranks, not bitwise"
  "$PBMS" run "${case}_one_rank.yaml" --resume --ranks dpd=1 > "${case}_one_rank.out" 2>&1 ||
    { cat "${case}_one_rank.out"; fail "$case: the resume on 1 rank"; }
  # The grid pull's midpoint move (dpd_run's default since 2026-12-07)
  # changes more than round-off with the ranks: a particle whose midpoint
  # stands past its rank's box takes its weights at the box's face. Its
  # bounds are dpd_grid_1_2_4_ranks' for that move (measured here 5e-6 Å,
  # 6.1e-5 Å/ps, summary 1.5e-6); the other cases keep round-off.
  tolerances="1e-9 1e-10"
  [ "$case" = gridpull ] && tolerances="1e-4 1e-2 1e-4"
  # shellcheck disable=SC2086
  compare "${case}_whole" "${case}_one_rank" "$stage" $tolerances ||
    fail "$case: resumed on 1 rank, beyond round-off"
done
fi

if runs_part mpm_md; then
for case in mpm_elastic mpm_j2 mpm_gas; do
  echo "== $case"
  "$PBMS" run "${case}_whole.yaml" > "${case}_whole.out" 2>&1 || { cat "${case}_whole.out"; fail "$case: the whole run"; }
  run_killed "$case" disks mpm_driver
  cp -a "runs/${case}_killed" "runs/${case}_other_ranks"
  "$PBMS" run "${case}_killed.yaml" --resume > "${case}_resumed.out" 2>&1 ||
    { cat "${case}_resumed.out"; fail "$case: the resume"; }
  grep -q "goes on from its checkpoint .*step_000000000800.h5" "${case}_resumed.out" ||
    { cat "${case}_resumed.out"; fail "$case: the resume did not go on from step 800"; }
  compare "${case}_whole" "${case}_killed" disks 0 0 || fail "$case: resumed on 1 rank, not bitwise"
  if [ "$case" = mpm_j2 ]; then  # the checkpoint must have carried plastic state
    "$PY" - "$PWD/runs/mpm_j2_whole" <<'PYEOF' || fail "mpm_j2: no plastic flow to carry"
import sys, h5py
d = h5py.File(f"{sys.argv[1]}/results.h5")["disks/probes/energy.dissipated"][()]
assert d[-1] > 0, d[-1]
print(f"  J2: {d[-1]:.3g} dissipated by plastic flow by the end")
PYEOF
  fi
  "$PBMS" run "${case}_other_ranks.yaml" --resume --ranks mpm=2 > "${case}_other_ranks.out" 2>&1 ||
    { cat "${case}_other_ranks.out"; fail "$case: the resume on 2 ranks"; }
  compare "${case}_whole" "${case}_other_ranks" disks 1e-10 1e-10 ||
    fail "$case: resumed on 2 ranks, beyond round-off"
done
fi

# An MD stage with a checkpoint after each finished point: killed while the
# second is written, resumed from the first, and compared with the whole
# run: every summary value and the stage's TABLE bitwise.
# md_killed_resumed CASE STAGE TABLE OUTPUT SECOND FIRST
md_killed_resumed() {
  local case=$1 stage=$2 table=$3 output=$4 second=$5 first=$6 pid
  PBMS_TEST_CHECKPOINT_PAUSE="$second:120" "$PBMS" run "${case}_killed.yaml" > "${case}_killed.out" 2>&1 &
  pid=$!
  for _ in $(seq 1 1200); do
    [ -f "$output/${case}_killed/$stage/checkpoints/$second.h5.partial" ] && break
    kill -0 $pid 2>/dev/null || { cat "${case}_killed.out"; fail "$case: ended before the kill"; }
    sleep 0.1
  done
  kill -9 "$(job_process md_driver)"
  timeout 60 tail --pid=$pid -f /dev/null || fail "$case: the job did not end after the kill"
  "$PBMS" run "${case}_killed.yaml" --resume > "${case}_resumed.out" 2>&1 ||
    { cat "${case}_resumed.out"; fail "$case: the resume"; }
  grep -q "goes on from its checkpoint .*$first.h5" "${case}_resumed.out" ||
    { cat "${case}_resumed.out"; fail "$case: not from the first point"; }
  "$PY" - "$PWD/runs/${case}_whole" "$PWD/$output/${case}_killed" "$stage" "$table" "$first" <<'PYEOF' ||
import sys, glob, yaml, h5py, numpy as np
a, b, stage, table = sys.argv[1:5]
sa = yaml.safe_load(open(f"{a}/summary.yaml"))["stages"][stage]["results"]
sb = yaml.safe_load(open(f"{b}/summary.yaml"))["stages"][stage]["results"]
bad = [k for k in sa if sa[k]["value"] != sb[k]["value"]]
with h5py.File(f"{a}/results.h5") as fa, h5py.File(f"{b}/results.h5") as fb:
    t = f"{stage}/{table}"
    bad += [c for c in fa[t] if not np.array_equal(fa[t][c][()], fb[t][c][()])]
frames = 0
for h in glob.glob(f"{a}/{stage}/*.h5md"):
    with h5py.File(h) as fa, h5py.File(h.replace(a, b)) as fb:
        for q in ("position", "velocity"):
            d = f"particles/all/{q}/value"
            frames = fa[d].shape[0]
            bad += [] if np.array_equal(fa[d][()], fb[d][()]) else [d]
print(f"  resumed from {sys.argv[5]}: {len(sa)} summary values, the {table} table"
      + (f" and {frames} H5MD frames " if frames else " ")
      + ("bitwise as the whole run" if not bad else f"differ: {bad}"))
sys.exit(1 if bad else 0)
PYEOF
    fail "$case: the resumed stage differs"
}

# signalled_resumed NAME RUN_DIR PAUSE PARTIAL [TO]: NAME.yaml stopped by
# SIGTERM (stop_during_checkpoint), the message and manifest that leaves,
# and the resume from its checkpoint.
signalled_resumed() {
  local name=$1 run=$2 pause=$3 partial=$4 to=${5:-launcher}
  stop_during_checkpoint "$name.yaml" "$pause" "$partial" "$name.out" "$to"
  grep -q "holds the run; to go on from there: ./pbms run $name.yaml --resume" "$name.out" ||
    { cat "$name.out"; fail "$name: the stopped job does not say how to go on"; }
  [ "$(yget "$run/manifest.yaml" status)" = stopped ] || fail "$name: the manifest does not say stopped"
  "$PBMS" run "$name.yaml" --resume > "${name}_resumed.out" 2>&1 ||
    { cat "${name}_resumed.out"; fail "$name: the resume after SIGTERM"; }
  grep -o "goes on from its checkpoint .*" "${name}_resumed.out" | sed 's/^/  /'
}

if runs_part mpm_md; then
echo "== md_isotherm: killed while the checkpoint after its second point is written"
"$PBMS" run md_whole.yaml > md_whole.out 2>&1 || { cat md_whole.out; fail "md: the whole run"; }
mapfile -t md_steps < <(grep -o "checkpoint after step [0-9]*" runs/md_whole/log.txt | awk '{print $4}')
[ "${#md_steps[@]}" -eq 2 ] || fail "md: the whole isotherm wrote ${#md_steps[@]} checkpoints, not 2"
md_killed_resumed md isotherm isotherm runs_md "$(printf 'step_%012d' "${md_steps[1]}")" \
  "$(printf 'step_%012d' "${md_steps[0]}")"

echo "== md_elastic: killed while the checkpoint after its second strained state is written"
"$PBMS" run elastic_whole.yaml > elastic_whole.out 2>&1 || { cat elastic_whole.out; fail "elastic: the whole run"; }
md_killed_resumed elastic elastic strains runs_elastic step_000000000002 step_000000000001

echo "== md_tension: killed while writing a checkpoint, resumed from the one before (LAMMPS restart files)"
echo "  the nanowire, killed in its loading (step 500), resumed from step 400:"
"$PBMS" run tension_whole.yaml > tension_whole.out 2>&1 || { cat tension_whole.out; fail "tension: the whole run"; }
md_killed_resumed tension wire stress_strain runs_tension step_000000000500 step_000000000400
echo "  the periodic crystal, killed as its equilibration ends (step 200), resumed from step 100:"
"$PBMS" run tension_periodic_whole.yaml > tension_periodic_whole.out 2>&1 ||
  { cat tension_periodic_whole.out; fail "tension_periodic: the whole run"; }
md_killed_resumed tension_periodic bulk stress_strain runs_tension_periodic step_000000000200 step_000000000100

echo "== SIGTERM to every task of the job (as Slurm's --signal sends it) during md_tension's loading"
run="$PWD/runs_tension_signalled/tension_signalled"
signalled_resumed tension_signalled "$run" "step_000000000500:3" \
  "$run/wire/checkpoints/step_000000000500.h5.partial" tasks
# The stop added a checkpoint the whole run did not write, and the stage
# went on from it in a new LAMMPS instance: bitwise up to it, round-off
# grown by MD after it.
"$PY" - runs/tension_whole "$run" <<'PYEOF' || fail "tension: resumed after SIGTERM, not the whole run"
import re, sys, h5py, numpy as np
a, b = sys.argv[1:]
stop = int(re.search(r"step_0*(\d+)\.h5", open(f"{b}/log.txt").read().split("goes on from")[-1]).group(1))
with h5py.File(f"{a}/wire/tension.h5md") as fa, h5py.File(f"{b}/wire/tension.h5md") as fb:
    steps = fa["particles/all/position/step"][()]
    pa, pb = fa["particles/all/position/value"][()], fb["particles/all/position/value"][()]
    before = [k for k in range(len(steps)) if steps[k] <= stop]
    after = [k for k in range(len(steps)) if steps[k] > stop]
    exact = all(np.array_equal(pa[k], pb[k]) for k in before)
    drift = max(np.max(np.abs(pa[k] - pb[k])) for k in after) if after else 0.0
print(f"  stopped after step {stop}: frames up to it bitwise: {exact}; later frames within {drift:.1e} A")
sys.exit(0 if exact and drift < 1e-9 else 1)
PYEOF
fi

if runs_part dpd; then
echo "== SIGTERM to ./pbms run: a checkpoint at the next step boundary, exit non-zero, resume"
run="$PWD/runs/pull_signalled"
signalled_resumed pull_signalled "$run" "step_000000000500:3" \
  "$run/pull/checkpoints/step_000000000500.h5.partial"
grep -q "checkpoint pull/checkpoints/step_000000000510.h5 holds the run" pull_signalled.out ||
  { cat pull_signalled.out; fail "the stop is not at the next 10-step boundary"; }
compare pull_whole pull_signalled pull 0 0 || fail "resumed after SIGTERM, not bitwise"

echo "== writing checkpoints changes nothing: the pull without checkpoint:"
"$PBMS" run pull_plain.yaml > pull_plain.out 2>&1 || { cat pull_plain.out; fail "the pull without checkpoints"; }
compare pull_whole pull_plain pull 0 0 || fail "writing checkpoints changed the pull"

echo "== a changed config"
sed -i 's/steps: 1000/steps: 1200/' pull_killed.yaml
if "$PBMS" run pull_killed.yaml --resume > changed.out 2>&1; then fail "a changed config was resumed"; fi
grep -q "stages\[0\].steps: '1000' in the earlier run, '1200' now" changed.out ||
  { cat changed.out; fail "the refusal does not name the changed key"; }
echo "  refused: $(grep -o "the config has changed since: .* now" changed.out)"
fi
