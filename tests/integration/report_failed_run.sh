source "$(dirname "$0")/lib.sh"
# The report page of a failed run, opened in a real browser. A job of three
# stages: a DPD elastic stage that finishes, a concurrent stage (a bar at
# rest, long enough to run until killed, particles written every 50 steps)
# whose dpd_driver is killed (SIGKILL) once it has run a few hundred steps,
# and a stage that never starts. A kill, not a bad input: validation can
# never refuse it. `./pbms run` must end non-zero having written
# report.html and printed its path, the numbers, the failure and the
# pending stage as its last lines; then report_browser.sh opens the page in
# headless Chromium: no broken image, no script error, every stage there,
# the failure's message, the failed stage's body if its H5MD files are
# readable after the kill.
"$PY" - "$(dirname "$0")/configs/concurrent_small.yaml" > failed_report.yaml <<'PYEOF'
import sys, yaml
cfg = yaml.safe_load(open(sys.argv[1]))
cfg["run"] = {"name": "failed_report", "seed": 7}
cfg["launch"] = {"dpd": 1, "mpm": 1}
impact = cfg["stages"][0]
impact["steps"] = 200000
impact["particles_every"] = 50
for m in impact["motion"]:
    m["velocity"] = [0, 0, 0]  # a bar at rest: it runs until killed
elastic = {"name": "elastic", "kind": "dpd_elastic", "material": "cu_cg", "temperature": 0}
after = {"name": "after", "kind": "dpd_elastic", "material": "cu_cg", "temperature": 0}
cfg["stages"] = [elastic, impact, after]
yaml.safe_dump(cfg, sys.stdout, sort_keys=False)
PYEOF
rm -rf runs
"$PBMS" run failed_report.yaml > out.txt 2> err.txt &
pid=$!
run="$PWD/runs/failed_report"
wait_for_step "$run" impact "[1-9][0-9][0-9]" $pid 1200
victim=$(job_process dpd_driver)
[ -n "$victim" ] || { kill $pid; fail "no dpd_driver process of this job found"; }
kill -9 "$victim"
rc=0
timeout 120 tail --pid=$pid -f /dev/null || fail "the job did not end within 120 s of the kill"
wait $pid || rc=$?
echo "./pbms run: exit code $rc after the kill; its last lines:"
tail -4 out.txt
[ "$rc" -ne 0 ] || fail "the job exited 0 after its dpd_driver was killed"
[ "$(yget "$run/manifest.yaml" status)" = failed ] || fail "the manifest does not say failed"
[ -s "$run/report.html" ] || { cat err.txt; fail "the failed run wrote no report.html"; }
grep -qx "pbms: report: $run/report.html" out.txt || fail "the last lines do not name the page"
grep -q "^pbms:   elastic (dpd_elastic, ok.*): c11 " out.txt || fail "the last lines do not give the numbers"
grep -q "^pbms:   impact (concurrent, failed): .*signal 9" out.txt || fail "the last lines do not give the failure"
grep -q "^pbms:   after (dpd_elastic, pending)" out.txt || fail "the last lines do not show the stage not run"
exec bash "$(dirname "$0")/report_browser.sh" "$ROOT" "$run"
