source "$(dirname "$0")/lib.sh"
# The README's first command, as a user runs it (default ranks from the config).
"$PBMS" run "$ROOT/configs/quickstart.yaml" > out.txt 2>&1 || { cat out.txt; fail "quickstart failed"; }
run=runs/quickstart
grep -q "\[isotherm\] step .* steps/s | ETA" out.txt || fail "no progress lines"
grep -q "\[isotherm\] step .* steps/s | ETA" "$run/log.txt" || fail "no progress lines in the log"
"$PY" "$(dirname "$0")/check_isotherm.py" "$run"
