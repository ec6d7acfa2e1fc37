source "$(dirname "$0")/lib.sh"
# The report page of a failed run, opened in a real browser. A job of three
# stages: a DPD elastic stage that finishes, a concurrent impact whose flyer
# overlaps the target (two particles on each shared site: NaN forces, and
# the job ends at step 1; the particles are written every step), and a
# stage that never starts. `./pbms run` must end non-zero having written
# report.html and printed its path and the failure as its last lines; then
# report_browser.sh opens the page in headless Chromium: no broken image,
# no script error, every stage there, the failure's message, the body of
# the failed stage as far as it got.
"$PY" - "$(dirname "$0")/configs/concurrent_small.yaml" > failed_report.yaml <<'PYEOF'
import sys, yaml
cfg = yaml.safe_load(open(sys.argv[1]))
cfg["run"] = {"name": "failed_report", "seed": 7}
cfg["launch"] = {"dpd": 1, "mpm": 1}
impact = cfg["stages"][0]
for body in impact["bodies"]:
    if body["name"] == "flyer":
        body["region"]["hi"][0] = 5  # into the target: shared sites
impact["particles_every"] = 1
elastic = {"name": "elastic", "kind": "dpd_elastic", "material": "cu_cg", "temperature": 0}
after = {"name": "after", "kind": "dpd_elastic", "material": "cu_cg", "temperature": 0}
cfg["stages"] = [elastic, impact, after]
yaml.safe_dump(cfg, sys.stdout, sort_keys=False)
PYEOF
rc=0
timeout 300 "$PBMS" run failed_report.yaml > out.txt 2> err.txt || rc=$?
run="$PWD/runs/failed_report"
echo "./pbms run: exit code $rc; its last lines:"
tail -5 out.txt
[ "$rc" -ne 0 ] && [ "$rc" -ne 124 ] || { cat out.txt err.txt; fail "exit code $rc (0: did not fail; 124: hung)"; }
[ "$(yget "$run/manifest.yaml" status)" = failed ] || fail "the manifest does not say failed"
[ -s "$run/report.html" ] || { cat err.txt; fail "the failed run wrote no report.html"; }
grep -qx "pbms: report: $run/report.html" out.txt || fail "the last lines do not name the page"
grep -q "^pbms:   impact (concurrent, failed): .*non-finite" out.txt || fail "the last lines do not give the failure"
grep -q "^pbms:   after (dpd_elastic, pending)" out.txt || fail "the last lines do not show the stage not run"
exec bash "$(dirname "$0")/report_browser.sh" "$ROOT" "$run"
