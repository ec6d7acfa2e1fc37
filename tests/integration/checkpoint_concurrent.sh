source "$(dirname "$0")/lib.sh"
export PBMS_NO_PLOTS=1  # the runs here are checked by their numbers, not their plots
# Checkpoint and resume of the concurrent DPD/MPM stage: the small impact
# bar of configs/concurrent_small.yaml (a free rigid flyer, periodic across,
# the MPM part on 2 ranks, 300 steps, particle and grid frames every 50,
# a checkpoint every 50) and a pull of the same bar between two grips on a
# 1 ps velocity ramp (the tension curve), the MPM grip past its ramp when
# the checkpoint is written. Each case runs whole, and again killed: the
# test holds both parts' writers of the checkpoint after step 250 between
# data and rename and sends SIGKILL to dpd_driver. The manifest must list
# the checkpoints up to step 200 only, each with both parts' files;
# `./pbms run --resume` goes on from step 200 and must end bitwise as the
# whole run: every summary value (timings and exchange counts aside: they
# are of the steps a run made), every results.h5 dataset, every H5MD frame
# of both parts and every grid frame and the XDMF text. The impact resumed
# instead on 2 DPD ranks and 1 MPM rank ends to round-off (1e-9 Å,
# 1e-10 Å/ps). SIGTERM during the impact: both parts write a checkpoint at
# the next step boundary they agree on and the job ends non-zero within 10 s;
# its resume runs to the end.
base="$(dirname "$0")/configs/concurrent_small.yaml"

"$PY" - "$base" <<'PYEOF'
import sys, copy, yaml
base = yaml.safe_load(open(sys.argv[1]))
base["checkpoint"] = {"every_steps": 50}
base["stages"][0]["particles_every"] = 50
# A rod probe on the DPD half: its particles' slabs are fixed at the start,
# and a resumed run must take them from the checkpoint, not from where the
# particles stand at step 200.
base["stages"][0]["groups"].append(
    {"name": "dpd_bar", "region": {"style": "block", "lo": [0, 0, 0], "hi": [56, 28.92, 28.92]}})
base["stages"][0]["rods"] = [{"name": "bar", "group": "dpd_bar", "axis": "x"}]
def write(name, cfg):
    cfg = copy.deepcopy(cfg)
    cfg["run"]["name"] = name
    yaml.safe_dump(cfg, open(f"{name}.yaml", "w"), sort_keys=False)
pull = copy.deepcopy(base)
stage = pull["stages"][0]
stage["name"] = "pull"
stage["bodies"] = [stage["bodies"][0]]
stage["groups"] = [g for g in stage["groups"] if g["name"] in ("dpd_plane", "mpm_plane", "dpd_bar")] + [
    {"name": "left_grip", "region": {"style": "block", "lo": [-1, -1, -1], "hi": [8, 30, 30]}},
    {"name": "right_grip", "region": {"style": "block", "lo": [108, -1, -1], "hi": [117, 30, 30]}}]
stage["motion"] = [
    {"group": "left_grip", "kind": "rigid", "velocity": [-1, 0, 0], "ramp_time": 1},
    {"group": "right_grip", "kind": "rigid", "velocity": [1, 0, 0], "ramp_time": 1}]
stage["wave"] = {"opening": stage["wave"]["opening"]}
stage["tension"] = {"left_grip": "left_grip", "right_grip": "right_grip", "fit_strain": 0.01}
for case, cfg in (("impact", base), ("pull", pull)):
    write(f"{case}_whole", cfg)
    write(f"{case}_killed", cfg)
write("impact_other_ranks", base)
write("impact_signalled", base)
PYEOF

