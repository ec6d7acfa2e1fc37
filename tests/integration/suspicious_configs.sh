source "$(dirname "$0")/lib.sh"
# Legal but suspicious input is run, and said so. Two halves:
#  1. Every workflow under tests/configs/suspicious/ carries one suspicious
#     value. `./pbms validate FILE` must accept it (exit 0, no error line)
#     and warn of it: stderr holds the file's "# warn: <substring>" first
#     line, every ': warning: ' line has the form FILE:LINE:COL: warning:
#     KEY.PATH: message, and stdout counts the warnings.
#  2. A run with one warning of each kind: a concurrent stage whose MPM
#     lattice constant is 3.7 % off the material's (found by validation)
#     and a DPD pull of 10 steps (found by the driver: its fit window is far
#     shorter than the rod's sideways contraction takes). The job must
#     finish (exit 0) and show both warnings in the run's last lines, in
#     manifest.yaml and summary.yaml, and in report.html.
WARNING_LINE_RE='^[^:]+:[0-9]+:[0-9]+: warning: [^ ]+: '
failed=0
for file in "$ROOT"/tests/configs/suspicious/*.yaml; do
  name="$(basename "$file")"
  expect="$(head -n 1 "$file")"
  expect="${expect#\# warn: }"
  rc=0
  (cd "$ROOT" && ./pbms validate "tests/configs/suspicious/$name") >out.txt 2>err.txt || rc=$?
  reasons=()
  [ "$rc" -eq 0 ] || reasons+=("exit code $rc, expected 0")
  grep -qaF -- "$expect" err.txt || reasons+=("stderr lacks '$expect'")
  ! grep -qaF ': error: ' err.txt || reasons+=("an error line: $(grep -aF ': error: ' err.txt | head -n 1)")
  warnings="$(grep -aF ': warning: ' err.txt || true)"
  [ -n "$warnings" ] || reasons+=("no warning line")
  bad="$(grep -avE -- "$WARNING_LINE_RE" <<<"$warnings" || true)"
  [ -z "$bad" ] || reasons+=("malformed warning line: $(head -n 1 <<<"$bad")")
  grep -qE "ok \(.*[0-9]+ warnings? above\)" out.txt || reasons+=("stdout does not count the warnings")
  if [ "${#reasons[@]}" -eq 0 ]; then
    echo "ok $name"
  else
    echo "FAIL $name: $(printf '%s; ' "${reasons[@]}")"
    cat err.txt
    failed=$((failed + 1))
  fi
done
[ "$failed" -eq 0 ] || fail "$failed suspicious configs were not warned of as expected"

"$PY" - "$(dirname "$0")/configs/concurrent_small.yaml" > warned_run.yaml <<'PYEOF'
import sys, yaml
cfg = yaml.safe_load(open(sys.argv[1]))
cfg["run"] = {"name": "warned_run", "seed": 7}
cfg["launch"] = {"dpd": 1, "mpm": 1}
impact = cfg["stages"][0]
impact["steps"] = 30
impact["continuum"]["lattice_constant"] = 7.5
block = lambda lo, hi: {"style": "block", "lo": lo, "hi": hi}
pull = {
    "name": "pull", "kind": "dpd_run", "mode": "tension", "material": "cu_cg",
    "box": {"lo": [-20, -10, -10], "hi": [100, 40, 40]},
    "bodies": [{"name": "rod", "region": block([0, 0, 0], [72.3, 21.69, 21.69])}],
    "groups": [{"name": "left", "region": block([-1, -1, -1], [8, 23, 23])},
               {"name": "right", "region": block([64.3, -1, -1], [73.3, 23, 23])}],
    "motion": [{"group": "left", "kind": "rigid", "velocity": [-0.5, 0, 0]},
               {"group": "right", "kind": "rigid", "velocity": [0.5, 0, 0]}],
    "temperature": 298, "bath_temperature": 298, "steps": 10, "sample_every": 1,
    "tension": {"specimen": "rod", "axis": "x"},
}
cfg["stages"] = [pull, impact]
yaml.safe_dump(cfg, sys.stdout, sort_keys=False)
PYEOF
rm -rf runs
rc=0
"$PBMS" run warned_run.yaml > out.txt 2> err.txt || rc=$?
[ "$rc" -eq 0 ] || { tail -20 out.txt err.txt; fail "the warned run exited $rc"; }
run="$PWD/runs/warned_run"
echo "its last lines:"
grep '^pbms: ' out.txt | tail -6
grep -q ': warning: stages\[1\].continuum.lattice_constant: 7.5 Å is 3.7 % off' err.txt ||
  fail "validation did not warn of the lattice constant before the job"
grep -q '^pbms: warning: .*continuum.lattice_constant: 7.5 Å is 3.7 % off' out.txt ||
  fail "the last lines do not repeat the config's warning"
grep -q '^pbms: warning: pull: youngs_modulus .* comes from a pull too fast' out.txt ||
  fail "the last lines do not give the pull's warning"
"$PY" - "$run" <<'PYEOF' || fail "manifest.yaml or summary.yaml lacks a warning"
import sys, yaml
run = sys.argv[1]
manifest = yaml.safe_load(open(f"{run}/manifest.yaml"))
summary = yaml.safe_load(open(f"{run}/summary.yaml"))
config = manifest.get("config_warnings") or []
assert any("continuum.lattice_constant" in w for w in config), config
stage = next(s for s in manifest["stages"] if s["name"] == "pull")
assert any("pull too fast" in w for w in stage.get("warnings") or []), stage
pull = summary["stages"]["pull"]
assert any("pull too fast" in w for w in pull.get("warnings") or []), pull
assert pull["results"]["youngs_modulus"]["value"] > 0
print("manifest and summary hold both warnings")
PYEOF
grep -q "comes from a pull too fast" "$run/report.html" || fail "report.html lacks the pull's warning"
grep -q "is 3.7 % off the material" "$run/report.html" || fail "report.html lacks the config's warning"
echo "report.html shows both warnings"
