source "$(dirname "$0")/lib.sh"
export PBMS_NO_PLOTS=1  # the runs here are checked by their numbers, not their plots
# A fit killed midway (SIGKILL of the coupler) and started again with
# --resume replays the candidates it recorded, judges none of them again,
# and ends with the parameters of an uninterrupted run, bit for bit.
cfg="$ROOT/tests/integration/configs/fit_recovery_morse.yaml"
make_config() {  # make_config NAME
  sed -e "s/name: fit_recovery_morse/name: $1/" -e 's/global_evaluations: 150/global_evaluations: 120/' \
      "$cfg" > "$1.yaml"
}
make_config full
make_config cut
# The config names no file, so it runs from this directory as well.
"$PBMS" run full.yaml > full.txt 2>&1 || { cat full.txt; fail "uninterrupted run"; }

"$PBMS" run cut.yaml > cut.txt 2>&1 &
launcher=$!
journal=runs/cut/fit/evaluations.journal
for _ in $(seq 600); do
  [ -f "$journal" ] && [ "$(wc -l < "$journal")" -ge 80 ] && break
  sleep 0.1
done
[ -f "$journal" ] && [ "$(wc -l < "$journal")" -ge 80 ] || { cat cut.txt; fail "the fit never recorded 80 candidates"; }
# The coupler process itself, not mpirun (whose command line names it too).
pkill -KILL -f "^[^ ]*/coupler daemon cut.yaml" || fail "no coupler to kill"
wait "$launcher" && fail "the killed run exited 0"
recorded=$(wc -l < "$journal")
echo "killed after $recorded recorded candidates"

"$PBMS" run cut.yaml --resume > resumed.txt 2>&1 || { cat resumed.txt; fail "resumed run"; }
line=$(grep "resumed:" runs/cut/log.txt) || fail "the resumed run does not say what it replayed"
echo "$line"
"$PY" - "$recorded" "$line" <<'PYEOF'
import re, sys, yaml
recorded = int(sys.argv[1])
replayed, judged = map(int, re.search(r"(\d+) evaluations replayed .*, (\d+) judged now", sys.argv[2]).groups())
a = yaml.safe_load(open("runs/full/summary.yaml"))["stages"]["fit"]["results"]
b = yaml.safe_load(open("runs/cut/summary.yaml"))["stages"]["fit"]["results"]
bad = 0
def check(ok, text):
    global bad
    bad += not ok
    print(f"{'ok  ' if ok else 'FAIL'} {text}")
# A line being written at the kill may be lost: at most one fewer replayed.
check(recorded - 1 <= replayed <= recorded, f"{replayed} of {recorded} recorded candidates replayed")
check(replayed + judged == a["evaluations"]["value"],
      f"replayed {replayed} + judged {judged} = {a['evaluations']['value']:.0f} evaluations of the uninterrupted fit")
for k in ("d0", "alpha", "r0", "objective"):
    check(a[k]["value"] == b[k]["value"], f"{k}: {b[k]['value']!r} (resumed) == {a[k]['value']!r} (uninterrupted)")
sys.exit(1 if bad else 0)
PYEOF
echo "1 passed, 0 failed"