# Runs CASE_killed, holds the checkpoint writes after step 250 and kills
# dpd_driver: run_killed CASE STAGE
run_killed() {
  local case=$1 stage=$2 run="$PWD/runs/${1}_killed"
  local partial="$run/$stage/checkpoints/step_000000000250.mpm.h5.partial"
  PBMS_TEST_CHECKPOINT_PAUSE="step_000000000250:120" "$PBMS" run "${case}_killed.yaml" \
    > "${case}_killed.out" 2>&1 &
  local pid=$!
  for _ in $(seq 1 600); do
    [ -f "$partial" ] && [ -f "${partial/.mpm/}" ] && break
    kill -0 $pid 2>/dev/null || { cat "${case}_killed.out"; fail "$case: ended before the kill"; }
    sleep 0.1
  done
  [ -f "$partial" ] || fail "$case: no checkpoint write after step 250 to kill"
  kill -9 "$(job_process dpd_driver)"
  timeout 60 tail --pid=$pid -f /dev/null || fail "$case: the job did not end after the kill"
  ! wait $pid || fail "$case: the killed job exited 0"
  "$PY" - "$run" "$stage" <<'PYEOF' || fail "$case: the manifest lists an incomplete checkpoint"
import sys, os, yaml
m = yaml.safe_load(open(f"{sys.argv[1]}/manifest.yaml"))
s = next(s for s in m["stages"] if s["name"] == sys.argv[2])
listed = s.get("checkpoints") or []
assert listed and max(c["step"] for c in listed) == 200, listed
for c in listed:
    files = [c["file"]] + c.get("parts", [])
    assert len(files) == 2 and all(os.path.exists(f"{sys.argv[1]}/{f}") for f in files), c
print(f"  killed during the write after step 250: the manifest lists steps "
      f"{[c['step'] for c in listed]}, each with both parts' files")
PYEOF
}

compare() {  # compare WHOLE RESUMED STAGE POSITION_TOL VELOCITY_TOL
  "$PY" - "$PWD/runs/$1" "$PWD/runs/$2" "$3" "$4" "$5" <<'PYEOF'
import sys, yaml, h5py, numpy as np
a, b, stage, xtol, vtol = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4]), float(sys.argv[5])
exact = xtol == 0
def skipped(k):  # what a run measures of its own steps, not of the physics
    return k in ("steps_per_second", "wall_s", "checkpoints_written", "checkpoint_seconds") or \
        "exchange" in k or k.endswith("bytes_per_step")
bad = []
sa = yaml.safe_load(open(f"{a}/summary.yaml"))["stages"][stage]["results"]
sb = yaml.safe_load(open(f"{b}/summary.yaml"))["stages"][stage]["results"]
compared = [k for k in sa if not skipped(k)]
for k in compared:
    v, w = sa[k]["value"], sb.get(k, {}).get("value")
    same = w == v if exact else w is not None and abs(w - v) <= 1e-6 * max(1.0, abs(v))
    if not same:
        bad.append(f"summary {k}: {v!r} whole, {w!r} resumed")
if exact:
    with h5py.File(f"{a}/results.h5") as fa, h5py.File(f"{b}/results.h5") as fb:
        def walk(g, h, path):
            for k in g:
                if skipped(k):
                    continue
                if isinstance(g[k], h5py.Group):
                    walk(g[k], h[k], f"{path}/{k}")
                elif not np.array_equal(g[k][()], h[k][()], equal_nan=True):
                    bad.append(f"results.h5 {path}/{k} differs")
        walk(fa[stage], fb[stage], stage)
    with h5py.File(f"{a}/{stage}/mpm_grid.h5") as fa, h5py.File(f"{b}/{stage}/mpm_grid.h5") as fb:
        if sorted(fa) != sorted(fb):
            bad.append(f"grid frames {sorted(fb)}, the whole run's {sorted(fa)}")
        for g in fa:
            for d in fa[g]:
                if g in fb and not np.array_equal(fa[g][d][()], fb[g][d][()]):
                    bad.append(f"grid {g}/{d} differs")
    if open(f"{a}/{stage}/mpm_grid.xdmf").read() != open(f"{b}/{stage}/mpm_grid.xdmf").read():
        bad.append("mpm_grid.xdmf differs")
