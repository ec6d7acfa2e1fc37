source "$(dirname "$0")/lib.sh"
# SIGKILL one md_driver rank mid-stage: the job must end within 10 s with a
# non-zero exit, a message naming md_driver, the rank and the stage, a failed
# manifest, and the finished stage's results intact.
# A previous run's manifest would satisfy the wait below before this run starts.
rm -rf runs
"$PBMS" run "$(dirname "$0")/configs/kill_target.yaml" > out.txt 2> err.txt &
pid=$!
run=runs/kill_target
wait_for_step "$run" isotherm "[1-9]" $pid
victim=$(job_process md_driver 2)
[ -n "$victim" ] || fail "no md_driver process with world rank 2 found"
start=$(date +%s.%N)
kill -9 "$victim"
rc=0
wait $pid || rc=$?
elapsed=$("$PY" -c "import time; print(round($(date +%s.%N) - $start, 2))")
cat out.txt err.txt
echo "exit code $rc after ${elapsed}s"
[ "$rc" -ne 0 ] || fail "job exited 0 after a rank was killed"
"$PY" -c "import sys; sys.exit(0 if $elapsed < 10 else 1)" || fail "job took ${elapsed}s to end"
grep -q "md_driver rank 1" err.txt || fail "message does not name md_driver rank 1"
grep -q "stage 'isotherm'" err.txt || fail "message does not name the stage"
grep -q "signal 9" err.txt || fail "message does not name the signal"
"$PY" - <<'PYEOF'
import sys, yaml, h5py
run = "runs/kill_target"
m = yaml.safe_load(open(f"{run}/manifest.yaml"))
f = m["failure"]
ok = m["status"] == "failed" and f["program"] == "md_driver" and f["rank"] == 1 and f["stage"] == "isotherm"
print("manifest:", m["status"], f)
s = yaml.safe_load(open(f"{run}/summary.yaml"))
ok &= s["stages"]["elastic"]["status"] == "ok" and s["stages"]["isotherm"]["status"] == "failed"
ok &= abs(s["stages"]["elastic"]["results"]["c11"]["value"] - 169.9) < 2
with h5py.File(f"{run}/results.h5", "r") as h:
    ok &= "elastic" in h and h["elastic/c44"][()] > 70
yaml.safe_load(open(f"{run}/config.yaml"))
sys.exit(0 if ok else 1)
PYEOF
echo "1 passed, 0 failed"