period = 28.92  # across the bar: stored positions may differ by an image
for part in ("dpd", "mpm"):
    with h5py.File(f"{a}/{stage}/{part}_particles.h5md") as fa, h5py.File(f"{b}/{stage}/{part}_particles.h5md") as fb:
        pa, pb = fa["particles/all/position"], fb["particles/all/position"]
        if not np.array_equal(pa["step"][()], pb["step"][()]):
            bad.append(f"{part} H5MD frames at steps {list(pb['step'][()])}, the whole run's at {list(pa['step'][()])}")
            continue
        for q, tol in (("position", xtol), ("velocity", vtol)):
            x, y = fa[f"particles/all/{q}/value"][()], fb[f"particles/all/{q}/value"][()]
            if exact:
                if not np.array_equal(x, y):
                    bad.append(f"{part} H5MD {q} frames differ")
                continue
            d = np.abs(x[-1] - y[-1])
            if q == "position":
                d[..., 1:] = np.minimum(d[..., 1:], np.abs(d[..., 1:] - period))
            if d.max() > tol:
                bad.append(f"{part} final {q} values differ by up to {d.max():.3g}")
            print(f"  {part} final {q} values: largest difference {d.max():.3g}")
        if exact:
            print(f"  {part} H5MD: the same {len(pa['step'])} frames, bit for bit")
print(f"  {len(compared)} summary values compared" + ("" if bad else ": all as the whole run's"))
for line in bad:
    print("  " + line)
sys.exit(1 if bad else 0)
PYEOF
}

for spec in impact:impact pull:pull; do
  case=${spec%%:*} stage=${spec##*:}
  echo "== $case"
  "$PBMS" run "${case}_whole.yaml" > "${case}_whole.out" 2>&1 || { cat "${case}_whole.out"; fail "$case: the whole run"; }
  run_killed "$case" "$stage"
  [ "$case" = impact ] && cp -a runs/impact_killed runs/impact_other_ranks
  "$PBMS" run "${case}_killed.yaml" --resume > "${case}_resumed.out" 2>&1 ||
    { cat "${case}_resumed.out"; fail "$case: the resume"; }
  grep -q "goes on from its checkpoint .*step_000000000200.h5" "${case}_resumed.out" ||
    { cat "${case}_resumed.out"; fail "$case: the resume did not go on from step 200"; }
  compare "${case}_whole" "${case}_killed" "$stage" 0 0 || fail "$case: resumed, not bitwise"
done

"$PY" - "$PWD/runs/pull_whole" <<'PYEOF' || fail "pull: no tension curve to carry"
import sys, h5py
g = h5py.File(f"{sys.argv[1]}/results.h5")["pull/tension_curve"]
print(f"  pull: {len(g['strain'])} points of the tension curve, to strain {g['strain'][-1]:.4f}")
assert len(g["strain"]) > 10 and g["strain"][-1] > 0
PYEOF

echo "== impact resumed on 2 DPD ranks and 1 MPM rank"
"$PBMS" run impact_other_ranks.yaml --resume --ranks dpd=2 --ranks mpm=1 > other_ranks.out 2>&1 ||
  { cat other_ranks.out; fail "impact: the resume on other ranks"; }
compare impact_whole impact_other_ranks impact 1e-9 1e-10 || fail "impact: on other ranks, beyond round-off"

echo "== SIGTERM to ./pbms run during the impact"
run="$PWD/runs/impact_signalled"
stop_during_checkpoint impact_signalled.yaml "step_000000000100:2" \
  "$run/impact/checkpoints/step_000000000100.h5.partial" signalled.out
grep -q "checkpoint impact/checkpoints/step_000000000110.h5 holds the run; to go on from there: ./pbms run impact_signalled.yaml --resume" signalled.out ||
  { cat signalled.out; fail "the stopped job does not say how to go on"; }
[ "$(yget "$run/manifest.yaml" status)" = stopped ] || fail "the manifest does not say stopped"
"$PBMS" run impact_signalled.yaml --resume > signalled_resumed.out 2>&1 ||
  { cat signalled_resumed.out; fail "the resume after SIGTERM"; }
grep -q "goes on from its checkpoint .*step_000000000110.h5" signalled_resumed.out ||
  { cat signalled_resumed.out; fail "the resume after SIGTERM did not go on from the stop's checkpoint"; }
grep -o "goes on from its checkpoint .*" signalled_resumed.out | sed 's/^/  /'
compare impact_whole impact_signalled impact 1e-9 1e-10 ||
  fail "resumed after SIGTERM, beyond round-off of the whole run"
